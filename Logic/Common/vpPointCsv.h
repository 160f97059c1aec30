#ifndef vpPointCsv_h
#define vpPointCsv_h

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// Parses "X,Y,Z" (three finite numbers, commas or spaces between them). Throws
/// InputError(source, problem) otherwise.
std::array<double, 3> ParsePoint(const std::string& text, const std::string& source);

/// Reads one point per line: x,y,z. A first line that is not numeric is a header; blank lines and
/// lines starting with '#' are skipped. Throws InputError naming the file and the line number for
/// anything else, and for a file with no point at all.
std::vector<std::array<double, 3>> ReadPointCsv(const std::string& fileName);
} // namespace vp

#endif
