#include "vpDicomLabelSeriesReader.h"

#include "vpDcmtkFile.h"
#include "vpDicomSegReader.h"
#include "vpInputError.h"
#include "vpSliceStack.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>

#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

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

// One slice as read: its geometry and its stored values, widened to 32 bits.
/// The largest slice side taken (pixels): CT and MR slices are 512 or 1024 wide, micro-CT a few
/// thousand.
constexpr unsigned MaxSliceSide = 8192;
/// The most voxels a series may hold, as the other readers (about 268 million).
constexpr double MaxSeriesVoxels = double(std::size_t(1) << 28);

struct Slice
{
  std::string File;
  std::string SeriesUid;
  ImageIdentity Identity;
  std::array<double, 3> Position{};
  std::array<double, 6> Orientation{};
  std::array<double, 2> Spacing{}; // row spacing (between rows), column spacing
  unsigned Rows = 0, Columns = 0;
  /// The stored values as stored (8 or 16 bits each), and which values they are: kept narrow, as
  /// widening every slice to 32 bits and checking the series after made reading a 258-slice
  /// series take twice as long as DCMTK's parsing of it.
  std::vector<std::uint8_t> Stored;
  unsigned BytesPerValue = 1;
  LabelCensus Census;
};

OFCondition GetPixels(DcmDataset* data, const Uint8*& pixels, unsigned long* count)
{
  return data->findAndGetUint8Array(DCM_PixelData, pixels, count);
}

OFCondition GetPixels(DcmDataset* data, const Uint16*& pixels, unsigned long* count)
{
  return data->findAndGetUint16Array(DCM_PixelData, pixels, count);
}

// The stored values as they are, and their census; signed ones (PixelRepresentation 1) counted
// with their sign.
template <typename Stored, typename Signed>
void CopyPixels(DcmDataset* data, bool isSigned, std::size_t count, Slice& slice, const std::string& where)
{
  const Stored* pixels = nullptr;
  unsigned long length = 0;
  // Checked before anything is allocated: Rows x Columns of a hostile header asked for 17 GB
  // (fuzz_dicom_label_series).
  if (GetPixels(data, pixels, &length).bad() || !pixels || length < count)
  {
    throw InputError(where, "pixel data missing or shorter than Rows x Columns");
  }
  slice.BytesPerValue = sizeof(Stored);
  slice.Stored.resize(count * sizeof(Stored));
  std::memcpy(slice.Stored.data(), pixels, count * sizeof(Stored));
  if (isSigned)
  {
    slice.Census.Add(reinterpret_cast<const Signed*>(pixels), count);
  }
  else
  {
    slice.Census.Add(pixels, count);
  }
}

Slice ReadSlice(const std::string& folder, const fs::path& path)
{
  Slice s;
  s.File = path.filename().string();
  const std::string where = folder + " (" + s.File + ")";
  DcmFileFormat file;
  LoadDicomFile(file, path.string(), where);
  DcmDataset* data = file.getDataset();
  OFString text;
  data->findAndGetOFString(DCM_SOPClassUID, text);
  if (DicomSegReader::IsSegmentationClass(text.c_str()))
  {
    throw InputError(where, "a DICOM SEG file: give the file itself, not the folder that holds it");
  }
  data->findAndGetOFString(DCM_SeriesInstanceUID, text);
  s.SeriesUid = text.c_str();
  s.Identity = IdentityOf(*data);
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
  if (rows > MaxSliceSide || columns > MaxSliceSide)
  {
    // Read before the pixel data: two slices of 16384 x 16384 took gigabytes.
    throw InputError(where, std::to_string(columns) + " x " + std::to_string(rows) + " pixels: a slice of a labelmap is at most " +
        std::to_string(MaxSliceSide) + " x " + std::to_string(MaxSliceSide));
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
  if (bitsAllocated == 8)
  {
    CopyPixels<Uint8, std::int8_t>(data, representation != 0, count, s, where);
  }
  else if (bitsAllocated == 16)
  {
    CopyPixels<Uint16, std::int16_t>(data, representation != 0, count, s, where);
  }
  else
  {
    throw InputError(where, std::to_string(bitsAllocated) + "-bit pixels; labelmaps here are 8 or 16 bits");
  }
  return s;
}

/// Each slice's values into its place in the grid, narrowed or widened to the grid's type (the
/// census has checked that they fit), on every core: a fresh 67 MB grid is mostly page faults.
void PlaceSlices(const std::vector<Slice>& slices, const SliceStack& stack, LabelGrid& grid)
{
  const std::size_t sliceSize = static_cast<std::size_t>(slices.front().Rows) * slices.front().Columns;
  const bool narrow = grid.Labels->GetScalarType() == VTK_UNSIGNED_CHAR;
  void* voxels = grid.Labels->GetScalarPointer();
  vtkSMPTools::For(0, static_cast<vtkIdType>(slices.size()), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      const Slice& s = slices[static_cast<std::size_t>(p)];
      const std::size_t offset = sliceSize * static_cast<std::size_t>(stack.SliceOfPlane[static_cast<std::size_t>(p)]);
      const auto* wide = reinterpret_cast<const std::uint16_t*>(s.Stored.data());
      if (narrow && s.BytesPerValue == 1)
      {
        std::memcpy(static_cast<std::uint8_t*>(voxels) + offset, s.Stored.data(), sliceSize);
      }
      else if (narrow)
      {
        std::transform(wide, wide + sliceSize, static_cast<std::uint8_t*>(voxels) + offset,
          [](std::uint16_t v) { return static_cast<std::uint8_t>(v); });
      }
      else if (s.BytesPerValue == 1)
      {
        std::copy(s.Stored.begin(), s.Stored.end(), static_cast<std::uint16_t*>(voxels) + offset);
      }
      else
      {
        std::memcpy(static_cast<std::uint16_t*>(voxels) + offset, wide, sliceSize * 2);
      }
    }
  });
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
  // The first slice alone: with the number of files it tells the series' size before the others
  // are read. Then the rest on every core (DCMTK reads separate files independently): a
  // 260-slice series of five structures took 9.4 s on one.
  std::vector<Slice> slices(files.size());
  slices[0] = ReadSlice(folder, files[0]);
  const double voxels = double(slices.front().Rows) * double(slices.front().Columns) * double(files.size());
  if (voxels > MaxSeriesVoxels)
  {
    throw InputError(folder, std::to_string(files.size()) + " slices of " + std::to_string(slices.front().Columns) + " x " +
        std::to_string(slices.front().Rows) + " pixels: " + NumberText(voxels, 4) + " voxels, more than the " +
        NumberText(MaxSeriesVoxels, 4) + " this reader takes");
  }
  std::vector<std::exception_ptr> failures(files.size());
  std::atomic<std::size_t> next{ 1 };
  const auto work = [&] {
    for (std::size_t i = next++; i < files.size(); i = next++)
    {
      try
      {
        slices[i] = ReadSlice(folder, files[i]);
      }
      catch (...)
      {
        failures[i] = std::current_exception();
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>({ std::max(1u, std::thread::hardware_concurrency()), 8, files.size() - 1 });
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t)
  {
    pool.emplace_back(work);
  }
  work();
  for (std::thread& thread : pool)
  {
    thread.join();
  }
  // The first problem in file order, as a reading one by one would have met it.
  for (std::size_t i = 1; i < files.size(); ++i)
  {
    if (failures[i])
    {
      std::rethrow_exception(failures[i]);
    }
    if (slices[i].SeriesUid != slices.front().SeriesUid)
    {
      throw InputError(folder, "more than one series (" + slices.front().File + " and " + slices[i].File +
          " differ in SeriesInstanceUID); give each series its own folder");
    }
  }

  std::vector<PlanePlacement> planes;
  for (const Slice& s : slices)
  {
    if (s.Rows != slices.front().Rows || s.Columns != slices.front().Columns)
    {
      throw InputError(folder, "slices of different sizes (" + slices.front().File + " and " + s.File + ")");
    }
    planes.push_back({ s.File, s.Position, s.Orientation, s.Spacing });
  }
  const SliceStack stack = StackPlanes(folder, planes, StackRule::Contiguous);
  LabelCensus census;
  for (const Slice& s : slices)
  {
    census.Merge(s.Census);
  }
  census.CheckLabels(folder);
  const int dimensions[3] = { static_cast<int>(slices.front().Columns), static_cast<int>(slices.front().Rows),
    stack.NumberOfSlices };
  LabelGrid grid = NewLabelGrid(dimensions, stack.IjkToLps, census.Highest());
  PlaceSlices(slices, stack, grid);
  grid.Identity = slices.front().Identity; // one series: one patient, study and frame
  return grid;
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
