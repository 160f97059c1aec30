// Runs a fuzz target over files or folders of inputs when libFuzzer is not available (gcc builds),
// so the seed corpus and any saved crash reproducers are exercised by every test run.
#include <cstdint>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
int RunFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string s = bytes.str();
  // Truncation is the commonest corruption: each input's prefixes are inputs too.
  for (std::size_t cut : { std::size_t(0), std::size_t(1), std::size_t(80), std::size_t(84), s.size() / 2, s.size() - 1 })
  {
    if (cut < s.size())
    {
      const std::string prefix = s.substr(0, cut);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(prefix.data()), prefix.size());
    }
  }
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  return 1;
}
} // namespace

int main(int argc, char** argv)
{
  int count = 0;
  for (int i = 1; i < argc; ++i)
  {
    struct stat info;
    if (stat(argv[i], &info) != 0)
    {
      std::fprintf(stderr, "%s: no such file\n", argv[i]);
      return 1;
    }
    if (S_ISDIR(info.st_mode))
    {
      DIR* dir = opendir(argv[i]);
      while (dirent* e = readdir(dir))
      {
        const std::string name = e->d_name;
        if (name != "." && name != "..")
        {
          count += RunFile(std::string(argv[i]) + "/" + name);
        }
      }
      closedir(dir);
    }
    else
    {
      count += RunFile(argv[i]);
    }
  }
  std::printf("replayed %d inputs\n", count);
  return count > 0 ? 0 : 1;
}
