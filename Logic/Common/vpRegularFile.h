#ifndef vpRegularFile_h
#define vpRegularFile_h

#include <cstdint>
#include <string>

namespace vp
{
/// The size of fileName, which must be a regular file. Checked before anything opens it: a FIFO
/// with no writer would block the open, /dev/zero never ends. Throws InputError(fileName, ...)
/// with "no such file" (or the system's reason) when it cannot be looked at, ifFolder when it is
/// a folder, ifSpecial when it is a device, a pipe or a socket.
std::uint64_t RegularFileSize(const std::string& fileName, const std::string& ifFolder, const std::string& ifSpecial);
} // namespace vp

#endif
