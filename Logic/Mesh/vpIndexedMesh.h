#ifndef vpIndexedMesh_h
#define vpIndexedMesh_h

#include <vtkSmartPointer.h>

#include <array>
#include <cstddef>
#include <vector>

#include <vtkPolyData.h>

class vtkPoints;

namespace vp
{
/// Turns a triangle soup (9 coordinates per triangle) into an indexed vtkPolyData: vertices that
/// are bit-for-bit equal are merged (STL stores every corner three times, and topology, which the
/// inside test needs, exists only once they are shared), and degenerate triangles (a repeated
/// corner or a zero area relative to the longest edge) are dropped and counted.
template <typename Real>
vtkSmartPointer<vtkPolyData> BuildIndexedMesh(
  const Real* coordinates, std::size_t triangleCount, std::size_t* degenerateDropped);

/// A vtkPolyData of the given points (shared, not copied) and triangles (point ids), nothing else.
vtkSmartPointer<vtkPolyData> MakeTriangleMesh(vtkPoints* points, const std::vector<std::array<vtkIdType, 3>>& triangles);
} // namespace vp

#endif
