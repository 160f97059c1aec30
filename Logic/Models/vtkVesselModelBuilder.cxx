#include "vtkVesselModelBuilder.h"

#include "vpInputError.h"

#include <vtkAppendPolyData.h>
#include <vtkDecimatePro.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

vtkStandardNewMacro(vtkVesselModelBuilder);

namespace
{
bool SameGrid(const vp::LabelGrid& a, const vp::LabelGrid& b)
{
  int da[3], db[3];
  a.Labels->GetDimensions(da);
  b.Labels->GetDimensions(db);
  if (!std::equal(da, da + 3, db))
  {
    return false;
  }
  for (int i = 0; i < 16; ++i)
  {
    if (std::abs(a.IjkToLps[i] - b.IjkToLps[i]) > 1e-6 * (1.0 + std::abs(a.IjkToLps[i])))
    {
      return false;
    }
  }
  return true;
}

template <typename T>
void MarkVoxels(const T* labels, vtkIdType count, int labelValue, std::vector<std::uint8_t>& mask)
{
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (labelValue == 0 ? labels[i] != 0 : labels[i] == static_cast<T>(labelValue))
    {
      mask[static_cast<std::size_t>(i)] = 1;
    }
  }
}
/// The union of the structures' voxels on their grid (dims), 1 inside; sources: their files.
std::vector<std::uint8_t> UnionOfVoxels(const std::vector<const vp::LabelStructure*>& structures, const int dims[3], std::string& sources)
{
  const vtkIdType count = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(count), 0);
  for (const vp::LabelStructure* s : structures)
  {
    vtkDataArray* scalars = s->Grid.Labels->GetPointData()->GetScalars();
    void* data = scalars->GetVoidPointer(0);
    switch (scalars->GetDataType())
    {
      case VTK_UNSIGNED_CHAR:
        MarkVoxels(static_cast<const std::uint8_t*>(data), count, s->LabelValue, inside);
        break;
      case VTK_UNSIGNED_SHORT:
        MarkVoxels(static_cast<const std::uint16_t*>(data), count, s->LabelValue, inside);
        break;
      default:
        throw vp::InputError(s->Source, "labels of an unexpected voxel type");
    }
    sources += (sources.empty() ? "" : ", ") + s->Source;
  }
  return inside;
}

/// The voxels' extent, padded by one empty voxel on every side so the surface is closed, as a
/// mask in the source grid's index space; voxels: how many are inside. Throws InputError naming
/// sources when none is.
vtkSmartPointer<vtkImageData> PaddedMask(const std::vector<std::uint8_t>& inside, const int dims[3], const std::string& sources,
  vtkIdType& voxels)
{
  int lo[3] = { dims[0], dims[1], dims[2] }, hi[3] = { -1, -1, -1 };
  voxels = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      const std::uint8_t* row = inside.data() + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
      for (int i = 0; i < dims[0]; ++i)
      {
        if (row[i])
        {
          ++voxels;
          lo[0] = std::min(lo[0], i), hi[0] = std::max(hi[0], i);
          lo[1] = std::min(lo[1], j), hi[1] = std::max(hi[1], j);
          lo[2] = std::min(lo[2], k), hi[2] = std::max(hi[2], k);
        }
      }
    }
  }
  if (voxels == 0)
  {
    throw vp::InputError(sources, "the structure is empty: no voxel carries its label");
  }
  auto mask = vtkSmartPointer<vtkImageData>::New();
  mask->SetDimensions(hi[0] - lo[0] + 3, hi[1] - lo[1] + 3, hi[2] - lo[2] + 3);
  mask->SetOrigin(lo[0] - 1, lo[1] - 1, lo[2] - 1); // index space of the source grid
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* out = static_cast<std::uint8_t*>(mask->GetScalarPointer());
  std::fill(out, out + mask->GetNumberOfPoints(), 0);
  int md[3];
  mask->GetDimensions(md);
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      const std::uint8_t* row = inside.data() + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
      std::uint8_t* target =
        out + (static_cast<std::size_t>(k - lo[2] + 1) * md[1] + (j - lo[1] + 1)) * md[0] + 1;
      std::copy(row + lo[0], row + hi[0] + 1, target);
    }
  }
  return mask;
}

/// The surface from index space into the patient's (LPS mm), its normals and winding outward.
vtkSmartPointer<vtkPolyData> PlaceInPatient(vtkPolyData* surface, const vp::LabelGrid& grid)
{
  vtkNew<vtkMatrix4x4> matrix;
  matrix->DeepCopy(grid.IjkToLps.data());
  vtkNew<vtkTransform> ijkToLps;
  ijkToLps->SetMatrix(matrix);
  vtkNew<vtkTransformPolyDataFilter> place;
  place->SetInputData(surface);
  place->SetTransform(ijkToLps);

  // A reflecting index-to-LPS matrix turns the winding inside out; auto-orientation puts every
  // closed piece's normals (and triangle order) outward again.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(place->GetOutputPort());
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOn();
  normals->SplittingOff();
  normals->ComputeCellNormalsOff();
  normals->Update();
  vtkSmartPointer<vtkPolyData> result = normals->GetOutput();
  return result;
}
} // namespace

void vtkVesselModelBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SmoothingFactor: " << this->SmoothingFactor << "\n";
  os << indent << "SmoothingIterations: " << this->SmoothingIterations << "\n";
  os << indent << "DecimationFactor: " << this->DecimationFactor << "\n";
  os << indent << "NumberOfVoxels: " << this->NumberOfVoxels << "\n";
}

vtkSmartPointer<vtkPolyData> vtkVesselModelBuilder::Build(const std::vector<const vp::LabelStructure*>& structures)
{
  this->NumberOfVoxels = 0;
  this->VoxelVolumeMm3 = 0.0;
  std::vector<std::vector<const vp::LabelStructure*>> groups;
  for (const vp::LabelStructure* s : structures)
  {
    if (!s || !s->Grid.Labels)
    {
      continue;
    }
    auto group = std::find_if(groups.begin(), groups.end(),
      [&](const auto& g) { return SameGrid(g.front()->Grid, s->Grid); });
    if (group == groups.end())
    {
      groups.push_back({ s });
    }
    else
    {
      group->push_back(s);
    }
  }
  if (groups.size() == 1)
  {
    return this->BuildOnGrid(groups.front());
  }
  vtkNew<vtkAppendPolyData> append;
  for (const auto& group : groups)
  {
    append->AddInputData(this->BuildOnGrid(group));
  }
  append->Update();
  vtkSmartPointer<vtkPolyData> out = append->GetOutput();
  return out;
}

vtkSmartPointer<vtkPolyData> vtkVesselModelBuilder::BuildOnGrid(const std::vector<const vp::LabelStructure*>& structures)
{
  const vp::LabelGrid& grid = structures.front()->Grid;
  int dims[3];
  grid.Labels->GetDimensions(dims);
  std::string sources;
  const std::vector<std::uint8_t> inside = UnionOfVoxels(structures, dims, sources);
  vtkIdType voxels = 0;
  vtkSmartPointer<vtkImageData> mask = PaddedMask(inside, dims, sources, voxels);
  this->NumberOfVoxels += voxels;
  this->VoxelVolumeMm3 += static_cast<double>(voxels) * grid.VoxelVolumeMm3();

  vtkNew<vtkDiscreteFlyingEdges3D> contour;
  contour->SetInputData(mask);
  contour->SetValue(0, 1.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  return PlaceInPatient(this->DecimateAndSmooth(contour->GetOutput()), grid);
}

vtkSmartPointer<vtkPolyData> vtkVesselModelBuilder::DecimateAndSmooth(vtkPolyData* contour) const
{
  vtkSmartPointer<vtkPolyData> surface = contour;
  if (this->DecimationFactor > 0.0)
  {
    // Slicer's settings: keep the topology, never split, never delete boundary vertices.
    vtkNew<vtkDecimatePro> decimate;
    decimate->SetInputData(surface);
    decimate->SetTargetReduction(this->DecimationFactor);
    decimate->PreserveTopologyOn();
    decimate->SetMaximumError(1);
    decimate->SplittingOff();
    decimate->BoundaryVertexDeletionOff();
    decimate->Update();
    surface = decimate->GetOutput();
  }

  if (this->SmoothingFactor > 0.0)
  {
    // On the voxel grid (index space), so the pass band means the same at any voxel spacing.
    vtkNew<vtkWindowedSincPolyDataFilter> smooth;
    smooth->SetInputData(surface);
    smooth->SetNumberOfIterations(this->SmoothingIterations);
    smooth->SetPassBand(std::pow(10.0, -4.0 * this->SmoothingFactor));
    smooth->BoundarySmoothingOff();
    smooth->FeatureEdgeSmoothingOff();
    smooth->NonManifoldSmoothingOn();
    smooth->NormalizeCoordinatesOn();
    smooth->Update();
    surface = smooth->GetOutput();
  }

  return surface;
}
