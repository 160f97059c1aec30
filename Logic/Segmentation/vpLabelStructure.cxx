#include "vpLabelStructure.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
/// The determinant of the 3x3 part of a row-major 4x4 matrix: a voxel's signed volume.
double Determinant3(const std::array<double, 16>& m)
{
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
}
} // namespace

double LabelGrid::SpacingMm(int k) const
{
  const auto& m = this->IjkToLps;
  return std::sqrt(m[k] * m[k] + m[4 + k] * m[4 + k] + m[8 + k] * m[8 + k]);
}

double LabelGrid::VoxelVolumeMm3() const
{
  // |det| of the 3x3 part: also right for sheared (gantry-tilted) grids.
  return std::abs(Determinant3(this->IjkToLps));
}

void CheckVoxelGeometry(const std::array<double, 16>& m, const std::string& source)
{
  const char* axisName[3] = { "column (i)", "row (j)", "slice (k)" };
  double length[3];
  for (int c = 0; c < 3; ++c)
  {
    length[c] = std::hypot(std::hypot(m[c], m[4 + c]), m[8 + c]); // 1e-300 squared is 0
    if (!std::isfinite(m[c]) || !std::isfinite(m[4 + c]) || !std::isfinite(m[8 + c]))
    {
      throw InputError(source, std::string("the voxel's ") + axisName[c] + " direction holds a NaN or infinite value");
    }
    if (!(length[c] >= limits::MinVoxelMm && length[c] <= limits::MaxVoxelMm))
    {
      throw InputError(source, std::string("a voxel ") + NumberText(length[c]) + " mm long along its " + axisName[c] +
          " axis: a voxel is " + NumberText(limits::MinVoxelMm) + " to " + NumberText(limits::MaxVoxelMm) + " mm");
    }
  }
  if (!(std::fabs(Determinant3(m)) >= 1e-3 * length[0] * length[1] * length[2]))
  {
    throw InputError(source, "the voxel's three axes lie in one plane (its directions are degenerate)");
  }
  const double origin[3] = { m[3], m[7], m[11] };
  CheckCoordinates(origin, source, "the image's origin");
}

LabelCensus::LabelCensus()
  : Present(65536 / 64, 0)
{
}

template <typename T>
void LabelCensus::AddValues(const T* values, std::size_t count)
{
  T lo = 0, hi = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    lo = std::min(lo, values[i]);
    hi = std::max(hi, values[i]);
  }
  this->Lo = std::min<std::int32_t>(this->Lo, lo);
  this->Hi = std::max<std::int32_t>(this->Hi, hi);
  if (lo < 0 || static_cast<std::int64_t>(hi) > 65535)
  {
    return; // not labels: CheckLabels says so, whichever values occur
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    const auto v = static_cast<std::uint32_t>(values[i]);
    this->Present[v >> 6] |= std::uint64_t(1) << (v & 63);
  }
}

void LabelCensus::Add(const std::int32_t* values, std::size_t count) { this->AddValues(values, count); }
void LabelCensus::Add(const std::uint16_t* values, std::size_t count) { this->AddValues(values, count); }
void LabelCensus::Add(const std::int16_t* values, std::size_t count) { this->AddValues(values, count); }
void LabelCensus::Add(const std::uint8_t* values, std::size_t count) { this->AddValues(values, count); }
void LabelCensus::Add(const std::int8_t* values, std::size_t count) { this->AddValues(values, count); }

void LabelCensus::Merge(const LabelCensus& other)
{
  this->Lo = std::min(this->Lo, other.Lo);
  this->Hi = std::max(this->Hi, other.Hi);
  for (std::size_t w = 0; w < this->Present.size(); ++w)
  {
    this->Present[w] |= other.Present[w];
  }
}

void LabelCensus::CheckLabels(const std::string& source) const
{
  if (this->Lo < 0)
  {
    throw InputError(source, "an image, not a labelmap: negative voxel values (down to " + std::to_string(this->Lo) +
        "), as in CT; give the segmentation, not the scan");
  }
  if (this->Hi > 65535)
  {
    throw InputError(source, "label values up to " + std::to_string(this->Hi) + "; labels here fit in 16 bits");
  }
  std::size_t distinct = 0;
  for (std::uint64_t word : this->Present)
  {
    distinct += static_cast<std::size_t>(__builtin_popcountll(word));
  }
  if (distinct > 256)
  {
    throw InputError(source, "an image, not a labelmap: " + std::to_string(distinct) +
        " distinct voxel values, as in CT or MR; give the segmentation, not the scan");
  }
}

LabelGrid NewLabelGrid(const int dimensions[3], const std::array<double, 16>& ijkToLps, std::int32_t highestValue)
{
  LabelGrid grid;
  grid.IjkToLps = ijkToLps;
  grid.Labels = vtkSmartPointer<vtkImageData>::New();
  grid.Labels->SetDimensions(dimensions[0], dimensions[1], dimensions[2]);
  grid.Labels->AllocateScalars(highestValue <= 255 ? VTK_UNSIGNED_CHAR : VTK_UNSIGNED_SHORT, 1);
  return grid;
}

LabelGrid MakeLabelGrid(const std::string& source, const int dimensions[3], const std::vector<std::int32_t>& values,
  const std::array<double, 16>& ijkToLps)
{
  LabelCensus census;
  census.Add(values.data(), values.size());
  census.CheckLabels(source);
  LabelGrid grid = NewLabelGrid(dimensions, ijkToLps, census.Highest());
  if (census.Highest() <= 255)
  {
    std::transform(values.begin(), values.end(), static_cast<std::uint8_t*>(grid.Labels->GetScalarPointer()),
      [](std::int32_t v) { return static_cast<std::uint8_t>(v); });
  }
  else
  {
    std::transform(values.begin(), values.end(), static_cast<std::uint16_t*>(grid.Labels->GetScalarPointer()),
      [](std::int32_t v) { return static_cast<std::uint16_t>(v); });
  }
  return grid;
}

std::vector<int> LabelValuesIn(const LabelGrid& grid)
{
  // A byte per value, not vector<bool>: a bit's read-modify-write made this scan of 67M voxels
  // (a 258-slice series) slower than reading the series.
  std::vector<std::uint8_t> present(65536, 0);
  vtkDataArray* scalars = grid.Labels->GetPointData()->GetScalars();
  const auto n = static_cast<std::size_t>(scalars->GetNumberOfTuples());
  if (scalars->GetDataType() == VTK_UNSIGNED_CHAR)
  {
    const auto* v = static_cast<const std::uint8_t*>(scalars->GetVoidPointer(0));
    for (std::size_t i = 0; i < n; ++i)
    {
      present[v[i]] = 1;
    }
  }
  else if (scalars->GetDataType() == VTK_UNSIGNED_SHORT)
  {
    const auto* v = static_cast<const std::uint16_t*>(scalars->GetVoidPointer(0));
    for (std::size_t i = 0; i < n; ++i)
    {
      present[v[i]] = 1;
    }
  }
  else
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      present[static_cast<std::size_t>(scalars->GetTuple1(static_cast<vtkIdType>(i)))] = 1;
    }
  }
  std::vector<int> values;
  for (int v = 1; v < 65536; ++v)
  {
    if (present[static_cast<std::size_t>(v)])
    {
      values.push_back(v);
    }
  }
  return values;
}

LabelStructures StructuresOf(const LabelGrid& grid, const std::string& source, const std::string& singleName)
{
  const std::vector<int> values = LabelValuesIn(grid);
  if (values.empty())
  {
    throw InputError(source, "the labelmap is empty: every voxel is 0");
  }
  LabelStructures structures;
  for (int v : values)
  {
    LabelStructure s;
    s.Name = values.size() == 1 ? singleName : "label " + std::to_string(v);
    s.OnlyValue = values.size() == 1;
    s.Source = source;
    s.LabelValue = v;
    s.Grid = grid;
    structures.push_back(std::move(s));
  }
  return structures;
}

std::string ImageIdentity::Describe() const
{
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (!this->PatientName.empty() || !this->PatientId.empty())
  {
    add("patient '" + Printable(this->PatientName.empty() ? this->PatientId : this->PatientName) + "'" +
      (!this->PatientName.empty() && !this->PatientId.empty() ? " (ID " + Printable(this->PatientId) + ")" : ""));
  }
  if (!this->StudyUid.empty())
  {
    add("study " + Printable(this->StudyUid));
  }
  if (!this->FrameOfReferenceUid.empty())
  {
    add("frame of reference " + Printable(this->FrameOfReferenceUid));
  }
  return text.empty() ? "no patient or frame of reference recorded" : text;
}

std::string ImageIdentity::DiffersIn(const ImageIdentity& other) const
{
  auto differ = [](const std::string& a, const std::string& b) { return !a.empty() && !b.empty() && a != b; };
  // A person name's family name (before its first '^'): IRCADb names each structure's series
  // "liver_01^artery", "liver_01^liver", ..., one patient under several names, and gives each its
  // own study, so the study alone says nothing of the patient.
  auto family = [](const std::string& name) { return name.substr(0, name.find('^')); };
  if (differ(this->PatientId, other.PatientId) || differ(family(this->PatientName), family(other.PatientName)))
  {
    return "patient";
  }
  if (differ(this->FrameOfReferenceUid, other.FrameOfReferenceUid))
  {
    return "frame of reference";
  }
  return std::string();
}
} // namespace vp
