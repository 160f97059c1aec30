#ifndef vpModelTestSupport_h
#define vpModelTestSupport_h

// Shared by the segmentation, model and command tests: synthetic label grids, surface measures,
// mesh files.
#include "vpLabelStructure.h"
#include "vtkVesselMeshWriter.h"

#include <vtkCellArray.h>
#include <vtkFeatureEdges.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace vp
{
namespace test
{
/// Writes mesh as dir/name (STL, LPS) and returns the path.
inline std::string WriteMeshFile(const std::string& dir, const std::string& name, vtkPolyData* mesh)
{
  vtkNew<vtkVesselMeshWriter> writer;
  writer->SetFileName(dir + "/" + name);
  writer->SetInputData(mesh);
  writer->Write();
  return writer->GetFileName();
}

/// mesh with cell `cell` removed: a hole of one triangle, the smallest defect a surface can have.
inline vtkSmartPointer<vtkPolyData> WithoutCell(vtkPolyData* mesh, vtkIdType cell)
{
  auto holed = vtkSmartPointer<vtkPolyData>::New();
  holed->DeepCopy(mesh);
  holed->BuildCells();
  holed->DeleteCell(cell);
  holed->RemoveDeletedCells();
  return holed;
}

/// A grid of the given size whose voxel centres p (LPS) get label(p).
inline LabelGrid MakeGrid(const int dims[3], const std::array<double, 16>& ijkToLps,
  const std::function<int(const double p[3])>& label)
{
  LabelGrid grid;
  grid.IjkToLps = ijkToLps;
  grid.Labels = vtkSmartPointer<vtkImageData>::New();
  grid.Labels->SetDimensions(dims[0], dims[1], dims[2]);
  grid.Labels->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* out = static_cast<unsigned char*>(grid.Labels->GetScalarPointer());
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const auto& m = ijkToLps;
        const double p[3] = { m[0] * i + m[1] * j + m[2] * k + m[3], m[4] * i + m[5] * j + m[6] * k + m[7],
          m[8] * i + m[9] * j + m[10] * k + m[11] };
        *out++ = static_cast<unsigned char>(label(p));
      }
  return grid;
}

/// Boundary plus non-manifold edges: 0 for a closed manifold surface.
inline vtkIdType OpenEdges(vtkPolyData* surface)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(surface);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfCells();
}

/// Volume by the divergence theorem with the triangles' own winding: positive when they face out.
inline double SignedVolume(vtkPolyData* surface)
{
  double volume = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    surface->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() != 3)
      continue;
    double a[3], b[3], d[3];
    surface->GetPoint(ids->GetId(0), a);
    surface->GetPoint(ids->GetId(1), b);
    surface->GetPoint(ids->GetId(2), d);
    volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0])) / 6.0;
  }
  return volume;
}

/// Distances from every vertex of a (that keepA accepts, when given) to the surface b, and from
/// every vertex of b to a.
inline std::vector<double> SymmetricSurfaceDistances(
  vtkPolyData* a, vtkPolyData* b, const std::function<bool(const double p[3])>& keepA = nullptr)
{
  std::vector<double> all;
  for (auto [from, to] : { std::make_pair(a, b), std::make_pair(b, a) })
  {
    vtkNew<vtkStaticCellLocator> locator;
    locator->SetDataSet(to);
    locator->BuildLocator();
    for (vtkIdType i = 0; i < from->GetNumberOfPoints(); ++i)
    {
      double p[3], closest[3], d2;
      vtkIdType cell;
      int sub;
      from->GetPoint(i, p);
      if (from == a && keepA && !keepA(p))
        continue;
      locator->FindClosestPoint(p, closest, cell, sub, d2);
      all.push_back(std::sqrt(d2));
    }
  }
  return all;
}

inline double Mean(const std::vector<double>& v)
{
  double s = 0.0;
  for (double x : v)
    s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

inline double Percentile(std::vector<double> v, double q)
{
  if (v.empty())
    return 0.0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}
} // namespace test
} // namespace vp

#endif
