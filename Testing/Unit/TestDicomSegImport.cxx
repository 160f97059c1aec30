// DICOM SEG import: every SEG file of the shared data (dcmqi, highdicom, dcmjs), binary,
// fractional, overlapping and the label-map class, with its segments, names and geometry; the
// voxels checked against an independent copy of the same segmentation where the data has one
// (dcmqi's NRRD of the liver, highdicom's binary twin of its fractional file, the CT slices the
// liver SEG was drawn on).
#include "vpInputError.h"
#include "vpSegmentationImport.h"
#include "vpTestSupport.h"
#include "vpVesselLabelTable.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <gtest/gtest.h>

#include <vtkImageData.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace
{
class DicomSegImport : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Data = vp::test::TestDataDir();
    if (this->Data.empty())
      GTEST_SKIP() << "VP_TEST_DATA not set: the DICOM SEG files are in ../shared/data";
  }

  vp::LabelStructures Import(const std::string& relative)
  {
    return vp::ImportSegmentation(this->Data + "/" + relative, nullptr);
  }

  std::string Data;
};

bool Inside(const vp::LabelStructure& s, int i, int j, int k)
{
  const double v = s.Grid.Labels->GetScalarComponentAsDouble(i, j, k, 0);
  return s.LabelValue == 0 ? v != 0.0 : v == s.LabelValue;
}

std::size_t CountInside(const vp::LabelStructure& s, int slice = -1)
{
  const int* d = s.Grid.Labels->GetDimensions();
  std::size_t n = 0;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
        n += (slice < 0 || slice == k) && Inside(s, i, j, k);
  return n;
}

std::size_t CountBoth(const vp::LabelStructure& a, const vp::LabelStructure& b)
{
  const int* d = a.Grid.Labels->GetDimensions();
  std::size_t n = 0;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
        n += Inside(a, i, j, k) && Inside(b, i, j, k);
  return n;
}

void ExpectGeometry(const vp::LabelStructure& s, std::array<int, 3> dimensions, std::array<double, 3> origin,
  std::array<double, 3> spacing)
{
  const int* d = s.Grid.Labels->GetDimensions();
  EXPECT_EQ(d[0], dimensions[0]) << s.Name;
  EXPECT_EQ(d[1], dimensions[1]) << s.Name;
  EXPECT_EQ(d[2], dimensions[2]) << s.Name;
  for (int r = 0; r < 3; ++r)
  {
    EXPECT_NEAR(s.Grid.IjkToLps[4 * r + 3], origin[r], 1e-3) << s.Name << " origin " << r;
    EXPECT_NEAR(s.Grid.SpacingMm(r), spacing[r], 1e-5) << s.Name << " spacing " << r;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.Grid.IjkToLps[4 * r + c], r == c ? spacing[r] : 0.0, 1e-5) << s.Name << " axial grid";
  }
}

std::vector<std::string> Names(const vp::LabelStructures& structures)
{
  std::vector<std::string> names;
  for (const auto& s : structures)
    names.push_back(s.Name);
  return names;
}

TEST_F(DicomSegImport, DcmqiLiverMatchesItsNrrdAndItsCtSlices)
{
  const auto seg = this->Import("dcmqi/liver.dcm");
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_EQ(seg[0].Name, "Liver");
  EXPECT_EQ(seg[0].Type.Meaning, "Liver");
  EXPECT_EQ(vp::VesselLabelTable::Default().ClassOf(seg[0]), "liver");
  ExpectGeometry(seg[0], { 512, 512, 3 }, { -235.2, -226.8, -128.69 }, { 0.810547, 0.810547, 1.0 });

  // The same liver as dcmqi's NRRD (read by ITK, not by us): voxel for voxel.
  const auto nrrd = this->Import("dcmqi/liver_seg.nrrd");
  ASSERT_EQ(nrrd.size(), 1u);
  const std::size_t voxels = CountInside(seg[0]);
  EXPECT_GT(voxels, 100000u);
  EXPECT_EQ(CountInside(nrrd[0]), voxels);
  EXPECT_EQ(CountBoth(seg[0], nrrd[0]), voxels);

  // Each slice lies where a CT slice it segments lies (the CT's file names run against z).
  std::vector<double> ctZ;
  for (int n = 1; n <= 3; ++n)
  {
    DcmFileFormat ct;
    const std::string file = this->Data + "/dcmqi/ct-3slice_0" + std::to_string(n) + ".dcm";
    ASSERT_TRUE(ct.loadFile(file.c_str()).good()) << file;
    Float64 z = 0;
    ASSERT_TRUE(ct.getDataset()->findAndGetFloat64(DCM_ImagePositionPatient, z, 2).good());
    ctZ.push_back(z);
  }
  std::sort(ctZ.begin(), ctZ.end());
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(seg[0].Grid.IjkToLps[11] + k * seg[0].Grid.IjkToLps[10], ctZ[k], 1e-3) << "slice " << k;
}

TEST_F(DicomSegImport, DcmqiPartialOverlapsKeepsFiveSegmentsAndTheirOverlaps)
{
  const auto seg = this->Import("dcmqi/partial_overlaps.dcm");
  EXPECT_EQ(Names(seg), (std::vector<std::string>{ "GREEN", "ORANGE", "PURPLE", "LIGHT_BLUE", "DARK_BLUE" }));
  ASSERT_EQ(seg.size(), 5u);
  EXPECT_EQ(seg[1].Type.Key(), "SCT:51114001"); // Artery
  EXPECT_EQ(seg[4].Type.Meaning, "Vein");
  for (const auto& s : seg)
    ExpectGeometry(s, { 512, 512, 3 }, { -235.2, -226.8, -128.69 }, { 0.810547, 0.810547, 1.0 });
  // Its 7 frames over 3 positions: Tissue and Artery only on the middle slice, Capillary on all
  // three, Edema and Vein on the lowest.
  EXPECT_EQ(CountInside(seg[0]), CountInside(seg[0], 1));
  EXPECT_EQ(CountInside(seg[1]), CountInside(seg[1], 1));
  EXPECT_GT(CountInside(seg[2], 0), 0u);
  EXPECT_GT(CountInside(seg[2], 2), 0u);
  EXPECT_EQ(CountInside(seg[3]), CountInside(seg[3], 0));
  EXPECT_NE(seg[0].Grid.Labels, seg[1].Grid.Labels) << "each segment has its own voxels";
  std::size_t overlapping = 0;
  for (std::size_t a = 0; a < seg.size(); ++a)
    for (std::size_t b = a + 1; b < seg.size(); ++b)
      overlapping += CountBoth(seg[a], seg[b]);
  EXPECT_GT(overlapping, 0u) << "overlaps are kept, not resolved into one label";
}

TEST_F(DicomSegImport, LabelMapClassSharesOneGridAndLeavesMissingSlicesEmpty)
{
  const auto seg = this->Import("dcmqi/sparse-labelmap-ppv5.dcm");
  ASSERT_EQ(seg.size(), 1u) << "segment 0 is the background, not a structure";
  EXPECT_EQ(seg[0].Name, "Liver");
  EXPECT_EQ(seg[0].LabelValue, 1);
  EXPECT_EQ(seg[0].Type.Key(), "SCT:10200004");
  EXPECT_EQ(vp::VesselLabelTable::Default().ClassOf(seg[0]), "liver");
  // Two frames 5 mm apart on a 2.5 mm grid: three slices, the middle one absent from the file.
  ExpectGeometry(seg[0], { 24, 38, 3 }, { 46.464901, 5.0188098, -177.75 }, { 0.7, 0.7, 2.5 });
  EXPECT_GT(CountInside(seg[0], 0), 0u);
  EXPECT_EQ(CountInside(seg[0], 1), 0u);
  EXPECT_GT(CountInside(seg[0], 2), 0u);
}

TEST_F(DicomSegImport, SrExampleAndDcmjsTumourSegmentsSitOnTheirFrames)
{
  const auto sr = this->Import("dcmqi/sr-example_seg.dcm");
  ASSERT_EQ(sr.size(), 1u);
  EXPECT_EQ(sr[0].Name, "Neoplasm, Primary");
  ExpectGeometry(sr[0], { 128, 128, 13 }, { -226.411, -430.789, -119.271 }, { 3.537818, 3.537818, 3.375 });

  const auto tumour = this->Import("dcmjs/tumor_User1_Manual_Trial1.dcm");
  EXPECT_EQ(Names(tumour), (std::vector<std::string>{ "Neoplasm, Primary", "Neoplasm, Secondary" }));
  ASSERT_EQ(tumour.size(), 2u);
  // Both segments share one slice grid, from the lowest frame of either (segment 2's, at
  // z = -432.584) to the highest (-405.584): 9 slices; segment 1 covers slices 2 to 5 only. The
  // voxel counts per frame are the set bits of each packed frame.
  for (const auto& s : tumour)
    ExpectGeometry(s, { 128, 128, 9 }, { -226.132, -425.884, -432.584 }, { 3.537818, 3.537818, 3.375 });
  EXPECT_EQ(CountInside(tumour[0], 2), 11u);
  EXPECT_EQ(CountInside(tumour[0], 5), 15u);
  EXPECT_EQ(CountInside(tumour[0]), 11u + 12u + 16u + 15u);
  EXPECT_EQ(CountInside(tumour[1], 0), 5u);
  EXPECT_EQ(CountInside(tumour[1], 8), 13u);
  EXPECT_EQ(CountInside(tumour[1]), 212u);
}

TEST_F(DicomSegImport, HighdicomFractionalEqualsItsBinaryTwinAtHalf)
{
  const auto binary = this->Import("highdicom/seg_image_ct_binary.dcm");
  const auto fractional = this->Import("highdicom/seg_image_ct_binary_fractional.dcm");
  ASSERT_EQ(binary.size(), 1u);
  ASSERT_EQ(fractional.size(), 1u);
  EXPECT_EQ(binary[0].Name, "first segment");
  EXPECT_EQ(binary[0].Type.Meaning, "Bone");
  ExpectGeometry(binary[0], { 16, 16, 3 }, { -125, -128.1, 103.02 }, { 0.488281, 0.488281, 1.25 });
  ExpectGeometry(fractional[0], { 16, 16, 3 }, { -125, -128.1, 103.02 }, { 0.488281, 0.488281, 1.25 });
  const std::size_t voxels = CountInside(binary[0]);
  EXPECT_EQ(voxels, 127u + 256u + 255u);
  EXPECT_EQ(CountInside(fractional[0]), voxels);
  EXPECT_EQ(CountBoth(binary[0], fractional[0]), voxels);
}

TEST_F(DicomSegImport, HighdicomOverlapKeepsBothSegmentsAcrossAGapOfEmptySlices)
{
  const auto seg = this->Import("highdicom/seg_image_ct_binary_overlap.dcm");
  EXPECT_EQ(Names(seg), (std::vector<std::string>{ "first segment", "second segment" }));
  ASSERT_EQ(seg.size(), 2u);
  // Frames at z = -99.48 and 103.02 to 105.52 mm, 1.25 mm apart: 165 slices, 161 of them empty.
  ExpectGeometry(seg[0], { 16, 16, 165 }, { -125, -128.1, -99.48 }, { 0.488281, 0.488281, 1.25 });
  for (int k : { 0, 162, 163, 164 })
    EXPECT_EQ(CountInside(seg[0], k), 16u) << "slice " << k;
  EXPECT_EQ(CountInside(seg[0]), 64u);
  EXPECT_EQ(CountInside(seg[1]), 16u);
  EXPECT_EQ(CountBoth(seg[0], seg[1]), 16u) << "the second segment lies inside the first";
}

TEST_F(DicomSegImport, AFolderHoldingASegAsksForTheFile)
{
  const std::string folder = vp::test::MakeTempDir("segfolder");
  std::filesystem::copy_file(this->Data + "/dcmqi/liver.dcm", folder + "/liver.dcm");
  try
  {
    vp::ImportSegmentation(folder, nullptr);
    ADD_FAILURE() << "a folder holding a SEG was read as a series";
  }
  catch (const vp::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("liver.dcm): a DICOM SEG file: give the file itself"), std::string::npos)
      << e.what();
  }
}

TEST_F(DicomSegImport, ImagesAreNotSegmentations)
{
  for (const auto& [file, sopClass] : std::vector<std::pair<std::string, std::string>>{
         { "highdicom/ct_image.dcm", "CTImageStorage" },
         { "dcmqi/23x38x3_multiframe_mf.dcm", "LegacyConvertedEnhancedCTImageStorage" } })
  {
    const std::string path = this->Data + "/" + file;
    try
    {
      vp::ImportSegmentation(path, nullptr);
      ADD_FAILURE() << path << " was imported";
    }
    catch (const vp::InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(path + ": a single DICOM " + sopClass + " object, not a segmentation"),
        std::string::npos)
        << e.what();
    }
  }
}
} // namespace
