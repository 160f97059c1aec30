#ifndef vpOutputFile_h
#define vpOutputFile_h

#include <string>

namespace vp
{
/// Writes bytes to fileName whole or not at all, and never replaces what is not a plain file:
/// - a regular file, or no file: a temporary file in the same folder, then one rename, so a
///   reader sees the old bytes or the new and a failed write leaves the old file as it was;
/// - a link: the same at the file it leads to (the link stays);
/// - a character device or a pipe (/dev/null, /dev/stdout, a FIFO a reader holds open): written
///   through, every byte checked (/dev/full says so), never replaced by a regular file;
/// - a folder, a block device, a socket, a link to nothing, a pipe nobody reads: refused.
/// Throws InputError naming the file and the reason.
void WriteFileAtomically(const std::string& fileName, const std::string& bytes);
} // namespace vp

#endif
