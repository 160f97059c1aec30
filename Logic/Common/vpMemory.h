#ifndef vpMemory_h
#define vpMemory_h

#include <cstdint>
#include <string>

namespace vp
{
/// The memory this process can still take, in bytes: the smaller of what the system has
/// available (MemAvailable) and what its address-space limit (ulimit -v) leaves.
std::uint64_t AvailableMemoryBytes();

/// Throws InputError(source, ...) when a structure estimated at bytes would not fit in
/// AvailableMemoryBytes(): checked before it is allocated, so that a library that prints its
/// own out-of-memory message and goes on (FCL) is never reached. what: the structure, in words.
void CheckMemoryFor(std::uint64_t bytes, const std::string& source, const std::string& what);
} // namespace vp

#endif
