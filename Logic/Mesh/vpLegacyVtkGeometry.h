#ifndef vpLegacyVtkGeometry_h
#define vpLegacyVtkGeometry_h

#include <cstddef>
#include <string>

namespace vp
{
/// Walks a legacy VTK polydata file's geometry the way VTK's reader will, and refuses what VTK
/// would index or allocate unchecked, before it sees the file: a 130-byte header claiming two
/// billion points took 23.5 GB, a cell whose point count runs past its section crashed inside
/// vtkCellArray (found by fuzz_vtk_reader).
///
/// Checked, ASCII and BINARY: the header; POINTS (its values within the file); VERTICES, LINES,
/// POLYGONS and TRIANGLE_STRIPS, classic (each cell's count within the section, the counts
/// filling it exactly) or 5.1 (OFFSETS from 0, never falling, ending at the connectivity's size);
/// METADATA blocks; every section declaring at most one value per byte of the file. Returns the
/// length of the geometry, up to the first POINT_DATA or CELL_DATA: the caller hands VTK only that
/// (the attributes are not needed and not walked). Field data before the geometry and unknown
/// sections are refused. Throws vp::InputError(fileName, "...") naming the section or line.
std::size_t CheckLegacyVtkGeometry(const std::string& bytes, const std::string& fileName);
} // namespace vp

#endif
