#ifndef vpLegacyVtkCounts_h
#define vpLegacyVtkCounts_h

#include <string>

namespace vp
{
/// Refuses a legacy VTK file whose sections declare more values than its bytes can hold, before
/// VTK's reader allocates what they declare: a 130-byte header claiming two billion points took
/// 23.5 GB. Each keyword line that sizes an array (POINTS, VERTICES, LINES, POLYGONS,
/// TRIANGLE_STRIPS, POINT_DATA, CELL_DATA and the attributes after them, LOOKUP_TABLE, and field
/// arrays) must declare at most one value per byte of the file, the least any encoding takes.
/// Throws vp::InputError(fileName, "line N: ...") otherwise; lines it does not know are VTK's.
void CheckLegacyVtkCounts(const std::string& bytes, const std::string& fileName);
} // namespace vp

#endif
