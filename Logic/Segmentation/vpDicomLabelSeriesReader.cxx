#include "vpDicomLabelSeriesReader.h"

#include "vpInputError.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/oflog/oflog.h>


#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace vp
{
namespace
{
bool IsVisibleDicomFile(const fs::directory_entry& entry)
{
  return entry.is_regular_file() && entry.path().filename().string()[0] != '.' &&
    DicomLabelSeriesReader::IsDicomFile(entry.path().string());
}

std::vector<fs::path> DicomFilesIn(const fs::path& folder)
{
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec))
  {
    if (IsVisibleDicomFile(entry))
    {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Stops at the first DICOM file: deciding a folder's layout needs one, not the whole listing.
bool ContainsDicomFile(const fs::path& folder)
{
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec))
  {
    if (IsVisibleDicomFile(entry))
    {
      return true;
    }
  }
  return false;
}

std::string Number(double value)
{
  std::ostringstream out;
  out << value;
  return out.str();
}

// One slice as read: its geometry and its stored values, widened to 32 bits.
struct Slice
{
  std::string File;
  std::string SeriesUid;
  std::array<double, 3> Position{};
  std::array<double, 6> Orientation{};
  std::array<double, 2> Spacing{}; // row spacing (between rows), column spacing
  unsigned Rows = 0, Columns = 0;
  double Along = 0.0; // position along the slice normal
  std::vector<std::int32_t> Values;
};

OFCondition GetPixels(DcmDataset* data, const Uint8*& pixels, unsigned long* count)
{
  return data->findAndGetUint8Array(DCM_PixelData, pixels, count);
}

OFCondition GetPixels(DcmDataset* data, const Uint16*& pixels, unsigned long* count)
{
  return data->findAndGetUint16Array(DCM_PixelData, pixels, count);
}

// Stored values, widened; signed ones (PixelRepresentation 1) keep their sign.
template <typename Stored, typename Signed>
void CopyPixels(DcmDataset* data, bool isSigned, std::vector<std::int32_t>& values, const std::string& where)
{
  const Stored* pixels = nullptr;
  unsigned long length = 0;
  if (GetPixels(data, pixels, &length).bad() || !pixels || length < values.size())
  {
    throw InputError(where, "pixel data missing or shorter than Rows x Columns");
  }
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = isSigned ? static_cast<Signed>(pixels[i]) : pixels[i];
  }
}

Slice ReadSlice(const std::string& folder, const fs::path& path)
{
  // DCMTK logs parse problems to stderr; ours is the one line that names the file.
  static const bool quiet = [] {
    OFLog::configure(OFLogger::OFF_LOG_LEVEL);
    return true;
  }();
  (void)quiet;
  Slice s;
  s.File = path.filename().string();
  const std::string where = folder + " (" + s.File + ")";
  DcmFileFormat file;
  if (file.loadFile(path.c_str()).bad())
  {
    throw InputError(where, "not a readable DICOM file");
  }
  DcmDataset* data = file.getDataset();
  const DcmXfer xfer(data->getOriginalXfer());
  if (xfer.isEncapsulated())
  {
    throw InputError(where, std::string("compressed pixel data (") + xfer.getXferName() + ", " + xfer.getXferID() +
        ") that this reader cannot decode; export the labelmap uncompressed");
  }
  OFString text;
  data->findAndGetOFString(DCM_SeriesInstanceUID, text);
  s.SeriesUid = text.c_str();
  Sint32 frames = 1;
  if (data->findAndGetSint32(DCM_NumberOfFrames, frames).good() && frames > 1)
  {
    throw InputError(where, "a multi-frame image (" + std::to_string(frames) + " frames), not a series of slices");
  }
  Uint16 rows = 0, columns = 0, bitsAllocated = 0, representation = 0, samples = 1;
  if (data->findAndGetUint16(DCM_Rows, rows).bad() || data->findAndGetUint16(DCM_Columns, columns).bad() ||
    rows == 0 || columns == 0)
  {
    throw InputError(where, "no image: Rows or Columns missing");
  }
  data->findAndGetUint16(DCM_BitsAllocated, bitsAllocated);
  data->findAndGetUint16(DCM_PixelRepresentation, representation);
  data->findAndGetUint16(DCM_SamplesPerPixel, samples);
  if (samples != 1)
  {
    throw InputError(where, "a colour image (" + std::to_string(samples) + " samples per pixel), not labels");
  }
  for (int k = 0; k < 3; ++k)
  {
    if (data->findAndGetFloat64(DCM_ImagePositionPatient, s.Position[k], k).bad())
    {
      throw InputError(where, "no ImagePositionPatient: the slice cannot be placed");
    }
  }
  for (int k = 0; k < 6; ++k)
  {
    if (data->findAndGetFloat64(DCM_ImageOrientationPatient, s.Orientation[k], k).bad())
    {
      throw InputError(where, "no ImageOrientationPatient: the slice cannot be placed");
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    if (data->findAndGetFloat64(DCM_PixelSpacing, s.Spacing[k], k).bad() || !(s.Spacing[k] > 0.0))
    {
      throw InputError(where, "no valid PixelSpacing");
    }
  }
  s.Rows = rows;
  s.Columns = columns;
  const std::size_t count = static_cast<std::size_t>(rows) * columns;
  s.Values.resize(count);
  if (bitsAllocated == 8)
  {
    CopyPixels<Uint8, std::int8_t>(data, representation != 0, s.Values, where);
  }
  else if (bitsAllocated == 16)
  {
    CopyPixels<Uint16, std::int16_t>(data, representation != 0, s.Values, where);
  }
  else
  {
    throw InputError(where, std::to_string(bitsAllocated) + "-bit pixels; labelmaps here are 8 or 16 bits");
  }
  return s;
}

double Dot(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
} // namespace

bool DicomLabelSeriesReader::IsDicomFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char head[132];
  return in.read(head, sizeof head) && std::memcmp(head + 128, "DICM", 4) == 0;
}

LabelGrid DicomLabelSeriesReader::ReadSeries(const std::string& folder)
{
  const std::vector<fs::path> files = DicomFilesIn(folder);
  if (files.empty())
  {
    throw InputError(folder, "no DICOM files in this folder");
  }
  std::vector<Slice> slices;
  slices.reserve(files.size());
  for (const auto& path : files)
  {
    slices.push_back(ReadSlice(folder, path));
    if (slices.back().SeriesUid != slices.front().SeriesUid)
    {
      throw InputError(folder, "more than one series (" + slices.front().File + " and " + slices.back().File +
          " differ in SeriesInstanceUID); give each series its own folder");
    }
  }

  // One orientation, size and pixel spacing for all; the normal orders the slices.
  const Slice& first = slices.front();
  const std::array<double, 3> row{ first.Orientation[0], first.Orientation[1], first.Orientation[2] };
  const std::array<double, 3> column{ first.Orientation[3], first.Orientation[4], first.Orientation[5] };
  const std::array<double, 3> normal{ row[1] * column[2] - row[2] * column[1], row[2] * column[0] - row[0] * column[2],
    row[0] * column[1] - row[1] * column[0] };
  if (std::abs(std::sqrt(Dot(normal, normal)) - 1.0) > 1e-3 || std::abs(Dot(row, column)) > 1e-3)
  {
    throw InputError(folder + " (" + first.File + ")", "ImageOrientationPatient is not two orthogonal unit vectors");
  }
  for (Slice& s : slices)
  {
    for (int k = 0; k < 6; ++k)
    {
      if (std::abs(s.Orientation[k] - first.Orientation[k]) > 1e-4)
      {
        throw InputError(folder, "slices with different orientations (" + first.File + " and " + s.File + ")");
      }
    }
    if (s.Rows != first.Rows || s.Columns != first.Columns)
    {
      throw InputError(folder, "slices of different sizes (" + first.File + " and " + s.File + ")");
    }
    if (std::abs(s.Spacing[0] - first.Spacing[0]) > 1e-4 * first.Spacing[0] ||
      std::abs(s.Spacing[1] - first.Spacing[1]) > 1e-4 * first.Spacing[1])
    {
      throw InputError(folder, "slices with different pixel spacings (" + first.File + " and " + s.File + ")");
    }
    s.Along = Dot(s.Position, normal);
  }
  std::stable_sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.Along < b.Along; });

  // Stacked along the normal at one spacing: no shear, no duplicate, no gap.
  std::vector<double> gaps;
  for (std::size_t i = 1; i < slices.size(); ++i)
  {
    std::array<double, 3> d{};
    for (int k = 0; k < 3; ++k)
    {
      d[k] = slices[i].Position[k] - slices[0].Position[k];
    }
    const double along = Dot(d, normal);
    const double across = std::sqrt(std::max(0.0, Dot(d, d) - along * along));
    if (across > 0.01)
    {
      throw InputError(folder, "slices are not stacked along their normal (" + slices[i].File + " is offset by " +
          Number(across) + " mm sideways): a tilted-gantry series, which this reader does not resample");
    }
    gaps.push_back(slices[i].Along - slices[i - 1].Along);
    if (gaps.back() < 1e-3)
    {
      throw InputError(folder, "two slices at the same position (" + slices[i - 1].File + " and " + slices[i].File + ")");
    }
  }
  double spacing = 1.0;
  if (!gaps.empty())
  {
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    spacing = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < gaps.size(); ++i)
    {
      if (std::abs(gaps[i] - spacing) <= std::max(0.01, 0.01 * spacing))
      {
        continue;
      }
      const double ratio = gaps[i] / spacing;
      const std::string between = " between " + slices[i].File + " and " + slices[i + 1].File + " (" +
        Number(gaps[i]) + " mm where the spacing is " + Number(spacing) + " mm)";
      if (ratio > 1.5 && std::abs(ratio - std::round(ratio)) < 0.05)
      {
        throw InputError(folder, "missing slice" + std::string(std::round(ratio) > 2.0 ? "s" : "") + between);
      }
      throw InputError(folder, "uneven slice spacing" + between);
    }
  }

  std::vector<std::int32_t> values;
  values.reserve(static_cast<std::size_t>(first.Rows) * first.Columns * slices.size());
  for (const Slice& s : slices)
  {
    values.insert(values.end(), s.Values.begin(), s.Values.end());
  }
  std::array<double, 16> m{};
  // Index (i column, j row, k slice) to LPS: i steps along the row direction by the column
  // spacing (PixelSpacing[1]), j along the column direction by the row spacing (PixelSpacing[0]).
  for (int r = 0; r < 3; ++r)
  {
    m[4 * r + 0] = row[r] * first.Spacing[1];
    m[4 * r + 1] = column[r] * first.Spacing[0];
    m[4 * r + 2] = normal[r] * spacing;
    m[4 * r + 3] = slices.front().Position[r];
  }
  m[15] = 1.0;
  const int dimensions[3] = { static_cast<int>(first.Columns), static_cast<int>(first.Rows), static_cast<int>(slices.size()) };
  return MakeLabelGrid(folder, dimensions, values, m);
}

LabelStructures DicomLabelSeriesReader::ReadFolder(const std::string& folder, const StructureFilter& wanted)
{
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
  {
    throw InputError(folder, "not a folder");
  }
  if (ContainsDicomFile(folder))
  {
    // One series of label values.
    const std::string name = fs::path(folder).lexically_normal().filename().string();
    return StructuresOf(ReadSeries(folder), folder,
      name.empty() ? fs::path(folder).lexically_normal().parent_path().filename().string() : name);
  }

  // One series per structure folder.
  std::vector<fs::path> folders;
  for (const auto& entry : fs::directory_iterator(folder, ec))
  {
    if (entry.is_directory() && ContainsDicomFile(entry.path()))
    {
      folders.push_back(entry.path());
    }
  }
  if (folders.empty())
  {
    throw InputError(folder, "no DICOM files here or in its sub-folders");
  }
  std::sort(folders.begin(), folders.end());
  LabelStructures structures;
  for (const auto& sub : folders)
  {
    LabelStructure s;
    s.Name = sub.filename().string();
    s.Source = sub.string();
    s.LabelValue = 0;
    if (!wanted || wanted(s.Name))
    {
      s.Grid = ReadSeries(sub.string());
      if (LabelValuesIn(s.Grid).empty())
      {
        throw InputError(s.Source, "the structure is empty: every voxel is 0");
      }
    }
    structures.push_back(std::move(s));
  }
  return structures;
}
} // namespace vp
