#ifndef vpMeshRefinement_h
#define vpMeshRefinement_h

#include <vtkSmartPointer.h>

#include <cstddef>

#include <vtkPolyData.h>

namespace vp
{
/// Splits triangles in two across their longest edge, largest first, until the mesh has exactly
/// targetTriangles (never fewer than it had). The surface is unchanged point for point, so
/// every distance to it is too: benchmarks use it to grow real vessel meshes to a given size.
/// New midpoints are not shared with the neighbour across the edge, so the result is not
/// watertight (its inside test answers "unknown").
vtkSmartPointer<vtkPolyData> RefineToTriangleCount(vtkPolyData* mesh, std::size_t targetTriangles);
} // namespace vp

#endif
