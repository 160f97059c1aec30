#ifndef vpMeshRefinement_h
#define vpMeshRefinement_h

#include <vtkSmartPointer.h>

#include <cstddef>

#include <vtkPolyData.h>

namespace vp
{
/// Grows a mesh to targetTriangles (one more where the last edge split had two triangles; never
/// fewer than it had; fewer than the target only when no edge of one or two triangles is left to
/// split): each triangle into four at its edges' midpoints while that stays within the target,
/// then edges bisected, the longest first. Every new point is shared by the
/// triangles on its edge, so the surface is unchanged point for point and so is its topology: a
/// closed mesh stays closed, a hole stays the same hole (its rim in more edges). Benchmarks use it
/// to grow real vessel meshes to a given size.
vtkSmartPointer<vtkPolyData> RefineToTriangleCount(vtkPolyData* mesh, std::size_t targetTriangles);
} // namespace vp

#endif
