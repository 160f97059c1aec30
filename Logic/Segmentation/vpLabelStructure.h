#ifndef vpLabelStructure_h
#define vpLabelStructure_h

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vp
{
/// A coded concept as DICOM carries it: coding scheme designator, code value, code meaning
/// (e.g. SCT 32764006 "Portal vein").
struct CodedConcept
{
  std::string Scheme;
  std::string Value;
  std::string Meaning;

  bool Empty() const { return this->Value.empty(); }
  /// "SCT:32764006" — the key the label table matches on.
  std::string Key() const { return this->Scheme + ":" + this->Value; }
};

/// Whose image a labelmap is, as DICOM says it (every field empty for NRRD and NIfTI, which do
/// not say): the models of one run must be one patient's, in one frame of reference.
struct ImageIdentity
{
  std::string PatientId;
  std::string PatientName;
  std::string StudyUid;
  std::string FrameOfReferenceUid;
  /// "patient 'P' (ID I), study S, frame of reference F", the known fields only.
  std::string Describe() const;
  /// "patient" when both know the patient (its ID, or its name's family name) and it differs,
  /// "frame of reference" likewise, else "". The study is not compared: some data sets (IRCADb)
  /// give each structure of one patient a study of its own.
  std::string DiffersIn(const ImageIdentity& other) const;
};

/// The voxel grid of an imported labelmap: integer labels on an index grid (vtkImageData with
/// origin 0 and spacing 1, so VTK filters work in index space as Slicer's do), and the 4x4
/// index-to-LPS matrix that places it in DICOM patient coordinates (millimetres).
struct LabelGrid
{
  vtkSmartPointer<vtkImageData> Labels;
  std::array<double, 16> IjkToLps{}; ///< row-major; column k is the step of index k in mm
  ImageIdentity Identity;             ///< whose image it is (DICOM)

  /// Spacing along index axis k (mm): the length of column k.
  double SpacingMm(int k) const;
  /// Volume of one voxel (mm^3).
  double VoxelVolumeMm3() const;
};

/// One labelled structure of an imported segmentation: the voxels of Grid equal to LabelValue
/// (or, with LabelValue 0, every non-zero voxel: IRCADb's one-mask-per-structure layout, whose
/// foreground is 255 in most files and 1 in some). Structures of one multi-label volume share
/// their Grid.
struct LabelStructure
{
  std::string Name;   ///< as the source names it: folder, SEG segment label, Segment<N>_Name, or "label N"
  std::string Source; ///< the file or folder it came from
  int LabelValue = 0;
  /// The labelmap held this value alone: its name is its source's (a mask's folder or file, or a
  /// temporary file Slicer named), so a table may know it by its value instead.
  bool OnlyValue = false;
  CodedConcept Category; ///< DICOM SEG coded anatomy; empty for other formats
  CodedConcept Type;
  LabelGrid Grid; ///< Grid.Labels is null for a structure listed but not read (not wanted)
  /// Which connected piece of its source structure this is (SplitIntoComponents: 1 the largest,
  /// of PieceCount); 0 for a structure whole.
  int Piece = 0;
  int PieceCount = 0;

  /// The source gave it no name of its own: "label N" of a multi-value labelmap, or the only value
  /// of one named after its file. Only its value (or a colour table's name for it) says what it is.
  bool IsUnnamed() const { return this->OnlyValue || this->Name == "label " + std::to_string(this->LabelValue); }
};

/// Everything one import produced, in the order the source lists it.
using LabelStructures = std::vector<LabelStructure>;

/// Decides, from a structure's name, whether its voxels are read (the others are only listed).
using StructureFilter = std::function<bool(const std::string& name)>;

/// Throws InputError(source, ...) unless an index-to-LPS matrix is a voxel grid a patient's image
/// can have: finite, each voxel axis from limits::MinVoxelMm to limits::MaxVoxelMm long, the three
/// axes not in one plane, the origin within limits::CoordinateMm. Checked from the header, before
/// any voxel is allocated (PixelSpacing 1e-300 gave a model of no volume).
void CheckVoxelGeometry(const std::array<double, 16>& ijkToLps, const std::string& source);

/// Which values a labelmap's voxels hold, gathered in parts (a slice each, on separate threads)
/// and merged: the lowest and highest, and which of 0 to 65535 occur.
class LabelCensus
{
public:
  LabelCensus();
  void Add(const std::int32_t* values, std::size_t count);
  void Add(const std::uint16_t* values, std::size_t count);
  void Add(const std::int16_t* values, std::size_t count);
  void Add(const std::uint8_t* values, std::size_t count);
  void Add(const std::int8_t* values, std::size_t count);
  void Merge(const LabelCensus& other);
  /// Throws vp::InputError naming source unless the values are labels: none negative, none above
  /// 65535 and at most 256 distinct ("an image, not a labelmap").
  void CheckLabels(const std::string& source) const;
  std::int32_t Highest() const { return this->Hi; }

private:
  template <typename T>
  void AddValues(const T* values, std::size_t count);
  std::int32_t Lo = 0, Hi = 0;
  std::vector<std::uint64_t> Present; ///< a bit per value 0 to 65535
};

/// A grid of dimensions for labels up to highestValue, in the narrowest unsigned type that holds
/// them (8 or 16 bits), its voxels not set.
LabelGrid NewLabelGrid(const int dimensions[3], const std::array<double, 16>& ijkToLps, std::int32_t highestValue);

/// Stores voxel values (x fastest, then y, then z) as a LabelGrid in the narrowest unsigned type
/// that holds them, after checking that they are labels: no negative value and at most 256
/// distinct ones; otherwise throws vp::InputError naming source ("an image, not a labelmap").
LabelGrid MakeLabelGrid(const std::string& source, const int dimensions[3], const std::vector<std::int32_t>& values,
  const std::array<double, 16>& ijkToLps);

/// The distinct non-zero values of a grid, ascending.
std::vector<int> LabelValuesIn(const LabelGrid& grid);

/// One structure per non-zero value of an unnamed labelmap: "label N", or singleName when the map
/// holds a single value (a one-structure mask named after its file or folder). Throws
/// vp::InputError naming source when every voxel is 0.
LabelStructures StructuresOf(const LabelGrid& grid, const std::string& source, const std::string& singleName);
} // namespace vp

#endif
