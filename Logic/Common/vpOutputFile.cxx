#include "vpOutputFile.h"

#include "vpInputError.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace vp
{
namespace
{
std::string Reason()
{
  return std::strerror(errno);
}

/// Every byte to fd, retrying short writes; false with errno set on failure.
bool WriteAll(int fd, const std::string& bytes)
{
  std::size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// A character device or a pipe: written through, as `cmd > /dev/null` would.
void WriteThrough(const std::string& fileName, const std::string& bytes, bool pipe)
{
  // A pipe opened for writing waits for a reader; without one, say so instead of hanging.
  const int fd = ::open(fileName.c_str(), O_WRONLY | O_CLOEXEC | (pipe ? O_NONBLOCK : 0));
  if (fd < 0)
  {
    throw InputError(fileName, errno == ENXIO ? std::string("cannot write: no process reads this pipe")
                                              : "cannot write: " + Reason());
  }
  if (pipe)
  {
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  }
  const bool written = WriteAll(fd, bytes);
  const std::string reason = Reason();
  if (::close(fd) != 0 || !written)
  {
    throw InputError(fileName, "write failed: " + (written ? Reason() : reason));
  }
}

/// A regular file (or none yet): a temporary beside it, then one rename.
void ReplaceRegular(const std::string& fileName, const std::string& shownName, const std::string& bytes)
{
  const std::string temporary = fileName + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0)
  {
    throw InputError(shownName, "cannot write: " + Reason());
  }
  const bool written = WriteAll(fd, bytes);
  const std::string reason = Reason();
  if (::close(fd) != 0 || !written)
  {
    const std::string why = written ? Reason() : reason;
    std::remove(temporary.c_str());
    throw InputError(shownName, "write failed: " + why);
  }
  if (std::rename(temporary.c_str(), fileName.c_str()) != 0)
  {
    const std::string why = Reason();
    std::remove(temporary.c_str());
    throw InputError(shownName, "cannot write: " + why);
  }
}
} // namespace

void WriteFileAtomically(const std::string& fileName, const std::string& bytes)
{
  struct stat link;
  if (::lstat(fileName.c_str(), &link) != 0)
  {
    if (errno != ENOENT)
    {
      throw InputError(fileName, "cannot write: " + Reason());
    }
    ReplaceRegular(fileName, fileName, bytes);
    return;
  }
  struct stat info = link;
  if (S_ISLNK(link.st_mode) && ::stat(fileName.c_str(), &info) != 0)
  {
    throw InputError(fileName, "cannot write: it is a link to nothing (" + Reason() + ")");
  }
  if (S_ISDIR(info.st_mode))
  {
    throw InputError(fileName, "cannot write: it is a folder");
  }
  if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode))
  {
    WriteThrough(fileName, bytes, S_ISFIFO(info.st_mode));
    return;
  }
  if (!S_ISREG(info.st_mode))
  {
    throw InputError(fileName, "cannot write: it is a block device or a socket, not a file");
  }
  if (!S_ISLNK(link.st_mode))
  {
    ReplaceRegular(fileName, fileName, bytes);
    return;
  }
  // Through the link: the file it leads to is replaced, the link stays a link.
  char resolved[PATH_MAX];
  if (!::realpath(fileName.c_str(), resolved))
  {
    throw InputError(fileName, "cannot write: " + Reason());
  }
  ReplaceRegular(resolved, fileName, bytes);
}
} // namespace vp
