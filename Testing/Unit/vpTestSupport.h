#ifndef vpTestSupport_h
#define vpTestSupport_h

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>
#include <vector>
#include <string>
#include <sys/stat.h>
#include <sys/socket.h>
#include <netinet/in.h>
#include <signal.h>
#include <chrono>
#include <thread>

// VP_UNDER_ASAN: AddressSanitizer's shadow and quarantine make a process's memory say nothing of
// the program's own, so memory bounds are not compared under it.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VP_UNDER_ASAN 1
#endif
#endif

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

/// v to 17 significant digits: read back, the same double.
inline std::string Number(double v)
{
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
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

/// bytes written to dir/name as they are; the path.
inline std::string WriteBytes(const std::string& dir, const std::string& name, const std::string& bytes)
{
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
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

/// Records names (files, and folders as "name/") in folder as the entries of a run of ours, as
/// vp::RunFolder's marker does: for a test that lays out an earlier run by hand.
/// A port free now on loopback (the kernel's choice), for a peer that must be told one: TCP, or
/// UDP with SOCK_DGRAM.
inline int FreePort(int type = SOCK_STREAM)
{
  const int s = socket(AF_INET, type, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  bind(s, reinterpret_cast<sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  getsockname(s, reinterpret_cast<sockaddr*>(&address), &length);
  close(s);
  return ntohs(address.sin_port);
}

/// Waits until a file a child writes holds text at least times times (seconds at most).
inline bool WaitForText(const std::string& file, const std::string& text, double seconds = 10.0, int times = 1)
{
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(1000 * seconds));
  while (std::chrono::steady_clock::now() < until)
  {
    const std::string content = Slurp(file);
    int found = 0;
    for (std::size_t at = content.find(text); at != std::string::npos; at = content.find(text, at + 1))
    {
      ++found;
    }
    if (found >= times)
    {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

/// Waits for a child to end (seconds at most, then kills it): its exit code, -signal when a
/// signal ended it, -999 when it had to be killed.
inline int WaitFor(pid_t child, double seconds)
{
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(1000 * seconds));
  int status = 0;
  while (std::chrono::steady_clock::now() < until)
  {
    if (waitpid(child, &status, WNOHANG) == child)
    {
      return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(child, SIGKILL);
  waitpid(child, &status, 0);
  return -999;
}

/// The cells of one CSV line (no quoting: our tables have none), a trailing empty cell kept.
inline std::vector<std::string> SplitCsvLine(const std::string& line)
{
  std::vector<std::string> cells(1);
  for (char c : line)
  {
    if (c == ',')
    {
      cells.emplace_back();
    }
    else
    {
      cells.back() += c;
    }
  }
  return cells;
}

inline void RecordAsRun(const std::string& folder, const std::vector<std::string>& names)
{
  std::string json = "{\"entries\": [";
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    const bool isFolder = !names[i].empty() && names[i].back() == '/';
    const std::string path = folder + "/" + (isFolder ? names[i].substr(0, names[i].size() - 1) : names[i]);
    struct stat info;
    if (::lstat(path.c_str(), &info) != 0)
    {
      continue;
    }
    const long long modified = isFolder ? 0 : static_cast<long long>(info.st_mtim.tv_sec) * 1000000000LL + info.st_mtim.tv_nsec;
    json += std::string(i ? ", " : "") + "{\"name\": \"" + names[i] + "\", \"device\": " + std::to_string(info.st_dev) +
      ", \"inode\": " + std::to_string(info.st_ino) + ", \"size\": " + std::to_string(isFolder ? 0 : info.st_size) +
      ", \"modified_ns\": " + std::to_string(modified) + "}";
  }
  std::ofstream(folder + "/.vesselproximity-run.json") << json << "]}\n";
}

/// Starts program with arguments, its stdout and stderr going to the given files, and returns
/// its process id at once; -1 when it cannot be started.
inline pid_t StartProgram(const std::string& program, const std::vector<std::string>& arguments,
  const std::string& outFile = "/dev/null", const std::string& errFile = "/dev/null")
{
  std::vector<std::string> argv{ program };
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::vector<char*> pointers;
  for (std::string& a : argv)
  {
    pointers.push_back(&a[0]);
  }
  pointers.push_back(nullptr);
  const pid_t child = fork();
  if (child == 0)
  {
    dup2(open(outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600), 1);
    dup2(open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600), 2);
    execv(program.c_str(), pointers.data());
    _exit(127);
  }
  return child;
}

#ifdef VP_EXECUTABLE
/// Starts the vesselproximity executable with arguments, its output silenced, and returns its
/// process id at once (for tests that interrupt it); -1 when it cannot be started.
inline pid_t StartTool(const std::vector<std::string>& arguments)
{
  return StartProgram(VP_EXECUTABLE, arguments);
}

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
