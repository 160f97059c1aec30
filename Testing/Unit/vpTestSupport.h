#ifndef vpTestSupport_h
#define vpTestSupport_h

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <string>
#include <sys/stat.h>

namespace vp
{
namespace test
{
/// Folder of the shared real test data (VP_TEST_DATA), empty when not set or missing.
inline std::string TestDataDir()
{
  const char* dir = std::getenv("VP_TEST_DATA");
#ifdef VP_DEFAULT_TEST_DATA
  if (!dir)
  {
    dir = VP_DEFAULT_TEST_DATA; // what VP_TEST_DATA was when the build was configured
  }
#endif
  struct stat info;
  if (!dir || !*dir || stat(dir, &info) != 0 || !S_ISDIR(info.st_mode))
  {
    return std::string();
  }
  return dir;
}

/// Where the build extracted archives from VP_TEST_DATA (IRCADb meshes), empty when absent.
inline std::string ExtractedDataDir()
{
  const char* dir = std::getenv("VP_EXTRACTED_DATA");
#ifdef VP_DEFAULT_EXTRACTED_DATA
  if (!dir)
  {
    dir = VP_DEFAULT_EXTRACTED_DATA;
  }
#endif
  struct stat info;
  if (!dir || !*dir || stat(dir, &info) != 0 || !S_ISDIR(info.st_mode))
  {
    return std::string();
  }
  return dir;
}

inline bool FileExists(const std::string& path)
{
  struct stat info;
  return stat(path.c_str(), &info) == 0;
}

/// A fresh empty folder under the build's temporary area.
inline std::string MakeTempDir(const std::string& name)
{
  const char* base = std::getenv("VP_TEST_TMP");
#ifdef VP_DEFAULT_TEST_TMP
  if (!base)
  {
    base = VP_DEFAULT_TEST_TMP;
  }
#endif
  std::string dir = std::string(base && *base ? base : "/tmp") + "/vp_" + name + "_XXXXXX";
  if (!mkdtemp(&dir[0]))
  {
    std::abort();
  }
  return dir;
}

struct ToolRun
{
  int ExitCode;
  std::string Out;
  std::string Err;
};

inline std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

#ifdef VP_EXECUTABLE
/// Runs the tool with arguments; environment ("NAME=value ...") is set for it alone.
inline ToolRun RunTool(const std::string& dir, const std::string& arguments, const std::string& environment = std::string())
{
  const std::string out = dir + "/stdout.txt", err = dir + "/stderr.txt";
  const std::string command =
    environment + " " + std::string(VP_EXECUTABLE) + " " + arguments + " >" + out + " 2>" + err;
  const int status = std::system(command.c_str());
  return { WIFEXITED(status) ? WEXITSTATUS(status) : -1, Slurp(out), Slurp(err) };
}
#endif
} // namespace test
} // namespace vp

#endif
