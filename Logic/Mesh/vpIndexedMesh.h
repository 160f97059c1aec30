#ifndef vpIndexedMesh_h
#define vpIndexedMesh_h

#include <vtkSmartPointer.h>

#include <cstddef>

#include <vtkPolyData.h>

namespace vp
{
/// Turns a triangle soup (9 coordinates per triangle) into an indexed vtkPolyData: vertices that
/// are bit-for-bit equal are merged (STL stores every corner three times, and topology, which the
/// inside test needs, exists only once they are shared), and degenerate triangles (a repeated
/// corner or a zero area relative to the longest edge) are dropped and counted.
template <typename Real>
vtkSmartPointer<vtkPolyData> BuildIndexedMesh(
  const Real* coordinates, std::size_t triangleCount, std::size_t* degenerateDropped);
} // namespace vp

#endif
