#include "vpRegularFile.h"

#include "vpInputError.h"

#include <cerrno>
#include <cstring>
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
} // namespace vp
