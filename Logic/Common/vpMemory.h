#ifndef vpMemory_h
#define vpMemory_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vp
{
/// The memory this process can still take, in bytes: the smaller of what the system has
/// available (MemAvailable) and what its address-space limit (ulimit -v) leaves.
std::uint64_t AvailableMemoryBytes();

/// Throws InputError(source, ...) when a structure estimated at bytes would not fit in
/// AvailableMemoryBytes(): checked before it is allocated, so that a library that prints its
/// own out-of-memory message and goes on (FCL) is never reached. what: the structure, in words.
void CheckMemoryFor(std::uint64_t bytes, const std::string& source, const std::string& what);

/// Asks the kernel to back the 2 MB pages wholly inside [data, data + bytes) with huge pages when
/// they are first touched (Linux's transparent huge pages in "madvise" mode; elsewhere nothing).
/// For tables read at random places by batches of points: with 4 KB pages nearly every lookup
/// into some 15 MB also misses the TLB, which under a hypervisor costs a two-level page walk.
void AdviseHugePages(const void* data, std::size_t bytes);

/// values.assign(count, value), on huge pages where the system gives them (AdviseHugePages).
template <typename T>
void AssignOnHugePages(std::vector<T>& values, std::size_t count, const T& value)
{
  values.clear();
  values.shrink_to_fit(); // a fresh allocation, untouched until assign()
  values.reserve(count);
  AdviseHugePages(values.data(), count * sizeof(T));
  values.assign(count, value);
}
} // namespace vp

#endif
