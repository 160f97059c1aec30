#include "vpVirtualDisplay.h"

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace vp
{
bool VirtualDisplay::Ensure()
{
  const char* current = std::getenv("DISPLAY");
  if (current && *current)
  {
    this->Display = current;
    return true;
  }
  if (this->Pid > 0)
  {
    return true;
  }
  int fds[2];
  if (pipe(fds) != 0)
  {
    this->Problem = "cannot create a pipe to start Xvfb";
    return false;
  }
  const pid_t pid = fork();
  if (pid < 0)
  {
    close(fds[0]);
    close(fds[1]);
    this->Problem = "cannot fork to start Xvfb";
    return false;
  }
  if (pid == 0)
  {
    close(fds[0]);
    // Xvfb writes the display number it chose to this descriptor once it accepts clients.
    const std::string fd = std::to_string(fds[1]);
    const int devnull = open("/dev/null", O_WRONLY);
    if (devnull >= 0)
    {
      dup2(devnull, STDOUT_FILENO);
      dup2(devnull, STDERR_FILENO);
    }
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1200x24", "-nolisten", "tcp", "-noreset",
      static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string number;
  pollfd wait{ fds[0], POLLIN, 0 };
  // Xvfb starts in well under a second; ten seconds covers a loaded machine.
  while (poll(&wait, 1, 10000) > 0)
  {
    char c;
    const ssize_t n = read(fds[0], &c, 1);
    if (n <= 0 || c == '\n')
    {
      break;
    }
    number += c;
  }
  close(fds[0]);
  if (number.empty())
  {
    int status = 0;
    kill(pid, SIGTERM);
    waitpid(pid, &status, 0);
    this->Problem = WIFEXITED(status) && WEXITSTATUS(status) == 127
      ? "no display (DISPLAY is unset) and Xvfb is not installed (Debian package xvfb)"
      : "no display (DISPLAY is unset) and Xvfb did not start";
    return false;
  }
  this->Pid = pid;
  this->Display = ":" + number;
  setenv("DISPLAY", this->Display.c_str(), 1);
  return true;
}

VirtualDisplay::~VirtualDisplay()
{
  if (this->Pid > 0)
  {
    kill(this->Pid, SIGTERM);
    int status = 0;
    waitpid(this->Pid, &status, 0);
    unsetenv("DISPLAY");
  }
}
} // namespace vp
