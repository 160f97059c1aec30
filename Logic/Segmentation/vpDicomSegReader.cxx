#include "vpDicomSegReader.h"

#include "vpDcmtkFile.h"
#include "vpInputError.h"
#include "vpSliceStack.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmfg/fgfact.h>
#include <dcmtk/dcmfg/fginterface.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <vtkImageData.h>

#include <algorithm>
#include <cstdint>
#include <memory>

namespace vp
{
namespace
{
// Not in DCMTK 3.6.7's dcuid.h: the class was added to the standard after that release.
constexpr const char* LabelMapSegmentationStorage = "1.2.840.10008.5.1.4.1.1.66.7";

struct SegmentInfo
{
  int Number = 0;
  std::string Label;
  CodedConcept Category;
  CodedConcept Type;
};

// The frames of a SEG, placed.
struct FrameGeometry
{
  SliceStack Stack;
  int Columns = 0;
  int Rows = 0;
};

FrameGeometry PlaceFrames(FGInterface& groups, std::size_t frames, DcmItem& data, const std::string& path,
  std::size_t maximumVoxels)
{
  FrameGeometry g;
  Uint16 rows = 0, columns = 0;
  if (data.findAndGetUint16(DCM_Rows, rows).bad() || data.findAndGetUint16(DCM_Columns, columns).bad() || rows == 0 ||
    columns == 0)
  {
    throw InputError(path, "no image: Rows or Columns missing");
  }
  g.Rows = rows;
  g.Columns = columns;
  std::vector<PlanePlacement> planes(frames);
  double spacingBetweenSlices = 0.0;
  for (std::size_t f = 0; f < frames; ++f)
  {
    PlanePlacement& p = planes[f];
    p.Name = "frame " + std::to_string(f + 1);
    const Uint32 frame = static_cast<Uint32>(f);
    auto* position = dynamic_cast<FGPlanePosPatient*>(groups.get(frame, DcmFGTypes::EFG_PLANEPOSPATIENT));
    auto* orientation = dynamic_cast<FGPlaneOrientationPatient*>(groups.get(frame, DcmFGTypes::EFG_PLANEORIENTPATIENT));
    auto* measures = dynamic_cast<FGPixelMeasures*>(groups.get(frame, DcmFGTypes::EFG_PIXELMEASURES));
    if (!position || position->getImagePositionPatient(p.PositionLps[0], p.PositionLps[1], p.PositionLps[2]).bad())
    {
      throw InputError(path, p.Name + " has no plane position: it cannot be placed");
    }
    auto& o = p.Orientation;
    if (!orientation || orientation->getImageOrientationPatient(o[0], o[1], o[2], o[3], o[4], o[5]).bad())
    {
      throw InputError(path, p.Name + " has no plane orientation: it cannot be placed");
    }
    if (!measures || measures->getPixelSpacing(p.PixelSpacingMm[0], 0).bad() ||
      measures->getPixelSpacing(p.PixelSpacingMm[1], 1).bad())
    {
      throw InputError(path, p.Name + " has no pixel spacing");
    }
    if (f == 0)
    {
      measures->getSpacingBetweenSlices(spacingBetweenSlices, 0);
    }
  }
  g.Stack = StackPlanes(path, planes, StackRule::Sparse, spacingBetweenSlices);
  const double voxels = double(rows) * double(columns) * double(g.Stack.NumberOfSlices);
  if (voxels > double(maximumVoxels))
  {
    throw InputError(path, "the frames span " + std::to_string(columns) + " x " + std::to_string(rows) + " x " +
        std::to_string(g.Stack.NumberOfSlices) + " voxels, more than the " + std::to_string(maximumVoxels) +
        " this reader allows");
  }
  return g;
}

vtkSmartPointer<vtkImageData> NewGrid(const FrameGeometry& g, int scalarType)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.Columns, g.Rows, g.Stack.NumberOfSlices);
  image->AllocateScalars(scalarType, 1);
  std::fill_n(static_cast<unsigned char*>(image->GetScalarPointer()),
    static_cast<std::size_t>(image->GetNumberOfPoints()) * static_cast<std::size_t>(image->GetScalarSize()), 0);
  return image;
}

LabelStructure MakeStructure(const SegmentInfo& segment, const std::string& path)
{
  LabelStructure s;
  s.Name = segment.Label.empty() ? "segment " + std::to_string(segment.Number) : segment.Label;
  s.Source = path;
  s.Category = segment.Category;
  s.Type = segment.Type;
  return s;
}

void RefuseEmpty(const LabelStructure& s, const std::string& path)
{
  if (s.Grid.Labels && LabelValuesIn(s.Grid).empty())
  {
    throw InputError(path, "segment '" + s.Name + "' is empty: no voxel is set");
  }
}

CodedConcept ConceptOf(CodeSequenceMacro& code)
{
  OFString scheme, value, meaning;
  code.getCodingSchemeDesignator(scheme);
  code.getCodeValue(value);
  code.getCodeMeaning(meaning);
  return { scheme.c_str(), value.c_str(), meaning.c_str() };
}

// BINARY and FRACTIONAL, through dcmseg: one grid per segment.
LabelStructures ReadSegmentation(DcmDataset& data, const std::string& path, const StructureFilter& wanted,
  std::size_t maximumVoxels)
{
  DcmSegmentation* loaded = nullptr;
  const OFCondition status = DcmSegmentation::loadDataset(data, loaded);
  std::unique_ptr<DcmSegmentation> seg(loaded);
  if (status.bad() || !seg)
  {
    throw InputError(path, std::string("not a segmentation DCMTK can read (") + status.text() + ")");
  }
  const bool fractional = seg->getSegmentationType() == DcmSegTypes::ST_FRACTIONAL;
  if (!fractional && seg->getSegmentationType() != DcmSegTypes::ST_BINARY)
  {
    throw InputError(path, "a segmentation type other than BINARY or FRACTIONAL");
  }
  Uint16 maximumFraction = 255;
  data.findAndGetUint16(DCM_MaximumFractionalValue, maximumFraction);
  if (fractional && maximumFraction == 0)
  {
    throw InputError(path, "MaximumFractionalValue is 0");
  }
  const std::size_t frames = seg->getNumberOfFrames();
  // DCMTK reads as many frames as NumberOfFrames says, and getFrame() trusts the per-frame groups'
  // count (with none read it indexed past the end: NumberOfFrames 0 crashed). They must agree.
  Sint32 declaredFrames = 0;
  if (frames == 0 || data.findAndGetSint32(DCM_NumberOfFrames, declaredFrames).bad() || declaredFrames <= 0 ||
    static_cast<std::size_t>(declaredFrames) != frames)
  {
    throw InputError(path, "NumberOfFrames (" + std::to_string(declaredFrames) + ") does not match the " +
        std::to_string(frames) + " per-frame functional groups");
  }
  FrameGeometry g = PlaceFrames(seg->getFunctionalGroups(), frames, data, path, maximumVoxels);

  LabelStructures structures;
  for (std::size_t n = 1; n <= seg->getNumberOfSegments(); ++n)
  {
    DcmSegment* segment = seg->getSegment(n);
    if (!segment)
    {
      throw InputError(path, "segment " + std::to_string(n) + " is listed but cannot be read");
    }
    SegmentInfo info;
    info.Number = static_cast<int>(n);
    OFString label;
    segment->getSegmentLabel(label);
    info.Label = label.c_str();
    info.Category = ConceptOf(segment->getSegmentedPropertyCategoryCode());
    info.Type = ConceptOf(segment->getSegmentedPropertyTypeCode());
    structures.push_back(MakeStructure(info, path));
    if (!wanted || wanted(structures.back().Name))
    {
      structures.back().Grid.Labels = NewGrid(g, VTK_UNSIGNED_CHAR);
      structures.back().Grid.IjkToLps = g.Stack.IjkToLps;
    }
  }

  const std::size_t pixels = static_cast<std::size_t>(g.Rows) * static_cast<std::size_t>(g.Columns);
  const std::size_t frameBytes = fractional ? pixels : (pixels + 7) / 8;
  FGInterface& groups = seg->getFunctionalGroups();
  for (std::size_t f = 0; f < frames; ++f)
  {
    auto* identification = dynamic_cast<FGSegmentation*>(groups.get(static_cast<Uint32>(f), DcmFGTypes::EFG_SEGMENTATION));
    Uint16 number = 0;
    if (!identification || identification->getReferencedSegmentNumber(number).bad() || number == 0 ||
      number > structures.size())
    {
      throw InputError(path, "frame " + std::to_string(f + 1) + " names no listed segment");
    }
    LabelStructure& s = structures[number - 1u];
    if (!s.Grid.Labels)
    {
      continue;
    }
    const DcmIODTypes::Frame* frame = seg->getFrame(f);
    if (!frame || !frame->pixData || frame->length < frameBytes)
    {
      throw InputError(path, "pixel data shorter than its " + std::to_string(frames) + " frames");
    }
    auto* out = static_cast<std::uint8_t*>(s.Grid.Labels->GetScalarPointer()) +
      pixels * static_cast<std::size_t>(g.Stack.SliceOfPlane[f]);
    for (std::size_t i = 0; i < pixels; ++i)
    {
      // BINARY frames pack 8 pixels per byte, the first in the lowest bit.
      const bool inside = fractional ? 2u * frame->pixData[i] >= maximumFraction : (frame->pixData[i >> 3] >> (i & 7)) & 1u;
      out[i] = static_cast<std::uint8_t>(out[i] | (inside ? 1u : 0u));
    }
  }
  for (const LabelStructure& s : structures)
  {
    RefuseEmpty(s, path);
  }
  return structures;
}

CodedConcept ConceptIn(DcmItem& item, const DcmTagKey& sequence)
{
  DcmItem* code = nullptr;
  CodedConcept c;
  if (item.findAndGetSequenceItem(sequence, code, 0).good() && code)
  {
    OFString text;
    code->findAndGetOFString(DCM_CodingSchemeDesignator, text);
    c.Scheme = text.c_str();
    code->findAndGetOFString(DCM_CodeValue, text);
    c.Value = text.c_str();
    code->findAndGetOFString(DCM_CodeMeaning, text);
    c.Meaning = text.c_str();
  }
  return c;
}

OFCondition GetPixels(DcmItem& data, const Uint8*& pixels, unsigned long* count)
{
  return data.findAndGetUint8Array(DCM_PixelData, pixels, count);
}

OFCondition GetPixels(DcmItem& data, const Uint16*& pixels, unsigned long* count)
{
  return data.findAndGetUint16Array(DCM_PixelData, pixels, count);
}

// Copies each stored frame into its slice of grid; false when the pixel data is short.
template <typename Stored>
bool CopyFrames(DcmItem& data, const FrameGeometry& g, LabelGrid& grid)
{
  const Stored* stored = nullptr;
  unsigned long count = 0;
  const std::size_t pixels = static_cast<std::size_t>(g.Rows) * static_cast<std::size_t>(g.Columns);
  const std::size_t frames = g.Stack.SliceOfPlane.size();
  if (GetPixels(data, stored, &count).bad() || !stored || count < frames * pixels)
  {
    return false;
  }
  auto* out = static_cast<Stored*>(grid.Labels->GetScalarPointer());
  for (std::size_t f = 0; f < frames; ++f)
  {
    std::copy_n(stored + f * pixels, pixels, out + pixels * static_cast<std::size_t>(g.Stack.SliceOfPlane[f]));
  }
  return true;
}

// LABELMAP, through dcmdata and dcmfg: frames of segment numbers, one shared grid.
LabelStructures ReadLabelMap(DcmDataset& data, const std::string& path, const StructureFilter& wanted,
  std::size_t maximumVoxels)
{
  FGInterface groups;
  if (groups.read(data).bad() || groups.getNumberOfFrames() == 0)
  {
    throw InputError(path, "no per-frame functional groups: the frames cannot be placed");
  }
  const std::size_t frames = groups.getNumberOfFrames();
  Sint32 declaredFrames = 0;
  if (data.findAndGetSint32(DCM_NumberOfFrames, declaredFrames).bad() || declaredFrames < 0 ||
    static_cast<std::size_t>(declaredFrames) != frames)
  {
    throw InputError(path, "NumberOfFrames does not match the " + std::to_string(frames) + " per-frame functional groups");
  }
  const FrameGeometry g = PlaceFrames(groups, frames, data, path, maximumVoxels);

  LabelStructures structures;
  bool anyWanted = false;
  for (unsigned long i = 0;; ++i)
  {
    DcmItem* item = nullptr;
    if (data.findAndGetSequenceItem(DCM_SegmentSequence, item, static_cast<signed long>(i)).bad() || !item)
    {
      break;
    }
    SegmentInfo info;
    Uint16 number = 0;
    if (item->findAndGetUint16(DCM_SegmentNumber, number).bad())
    {
      throw InputError(path, "segment " + std::to_string(i + 1) + " of SegmentSequence has no SegmentNumber");
    }
    if (number == 0)
    {
      continue; // the background
    }
    info.Number = number;
    OFString label;
    item->findAndGetOFString(DCM_SegmentLabel, label);
    info.Label = label.c_str();
    info.Category = ConceptIn(*item, DCM_SegmentedPropertyCategoryCodeSequence);
    info.Type = ConceptIn(*item, DCM_SegmentedPropertyTypeCodeSequence);
    structures.push_back(MakeStructure(info, path));
    structures.back().LabelValue = number;
    anyWanted = anyWanted || !wanted || wanted(structures.back().Name);
  }
  if (structures.empty())
  {
    throw InputError(path, "no segment listed in SegmentSequence");
  }
  if (!anyWanted)
  {
    return structures;
  }

  Uint16 bitsAllocated = 0;
  data.findAndGetUint16(DCM_BitsAllocated, bitsAllocated);
  if (bitsAllocated != 8 && bitsAllocated != 16)
  {
    throw InputError(path, std::to_string(bitsAllocated) + "-bit label map frames; 8 or 16 are read");
  }
  LabelGrid grid;
  grid.Labels = NewGrid(g, bitsAllocated == 8 ? VTK_UNSIGNED_CHAR : VTK_UNSIGNED_SHORT);
  grid.IjkToLps = g.Stack.IjkToLps;
  const bool complete = bitsAllocated == 8 ? CopyFrames<Uint8>(data, g, grid) : CopyFrames<Uint16>(data, g, grid);
  if (!complete)
  {
    throw InputError(path, "pixel data missing or shorter than its " + std::to_string(frames) + " frames");
  }
  const std::vector<int> present = LabelValuesIn(grid);
  for (LabelStructure& s : structures)
  {
    if (wanted && !wanted(s.Name))
    {
      continue;
    }
    s.Grid = grid;
    if (!std::binary_search(present.begin(), present.end(), s.LabelValue))
    {
      throw InputError(path, "segment '" + s.Name + "' is empty: no voxel holds its number " +
          std::to_string(s.LabelValue));
    }
  }
  return structures;
}
} // namespace

void DicomSegReader::PrepareForThreads()
{
  FGFactory::instance();
}

bool DicomSegReader::IsSegmentationClass(const std::string& sopClassUid)
{
  return sopClassUid == UID_SegmentationStorage || sopClassUid == LabelMapSegmentationStorage;
}

LabelStructures DicomSegReader::Read(const std::string& path, const StructureFilter& wanted, std::size_t maximumVoxels)
{
  DcmFileFormat file;
  LoadDicomFile(file, path, path);
  DcmDataset& data = *file.getDataset();
  OFString sopClass;
  data.findAndGetOFString(DCM_SOPClassUID, sopClass);
  if (sopClass != UID_SegmentationStorage && sopClass != LabelMapSegmentationStorage)
  {
    throw InputError(path, std::string("a single DICOM ") + dcmFindNameOfUID(sopClass.c_str(), "file") +
      " object, not a segmentation; give the folder that holds its series");
  }
  LabelStructures structures = sopClass == UID_SegmentationStorage ? ReadSegmentation(data, path, wanted, maximumVoxels)
                                                                    : ReadLabelMap(data, path, wanted, maximumVoxels);
  const ImageIdentity identity = IdentityOf(data);
  for (LabelStructure& structure : structures)
  {
    structure.Grid.Identity = identity;
  }
  return structures;
}
} // namespace vp
