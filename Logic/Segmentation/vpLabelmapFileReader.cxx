// The only translation unit that includes ITK headers: they are heavy to compile.
#include "vpLabelmapFileReader.h"

#include "vpLibraryStateLock.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"

#if defined(__clang__)
#include "vpItkClangCompat.h" // before any ITK header
#endif
#include <itkImageFileReader.h>
#include <itkMetaDataObject.h>
#include <itkNiftiImageIO.h>
#include <itkNrrdImageIO.h>
#include <itkVectorImage.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

namespace vp
{
namespace
{
bool EndsWith(const std::string& text, const std::string& suffix)
{
  if (text.size() < suffix.size())
  {
    return false;
  }
  std::string tail = text.substr(text.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == suffix;
}

bool IsNifti(const std::string& fileName)
{
  return EndsWith(fileName, ".nii") || EndsWith(fileName, ".nii.gz");
}

// The file's name without folder and without its labelmap ending.
std::string Stem(const std::string& fileName)
{
  std::string name = fileName.substr(fileName.find_last_of('/') + 1);
  for (const char* suffix : { ".seg.nrrd", ".nii.gz", ".nrrd", ".nhdr", ".nii" })
  {
    if (EndsWith(name, suffix))
    {
      return name.substr(0, name.size() - std::string(suffix).size());
    }
  }
  return name;
}

// "scheme^value^meaning" of Slicer's terminology strings.
CodedConcept ParseCode(const std::string& text)
{
  CodedConcept code;
  std::istringstream in(text);
  std::getline(in, code.Scheme, '^');
  std::getline(in, code.Value, '^');
  std::getline(in, code.Meaning, '^');
  return code;
}

// The Segment<N>_* keys of a Slicer segmentation file, by segment index.
struct SegmentKeys
{
  std::string Name;
  int LabelValue = 1;
  int Layer = 0;
  std::string Terminology;
};

// The whole text must be one integer that fits an int: std::stoi would take "3abc" as 3 and
// throw std::out_of_range (not an InputError) on a 70-digit segment index.
bool ParseInt(const std::string& text, int& value)
{
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && stop == end;
}

std::map<int, SegmentKeys> ReadSegmentKeys(const itk::MetaDataDictionary& dictionary, const std::string& fileName)
{
  std::map<int, SegmentKeys> segments;
  for (const std::string& key : dictionary.GetKeys())
  {
    if (key.rfind("Segment", 0) != 0 || key.find('_') == std::string::npos)
    {
      continue;
    }
    const std::string index = key.substr(7, key.find('_') - 7);
    if (index.empty() || !std::all_of(index.begin(), index.end(), ::isdigit))
    {
      continue;
    }
    std::string value;
    if (!itk::ExposeMetaData<std::string>(dictionary, key, value))
    {
      continue;
    }
    int number = 0;
    if (!ParseInt(index, number))
    {
      throw InputError(fileName, "header key " + key + " has a segment number out of range");
    }
    SegmentKeys& s = segments[number];
    const std::string field = key.substr(key.find('_') + 1);
    if (field == "Name")
    {
      s.Name = value;
    }
    else if (field == "Terminology")
    {
      s.Terminology = value;
    }
    else if ((field == "LabelValue" && !ParseInt(value, s.LabelValue)) || (field == "Layer" && !ParseInt(value, s.Layer)))
    {
      throw InputError(fileName, "header key " + key + " is not a whole number: '" + value + "'");
    }
  }
  return segments;
}

// How the voxels are stored in the file itself, which bounds what its header may claim: raw (a
// .nii, or a .nrrd with "encoding: raw"), gzip (a .nii.gz, or a .nrrd with "encoding: gzip"), or
// beyond what the file's size can tell (a separate data file, bzip2, text).
enum class VoxelStorage
{
  Raw,
  Gzip,
  Unbounded,
};

/// Calls visit(the line in lower case, the line) for each line of an NRRD file's header, up to
/// the blank line that ends it, while visit returns true.
void VisitNrrdHeader(
  const std::string& fileName, const std::function<bool(const std::string& lower, const std::string& line)>& visit)
{
  std::ifstream in(fileName, std::ios::binary);
  for (std::string line; std::getline(in, line) && !line.empty() && line != "\r";)
  {
    std::string lower = line;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (!visit(lower, line))
    {
      return;
    }
  }
}

VoxelStorage StorageOf(const std::string& fileName)
{
  if (EndsWith(fileName, ".nii") || EndsWith(fileName, ".nii.gz"))
  {
    return EndsWith(fileName, ".nii") ? VoxelStorage::Raw : VoxelStorage::Gzip;
  }
  if (!EndsWith(fileName, ".nrrd"))
  {
    return VoxelStorage::Unbounded;
  }
  VoxelStorage storage = VoxelStorage::Unbounded;
  VisitNrrdHeader(fileName, [&](const std::string& lower, const std::string&) {
    if (lower.rfind("data file:", 0) == 0 || lower.rfind("datafile:", 0) == 0)
    {
      storage = VoxelStorage::Unbounded;
      return false;
    }
    if (lower.rfind("encoding:", 0) == 0)
    {
      storage = lower.find("raw") != std::string::npos ? VoxelStorage::Raw
        : lower.find("gz") != std::string::npos       ? VoxelStorage::Gzip
                                                      : VoxelStorage::Unbounded;
    }
    return true;
  });
  return storage;
}

/// The lengths of the axes an NRRD header line gives: the vectors "(x,y,z)" of "space
/// directions" ("none": an axis not in space), or the numbers of "spacings" (NaN: the same).
/// A vector holding a NaN or an infinity has length NaN.
std::vector<double> AxisLengths(const std::string& value, bool vectors)
{
  std::vector<double> lengths;
  const auto numbers = [](const char* p, const char* stop, std::vector<double>& out) {
    while (p < stop)
    {
      char* end = nullptr;
      const double v = std::strtod(p, &end);
      if (end == p || end > stop)
      {
        ++p;
        continue;
      }
      out.push_back(v);
      p = end;
    }
  };
  if (!vectors)
  {
    numbers(value.c_str(), value.c_str() + value.size(), lengths);
    lengths.erase(std::remove_if(lengths.begin(), lengths.end(), [](double v) { return std::isnan(v); }), lengths.end());
    return lengths;
  }
  for (std::size_t open = value.find('('); open != std::string::npos; open = value.find('(', open + 1))
  {
    const std::size_t close = value.find(')', open);
    if (close == std::string::npos)
    {
      break;
    }
    std::vector<double> v;
    numbers(value.c_str() + open + 1, value.c_str() + close, v);
    double length = 0.0; // hypot: a component of 1e155 does not overflow when squared
    for (double x : v)
    {
      length = std::isfinite(x) ? std::hypot(length, x) : std::nan("");
    }
    lengths.push_back(length);
  }
  return lengths;
}

// ITK takes an NRRD's "space directions" apart into spacings and unit directions, and a column
// too long to square (1e155) became a spacing of 1 mm: the axes are checked as written.
void CheckNrrdDirections(const std::string& fileName)
{
  if (!EndsWith(fileName, ".nrrd") && !EndsWith(fileName, ".nhdr"))
  {
    return;
  }
  VisitNrrdHeader(fileName, [&](const std::string& lower, const std::string& line) {
    const bool vectors = lower.rfind("space directions:", 0) == 0;
    if (!vectors && lower.rfind("spacings:", 0) != 0)
    {
      return true;
    }
    const std::string field = line.substr(0, line.find(':'));
    for (const double length : AxisLengths(line.substr(field.size() + 1), vectors))
    {
      if (!(length >= limits::MinVoxelMm && length <= limits::MaxVoxelMm))
      {
        throw InputError(fileName, "\"" + field + "\" gives a voxel axis " +
            (std::isfinite(length) ? NumberText(length) + " mm long" : std::string("with a NaN or infinite value")) +
            ": a voxel is " + NumberText(limits::MinVoxelMm) + " to " + NumberText(limits::MaxVoxelMm) + " mm");
      }
    }
    return true;
  });
}

// Deflate (gzip) gives at most 1032 bytes out per byte in (zlib's technical details): a header
// claiming more than that of its file is refused before ITK allocates the image.
constexpr double GzipMaximumRatio = 1032.0;

void CheckClaimAgainstFile(const std::string& fileName, double claimed, double claimedBytes)
{
  std::error_code ec;
  const auto fileBytes = std::filesystem::file_size(fileName, ec);
  const VoxelStorage storage = ec ? VoxelStorage::Unbounded : StorageOf(fileName);
  if (storage == VoxelStorage::Raw && claimedBytes > static_cast<double>(fileBytes))
  {
    throw InputError(fileName, "the header claims " + std::to_string(static_cast<long long>(claimed)) + " voxels (" +
        std::to_string(static_cast<long long>(claimedBytes)) + " bytes, uncompressed), but the file is only " +
        std::to_string(fileBytes) + " bytes");
  }
  if (storage == VoxelStorage::Gzip && claimedBytes > GzipMaximumRatio * static_cast<double>(fileBytes))
  {
    throw InputError(fileName, "the header claims " + std::to_string(static_cast<long long>(claimed)) + " voxels (" +
        std::to_string(static_cast<long long>(claimedBytes)) + " bytes), more than gzip can hold in a file of " +
        std::to_string(fileBytes) + " bytes (at most 1032 to 1)");
  }
}
} // namespace

bool LabelmapFileReader::Handles(const std::string& fileName)
{
  return IsNifti(fileName) || EndsWith(fileName, ".nrrd") || EndsWith(fileName, ".nhdr");
}

namespace
{
using LabelImage = itk::VectorImage<double, 3>;

/// The image through io, its header checked before a voxel is read: three dimensions, a voxel
/// geometry (ijkToLps, filled here) the checks accept, no more voxels than maximumVoxels and no
/// more than the file holds. One line for ITK's own errors.
LabelImage::Pointer ReadLabelImage(itk::ImageIOBase* io, const std::string& fileName, std::size_t maximumVoxels,
  std::array<double, 16>& ijkToLps)
{
  using Image = LabelImage;
  Image::Pointer image;
  try
  {
    io->SetFileName(fileName);
    io->ReadImageInformation();
    if (io->GetNumberOfDimensions() != 3)
    {
      throw InputError(fileName, std::to_string(io->GetNumberOfDimensions()) + "-dimensional image; a labelmap is 3D");
    }
    double claimed = io->GetNumberOfComponents();
    for (unsigned d = 0; d < 3; ++d)
    {
      claimed *= static_cast<double>(io->GetDimensions(d));
    }
    // The geometry as the header gives it, checked before a voxel is read.
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        ijkToLps[4 * r + c] = io->GetDirection(static_cast<unsigned>(c))[static_cast<std::size_t>(r)] *
          io->GetSpacing(static_cast<unsigned>(c));
      }
      ijkToLps[4 * r + 3] = io->GetOrigin(static_cast<unsigned>(r));
    }
    ijkToLps[15] = 1.0;
    CheckVoxelGeometry(ijkToLps, fileName);
    if (claimed > static_cast<double>(maximumVoxels))
    {
      throw InputError(fileName, "the header claims " + std::to_string(static_cast<long long>(claimed)) +
          " voxels, more than the " + std::to_string(maximumVoxels) + " this reader takes");
    }
    // The voxels must fit in the file: a header claiming more is refused before the image is
    // allocated (a 100-byte file claiming 600^3 voxels took 256 MB first).
    CheckClaimAgainstFile(fileName, claimed, claimed * static_cast<double>(io->GetComponentSize()));
    auto reader = itk::ImageFileReader<Image>::New();
    reader->SetImageIO(io);
    reader->SetFileName(fileName);
    reader->Update();
    image = reader->GetOutput();
  }
  catch (const itk::ExceptionObject& e)
  {
    // ITK's description runs over lines, its cause on the last: one line, all of it.
    std::string what = e.GetDescription();
    std::replace(what.begin(), what.end(), '\n', ' ');
    while (!what.empty() && what.back() == ' ')
    {
      what.pop_back();
    }
    throw InputError(fileName, "cannot be read: " + what);
  }
  return image;
}

/// One grid per layer (vector component); values must be whole numbers.
std::vector<LabelGrid> LayerGrids(LabelImage* image, const std::string& fileName, const std::array<double, 16>& ijkToLps)
{
  const auto size = image->GetLargestPossibleRegion().GetSize();
  const int dimensions[3] = { static_cast<int>(size[0]), static_cast<int>(size[1]), static_cast<int>(size[2]) };
  const unsigned layers = image->GetNumberOfComponentsPerPixel();
  const std::size_t voxels = static_cast<std::size_t>(size[0]) * size[1] * size[2];
  const double* buffer = image->GetBufferPointer();
  std::vector<LabelGrid> grids;
  for (unsigned layer = 0; layer < layers; ++layer)
  {
    std::vector<std::int32_t> values(voxels);
    for (std::size_t i = 0; i < voxels; ++i)
    {
      const double v = buffer[i * layers + layer];
      if (v != std::floor(v) || std::abs(v) > 1e9)
      {
        std::ostringstream example;
        example << v;
        throw InputError(fileName, "an image, not a labelmap: non-integer voxel values (" + example.str() +
            "), as in CT or a probability map");
      }
      values[i] = static_cast<std::int32_t>(v);
    }
    grids.push_back(MakeLabelGrid(layers > 1 ? fileName + " (layer " + std::to_string(layer) + ")" : fileName,
      dimensions, values, ijkToLps));
  }
  return grids;
}

/// The structure a Segment<N>_ key set names, on its layer's grid.
LabelStructure SegmentStructure(int index, const SegmentKeys& keys, const std::string& fileName, const std::vector<LabelGrid>& grids)
{
  LabelStructure s;
  s.Name = keys.Name.empty() ? "Segment" + std::to_string(index) : keys.Name;
  s.Source = fileName;
  s.LabelValue = keys.LabelValue;
  // Slicer: "context~category scheme^value^meaning~type scheme^value^meaning~..."
  std::vector<std::string> fields;
  std::istringstream in(keys.Terminology);
  for (std::string field; std::getline(in, field, '~');)
  {
    fields.push_back(field);
  }
  if (fields.size() >= 3)
  {
    s.Category = ParseCode(fields[1]);
    s.Type = ParseCode(fields[2]);
  }
  s.Grid = grids[static_cast<std::size_t>(keys.Layer)];
  return s;
}
} // namespace

LabelStructures LabelmapFileReader::Read(const std::string& fileName, std::size_t maximumVoxels)
{
  // ITK's factories and singletons, made on first use, and NrrdIO's error buffers are the
  // process's: a cohort's cases read their labelmaps one at a time (the lock is released after
  // ITK's objects are gone).
  const std::lock_guard<std::mutex> lock(LibraryStateLock());
  itk::ImageIOBase::Pointer io;
  if (IsNifti(fileName))
  {
    io = itk::NiftiImageIO::New();
  }
  else
  {
    io = itk::NrrdImageIO::New();
  }
  if (!io->CanReadFile(fileName.c_str()))
  {
    throw InputError(fileName, std::string("not a readable ") + (IsNifti(fileName) ? "NIfTI" : "NRRD") + " file");
  }
  std::array<double, 16> ijkToLps{};
  CheckNrrdDirections(fileName);
  const LabelImage::Pointer image = ReadLabelImage(io, fileName, maximumVoxels, ijkToLps);
  const unsigned layers = image->GetNumberOfComponentsPerPixel();
  const std::vector<LabelGrid> grids = LayerGrids(image, fileName, ijkToLps);
  const std::map<int, SegmentKeys> segments = ReadSegmentKeys(io->GetMetaDataDictionary(), fileName);
  if (segments.empty())
  {
    if (layers > 1)
    {
      throw InputError(fileName, std::to_string(layers) + " components per voxel and no Segment<N>_ keys naming them");
    }
    return StructuresOf(grids.front(), fileName, Stem(fileName));
  }
  LabelStructures structures;
  for (const auto& [index, keys] : segments)
  {
    if (keys.Layer < 0 || keys.Layer >= static_cast<int>(layers))
    {
      throw InputError(fileName, "Segment" + std::to_string(index) + "_Layer is " + std::to_string(keys.Layer) +
          " but the file has " + std::to_string(layers) + " layer(s)");
    }
    structures.push_back(SegmentStructure(index, keys, fileName, grids));
  }
  return structures;
}
} // namespace vp
