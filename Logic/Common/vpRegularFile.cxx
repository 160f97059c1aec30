#include "vpRegularFile.h"

#include "vpInputError.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace vp
{
std::uint64_t RegularFileSize(const std::string& fileName, const std::string& ifFolder, const std::string& ifSpecial)
{
  struct stat info;
  if (stat(fileName.c_str(), &info) != 0)
  {
    throw InputError(fileName, errno == ENOENT ? "no such file" : std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode))
  {
    throw InputError(fileName, ifFolder);
  }
  if (!S_ISREG(info.st_mode))
  {
    throw InputError(fileName, ifSpecial);
  }
  return static_cast<std::uint64_t>(info.st_size);
}
std::string ReadSmallFile(const std::string& fileName, const std::string& what, std::uint64_t maxBytes)
{
  const std::uint64_t size = RegularFileSize(fileName, "is a folder, not a " + what,
    "is not a regular file (a device, pipe or socket), not a " + what);
  if (size > maxBytes)
  {
    throw InputError(fileName, "is " + std::to_string(size) + " bytes: not a " + what + " (at most " +
        std::to_string(maxBytes >> 20) + " MB)");
  }
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    throw InputError(fileName, "cannot be opened");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string FileItWouldReplace(const std::string& fileName, const std::vector<std::string>& files)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(fs::absolute(fileName, ec), ec);
  for (const std::string& file : files)
  {
    if (file.empty())
    {
      continue;
    }
    std::error_code fileEc;
    const fs::path other = fs::weakly_canonical(fs::absolute(file, fileEc), fileEc);
    std::error_code sameEc;
    if ((!ec && !fileEc && target == other) || fs::equivalent(fileName, file, sameEc))
    {
      return file;
    }
  }
  return std::string();
}
} // namespace vp
