#ifndef vpRegularFile_h
#define vpRegularFile_h

#include <cstdint>
#include <string>
#include <vector>

namespace vp
{
/// The size of fileName, which must be a regular file. Checked before anything opens it: a FIFO
/// with no writer would block the open, /dev/zero never ends. Throws InputError(fileName, ...)
/// with "no such file" (or the system's reason) when it cannot be looked at, ifFolder when it is
/// a folder, ifSpecial when it is a device, a pipe or a socket.
std::uint64_t RegularFileSize(const std::string& fileName, const std::string& ifFolder, const std::string& ifSpecial);

/// The whole of a small file that names what it is (a colour table, a point list): a regular
/// file (RegularFileSize, its messages "is a folder, not a WHAT" and "is not a regular file (a
/// device, pipe or socket), not a WHAT") of at most maxBytes ("is N bytes: not a WHAT (at most
/// M MB)"). Throws InputError(fileName, ...).
std::string ReadSmallFile(const std::string& fileName, const std::string& what, std::uint64_t maxBytes);

/// The one of files that writing fileName would replace (the same path once links and ".." are
/// resolved, or the same file by another name: a hard link); empty when none. An output is
/// checked against its run's inputs with it before anything is written.
std::string FileItWouldReplace(const std::string& fileName, const std::vector<std::string>& files);
} // namespace vp

#endif
