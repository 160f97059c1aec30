#include "vpMemory.h"

#include "vpInputError.h"

#include <fstream>
#include <limits>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

namespace vp
{
std::uint64_t AvailableMemoryBytes()
{
  std::uint64_t available = std::numeric_limits<std::uint64_t>::max();
  std::ifstream meminfo("/proc/meminfo");
  for (std::string key; meminfo >> key;)
  {
    std::uint64_t kb = 0;
    meminfo >> kb;
    if (key == "MemAvailable:")
    {
      available = kb * 1024u;
      break;
    }
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  struct rlimit limit;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
  {
    std::uint64_t pages = 0;
    std::ifstream("/proc/self/statm") >> pages; // the address space taken now
    const std::uint64_t used = pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
    const std::uint64_t left = limit.rlim_cur > used ? limit.rlim_cur - used : 0;
    available = std::min(available, left);
  }
  return available;
}

void CheckMemoryFor(std::uint64_t bytes, const std::string& source, const std::string& what)
{
  const std::uint64_t available = AvailableMemoryBytes();
  if (bytes > available)
  {
    throw InputError(source, what + " needs about " + NumberText(static_cast<double>(bytes) / 1e9, 3) + " GB, more than the " +
        NumberText(static_cast<double>(available) / 1e9, 3) + " GB this process has left");
  }
}

void AdviseHugePages(const void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t Huge = std::uintptr_t(2) << 20;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + Huge - 1) & ~(Huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(Huge - 1);
  if (data && end > begin)
  {
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE); // advice only: a refusal changes nothing
  }
#else
  (void)data;
  (void)bytes;
#endif
}
} // namespace vp
