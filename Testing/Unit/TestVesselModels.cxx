// Segmentation import and vessel model building: synthetic shapes with a known answer, the
// IRCADb patients against the data set's own meshes, and the real NRRD and NIfTI files.
#include "vpDicomLabelSeriesWriter.h"
#include "vpInputError.h"
#include "vpModelTestSupport.h"
#include "vpSegmentationImport.h"
#include "vpTestSupport.h"
#include "vpVesselLabelTable.h"
#include "vpVesselModelSet.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselModelBuilder.h"

#include <gtest/gtest.h>

#include <vtkMassProperties.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>

namespace
{
using vp::test::MakeGrid;

constexpr double Pi = 3.14159265358979323846;

// A rotated, anisotropic grid away from the origin: what a real scanner gives.
std::array<double, 16> ObliqueGrid(const double spacing[3], const double origin[3])
{
  const double c = std::cos(Pi / 6), s = std::sin(Pi / 6);
  const double axes[3][3] = { { c, s, 0 }, { -s, c, 0 }, { 0, 0, 1 } };
  std::array<double, 16> m{};
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
      m[4 * r + k] = axes[k][r] * spacing[k];
    m[4 * r + 3] = origin[r];
  }
  m[15] = 1;
  return m;
}

const vp::LabelStructure* Find(const vp::LabelStructures& all, const std::string& name)
{
  for (const auto& s : all)
    if (s.Name == name)
      return &s;
  return nullptr;
}

TEST(VesselModels, SyntheticSphereAndTubeThroughADicomSeries)
{
  // Sphere (label 1) and a tube with round ends (label 2; a vessel has no sharp rim, which
  // smoothing would round off), as one multi-label DICOM series whose file names run against
  // the slice order.
  const double spacing[3] = { 0.7, 0.8, 1.5 }, origin[3] = { -120.25, 37.5, -400.0 };
  const int dims[3] = { 90, 80, 40 };
  const auto m = ObliqueGrid(spacing, origin);
  auto at = [&](double i, double j, double k, int r) { return m[4 * r] * i + m[4 * r + 1] * j + m[4 * r + 2] * k + m[4 * r + 3]; };
  const double centre[3] = { at(30, 40, 20, 0), at(30, 40, 20, 1), at(30, 40, 20, 2) };
  const double radius = 13.0;
  const double axisPoint[3] = { at(68, 40, 20, 0), at(68, 40, 20, 1), at(68, 40, 20, 2) };
  const double tubeRadius = 4.0, halfLength = 20.0; // along z (the slice normal)
  auto sphereGap = [&](const double p[3]) {
    return std::sqrt(std::pow(p[0] - centre[0], 2) + std::pow(p[1] - centre[1], 2) + std::pow(p[2] - centre[2], 2)) - radius;
  };
  auto tubeGap = [&](const double p[3]) { // signed distance to the capsule
    const double z = std::max(0.0, std::abs(p[2] - axisPoint[2]) - halfLength);
    return std::sqrt(std::pow(p[0] - axisPoint[0], 2) + std::pow(p[1] - axisPoint[1], 2) + z * z) - tubeRadius;
  };
  const vp::LabelGrid written = MakeGrid(dims, m, [&](const double p[3]) { return sphereGap(p) <= 0 ? 1 : tubeGap(p) <= 0 ? 2 : 0; });
  std::vector<int> order(dims[2]);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  const std::string folder = vp::test::MakeTempDir("synthetic_series") + "/labels";
  vp::DicomLabelSeriesWriter::Write(written, folder, "synthetic", order);

  const vp::LabelStructures read = vp::ImportSegmentation(folder, nullptr);
  ASSERT_EQ(read.size(), 2u);
  const vp::LabelStructure* sphere = Find(read, "label 1");
  const vp::LabelStructure* tube = Find(read, "label 2");
  ASSERT_TRUE(sphere && tube);
  EXPECT_EQ(sphere->LabelValue, 1);
  EXPECT_EQ(tube->LabelValue, 2);
  for (int i = 0; i < 16; ++i)
    EXPECT_NEAR(sphere->Grid.IjkToLps[i], m[i], 1e-6) << "matrix element " << i;

  struct Case
  {
    const vp::LabelStructure* Structure;
    std::function<double(const double*)> Gap;
    double Volume;
  };
  const Case cases[] = { { sphere, sphereGap, 4.0 / 3.0 * Pi * radius * radius * radius },
    { tube, tubeGap, Pi * tubeRadius * tubeRadius * (2 * halfLength + 4.0 / 3.0 * tubeRadius) } };
  const double halfVoxel = 0.5 * 1.5;
  for (const Case& c : cases)
  {
    vtkNew<vtkVesselModelBuilder> builder;
    auto surface = builder->Build({ c.Structure });
    EXPECT_EQ(vp::test::OpenEdges(surface), 0) << c.Structure->Name;
    double worst = 0.0, sum = 0.0;
    for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
    {
      const double gap = std::abs(c.Gap(surface->GetPoint(i)));
      worst = std::max(worst, gap);
      sum += gap;
    }
    const double volume = vp::test::SignedVolume(surface);
    std::cout << c.Structure->Name << ": largest distance from the shape " << worst << " mm, mean "
              << sum / surface->GetNumberOfPoints() << " mm, volume " << volume << " (analytic " << c.Volume << ")\n";
    EXPECT_LE(worst, halfVoxel) << "the surface lies where the shape is, within half a voxel";
    EXPECT_NEAR(volume, c.Volume, 0.03 * c.Volume) << "positive: the triangles face outward";
  }
}

TEST(VesselModels, ReflectedGridStillGivesOutwardNormals)
{
  // A left-handed index-to-LPS matrix (slices stacked against the normal) mirrors the winding.
  std::array<double, 16> m{ 1, 0, 0, 5, 0, 1, 0, -3, 0, 0, -2, 40, 0, 0, 0, 1 };
  const int dims[3] = { 30, 30, 20 };
  const vp::LabelGrid grid = MakeGrid(dims, m, [](const double p[3]) {
    return std::pow(p[0] - 20, 2) + std::pow(p[1] - 12, 2) + std::pow(p[2] - 20, 2) < 64.0 ? 1 : 0;
  });
  vp::LabelStructure s;
  s.Name = "ball";
  s.Source = "synthetic";
  s.Grid = grid;
  vtkNew<vtkVesselModelBuilder> builder;
  auto surface = builder->Build({ &s });
  EXPECT_GT(vp::test::SignedVolume(surface), 0.9 * 4.0 / 3.0 * Pi * 512);
}

TEST(VesselModels, ACavitysWallFacesIntoTheCavity)
{
  // A hollow ball (radii 9 and 5 voxels): the solid's surface is two closed pieces, and the inner
  // one must face into the hole, or the enclosed volume reads outer + inner instead of the shell.
  // An orientation per piece from its own leftmost point (vtkPolyDataNormals' auto-orientation,
  // used before) turns both outward: 3,634 mm³ here instead of 2,550 (analytic 2,530).
  std::array<double, 16> m{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1 }; // reflecting, too
  const int dims[3] = { 26, 26, 26 };
  const vp::LabelGrid grid = MakeGrid(dims, m, [](const double p[3]) {
    const double r2 = std::pow(p[0] - 12.5, 2) + std::pow(p[1] - 12.5, 2) + std::pow(p[2] + 12.5, 2);
    return r2 < 81.0 && r2 > 25.0 ? 1 : 0;
  });
  vp::LabelStructure s;
  s.Name = "shell";
  s.Source = "synthetic";
  s.Grid = grid;
  vtkNew<vtkVesselModelBuilder> builder;
  builder->SetSmoothingFactor(0.0);
  auto surface = builder->Build({ &s });
  const double shell = 4.0 / 3.0 * Pi * (729.0 - 125.0);
  std::cout << "shell: enclosed " << vp::test::SignedVolume(surface) << " mm3 (analytic " << shell << ")\n";
  EXPECT_NEAR(vp::test::SignedVolume(surface), shell, 0.06 * shell);
  EXPECT_EQ(vp::test::OpenEdges(surface), 0);
}

TEST(VesselModels, LabelTableKnowsOurDataAndListsTheRest)
{
  const auto table = vp::VesselLabelTable::Default();
  EXPECT_EQ(table.ClassOfName("portalvein"), "portal_vein");
  EXPECT_EQ(table.ClassOfName("portalvein1"), "portal_vein");
  EXPECT_EQ(table.ClassOfName("venoussystem"), "hepatic_vein");
  EXPECT_EQ(table.ClassOfName("venacava"), "hepatic_vein");
  EXPECT_EQ(table.ClassOfName("Hepatic_Artery"), "hepatic_artery");
  EXPECT_EQ(table.ClassOfName("artery"), "hepatic_artery");
  EXPECT_EQ(table.ClassOfName("liver"), "liver");
  EXPECT_EQ(table.ClassOfName("bone"), "");
  vp::LabelStructure coded;
  coded.Name = "Segment 3";
  coded.Type = { "SCT", "32764006", "Portal vein" };
  EXPECT_EQ(table.ClassOf(coded), "portal_vein");
  vp::LabelStructure unnamed;
  unnamed.Name = "label 63";
  unnamed.LabelValue = 63;
  EXPECT_EQ(table.ClassOf(unnamed), "hepatic_vein"); // TotalSegmentator's inferior vena cava
  unnamed.Name = "label 52";
  unnamed.LabelValue = 52;
  EXPECT_EQ(table.ClassOf(unnamed), ""); // its aorta: not a liver vessel
  EXPECT_THROW(vp::VesselLabelTable::Parse("{\"classes\": [{\"class\": \"a\", \"names\": [\"x\"]},"
                                           " {\"class\": \"b\", \"names\": [\"X\"]}]}", "t.json"),
    vp::InputError);
  EXPECT_THROW(vp::VesselLabelTable::Parse("[1, 2", "t.json"), vp::InputError);
}

// ---- Real data -------------------------------------------------------------------------------

class IrcadbModels : public ::testing::TestWithParam<const char*>
{
};

TEST_P(IrcadbModels, EveryClassFoundAndCloseToTheDataSetsMeshes)
{
  const std::string root = vp::test::ExtractedDataDir() + "/ircadb/" + GetParam();
  if (vp::test::ExtractedDataDir().empty() || !vp::test::FileExists(root + "/MASKS_DICOM/.extracted"))
  {
    GTEST_SKIP() << "IRCADb masks not extracted (set VP_TEST_DATA to ../shared/data and re-run cmake)";
  }
  const auto table = vp::VesselLabelTable::Default();
  const vp::LabelStructures structures =
    vp::ImportSegmentation(root + "/MASKS_DICOM", [&](const std::string& n) { return !table.ClassOfName(n).empty(); });
  std::map<std::string, std::vector<const vp::LabelStructure*>> byClass;
  for (const auto& s : structures)
    if (s.Grid.Labels)
      byClass[table.ClassOf(s)].push_back(&s);
  const std::map<std::string, std::string> reference = { { "portal_vein", "portalvein.vtk" },
    { "hepatic_vein", "venoussystem.vtk" }, { "hepatic_artery", "artery.vtk" }, { "liver", "liver.vtk" } };
  for (const auto& [cls, file] : reference)
  {
    ASSERT_TRUE(byClass.count(cls)) << cls << " not found in " << root;
    vtkNew<vtkVesselModelBuilder> builder;
    auto ours = builder->Build(byClass[cls]);
    EXPECT_EQ(vp::test::OpenEdges(ours), 0) << cls << ": closed";

    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(root + "/MESHES_VTK/" + file);
    reader->Read();
    // The data set's meshes sit half a voxel further along every axis (voxel-corner frame).
    const vp::LabelGrid& grid = byClass[cls].front()->Grid;
    vtkNew<vtkTransform> shift;
    shift->Translate(-0.5 * grid.SpacingMm(0), -0.5 * grid.SpacingMm(1), -0.5 * grid.SpacingMm(2));
    vtkNew<vtkTransformPolyDataFilter> shifted;
    shifted->SetInputData(reader->GetOutput());
    shifted->SetTransform(shift);
    shifted->Update();
    // Their meshes are open where a vessel leaves the first or last slice; ours is closed there by
    // a cap beyond the slice centre, which has no counterpart in theirs and is left out.
    const double firstZ = grid.IjkToLps[11], lastZ = firstZ + grid.IjkToLps[10] * (grid.Labels->GetDimensions()[2] - 1);
    const auto distances = vp::test::SymmetricSurfaceDistances(
      ours, shifted->GetOutput(), [&](const double p[3]) { return p[2] >= firstZ && p[2] <= lastZ; });
    const double mean = vp::test::Mean(distances), p95 = vp::test::Percentile(distances, 0.95);
    vtkNew<vtkMassProperties> theirs;
    theirs->SetInputData(shifted->GetOutput());
    const double ourVolume = vp::test::SignedVolume(ours), theirVolume = theirs->GetVolume();
    std::cout << GetParam() << " " << cls << ": mean surface distance " << mean << " mm, 95th percentile " << p95
              << " mm, volume " << ourVolume << " mm3 (reference " << theirVolume << ")\n";
    EXPECT_LE(mean, 0.55) << cls;
    EXPECT_LE(p95, 1.6) << cls;
    EXPECT_GT(ourVolume, 0.0) << cls << ": triangles face outward";
    if (cls == "liver")
    {
      EXPECT_NEAR(ourVolume, theirVolume, 0.02 * theirVolume);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Patients, IrcadbModels, ::testing::Values("3Dircadb1.1", "3Dircadb1.4"));

TEST(VesselModels, LabelTableFindsTumoursByTheirNamesAndCodes)
{
  const auto table = vp::VesselLabelTable::Default();
  for (const char* name : { "livertumor01", "livertumor", "Tumor 2", "liver_tumour_3", "metastasis-1", "Lesion", "HCC",
         "Liver metastases 4" })
  {
    EXPECT_EQ(table.ClassOfName(name), "tumour") << name;
  }
  // Not the liver's tumours: a cyst (not resected with a margin), IRCADb's adrenal tumours (its
  // patient 5's leftsurretumor), a resection cavity (patient 14's metastasectomie), a thrombus.
  for (const char* name : { "liverkyst", "leftsurretumor", "rightsurretumor", "metastasectomie", "portal vein tumor thrombus" })
  {
    EXPECT_EQ(table.ClassOfName(name), "") << name;
  }
  EXPECT_EQ(table.ClassOfName("portal vein 2"), "portal_vein") << "a numbered name";
  EXPECT_EQ(table.RoleOf("tumour"), vp::ModelRole::Tumour);
  EXPECT_EQ(table.RoleOf("portal_vein"), vp::ModelRole::Vessel);
  EXPECT_EQ(table.RoleOf("liver"), vp::ModelRole::Liver);
  vp::LabelStructure coded;
  coded.Name = "Segment_4";
  coded.Type = { "SCT", "108369006", "Neoplasm" };
  EXPECT_EQ(table.ClassOf(coded), "tumour");
  // A table of the user's own: a role by name, and words too short to mean anything refused.
  const auto own = vp::VesselLabelTable::Parse(
    R"({"classes": [{"class": "lesion", "role": "tumour", "name_contains": ["nodule"]}, {"class": "pv", "names": ["pv"]}]})", "own.json");
  EXPECT_EQ(own.ClassOfName("Nodule 3"), "lesion");
  EXPECT_EQ(own.RoleOf("lesion"), vp::ModelRole::Tumour);
  EXPECT_EQ(own.RoleOf("pv"), vp::ModelRole::Vessel);
  EXPECT_THROW(vp::VesselLabelTable::Parse(R"({"classes": [{"class": "t", "name_contains": ["tu"]}]})", "t.json"), vp::InputError);
  EXPECT_THROW(vp::VesselLabelTable::Parse(R"({"classes": [{"class": "t", "role": "organ"}]})", "t.json"), vp::InputError);
}

// Patient 1's tumours are seven masks (livertumor01..07): one closed model each, named after
// its mask, on the data set's own mesh of it within a voxel; patient 4's are one mask of eight
// separate tumours: one model per piece, largest first.
TEST(VesselModels, IrcadbTumoursBecomeOneClosedModelEachCloseToTheDataSetsMeshes)
{
  const std::string root = vp::test::ExtractedDataDir() + "/ircadb/";
  if (vp::test::ExtractedDataDir().empty() || !vp::test::FileExists(root + "3Dircadb1.1/MASKS_DICOM/.extracted"))
  {
    GTEST_SKIP() << "IRCADb masks not extracted (set VP_TEST_DATA to ../shared/data and re-run cmake)";
  }
  vp::VesselModelParameters parameters;
  parameters.Classes = { "tumour" };
  const vp::VesselModelSet p1 = vp::BuildVesselModels({ root + "3Dircadb1.1/MASKS_DICOM" }, parameters, [](const std::string&, double) {});
  ASSERT_EQ(p1.Models.size(), 7u);
  for (std::size_t i = 0; i < p1.Models.size(); ++i)
  {
    const vp::VesselClassModel& m = p1.Models[i];
    char mask[32];
    std::snprintf(mask, sizeof mask, "livertumor%02zu", i + 1);
    char id[32];
    std::snprintf(id, sizeof id, "tumour_%02zu", i + 1);
    EXPECT_EQ(m.Name, id);
    EXPECT_EQ(m.DisplayName, std::string("tumour ") + (id + 7) + " (" + mask + ")");
    EXPECT_EQ(m.Role, vp::ModelRole::Tumour);
    EXPECT_EQ(vp::test::OpenEdges(m.Surface), 0) << id << ": closed";
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(root + "3Dircadb1.1/MESHES_VTK/" + mask + ".vtk");
    reader->Read();
    const vp::LabelGrid& grid = m.Structures.front()->Grid;
    vtkNew<vtkTransform> shift; // the data set's voxel-corner frame, as for the vessels
    shift->Translate(-0.5 * grid.SpacingMm(0), -0.5 * grid.SpacingMm(1), -0.5 * grid.SpacingMm(2));
    vtkNew<vtkTransformPolyDataFilter> shifted;
    shifted->SetInputData(reader->GetOutput());
    shifted->SetTransform(shift);
    shifted->Update();
    const auto distances = vp::test::SymmetricSurfaceDistances(m.Surface, shifted->GetOutput(), [](const double*) { return true; });
    const double voxel = std::max({ grid.SpacingMm(0), grid.SpacingMm(1), grid.SpacingMm(2) });
    const double p95 = vp::test::Percentile(distances, 0.95);
    std::cout << id << " (" << mask << "): mean surface distance " << vp::test::Mean(distances) << " mm, 95th percentile "
              << p95 << " mm, largest " << *std::max_element(distances.begin(), distances.end()) << " mm (voxel " << voxel
              << " mm), volume " << m.VolumeMm3 << " mm3 of " << m.Voxels << " voxels\n";
    const double diagonal = std::hypot(grid.SpacingMm(0), grid.SpacingMm(1), grid.SpacingMm(2));
    EXPECT_LE(p95, voxel) << id;
    EXPECT_LE(*std::max_element(distances.begin(), distances.end()), diagonal) << id << ": every point within a voxel";
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_GT(m.CentroidMm[k], m.BoundsMm[2 * k]) << id;
      EXPECT_LT(m.CentroidMm[k], m.BoundsMm[2 * k + 1]) << id;
    }
  }
  const vp::VesselModelSet p4 = vp::BuildVesselModels({ root + "3Dircadb1.4/MASKS_DICOM" }, parameters, [](const std::string&, double) {});
  ASSERT_EQ(p4.Models.size(), 8u);
  for (std::size_t i = 0; i < p4.Models.size(); ++i)
  {
    EXPECT_EQ(p4.Models[i].DisplayName.substr(10), "(livertumor, piece " + std::to_string(i + 1) + " of 8)");
    EXPECT_EQ(vp::test::OpenEdges(p4.Models[i].Surface), 0);
    if (i > 0)
    {
      EXPECT_LE(p4.Models[i].Voxels, p4.Models[i - 1].Voxels) << "largest first";
    }
  }
  const nlohmann::json doc = vp::VesselModelsJson(p4);
  EXPECT_EQ(doc["structures"][2]["id"], "tumour_03");
  EXPECT_EQ(doc["structures"][2]["role"], "tumour");
  EXPECT_EQ(doc["structures"][2]["file"], "tumour_03.stl");
  EXPECT_EQ(doc["structures"][2]["bounds_mm"].size(), 6u);
  EXPECT_EQ(doc["structures"][2]["centroid_mm"].size(), 3u);
  EXPECT_EQ(doc["structures"][2]["centroid"], doc["structures"][2]["centroid_mm"]) << "the design's name too";
  EXPECT_EQ(doc["structures"][2]["bounds"], doc["structures"][2]["bounds_mm"]);
  EXPECT_EQ(doc["structures"][2]["voxels"], p4.Models[2].Voxels);
}

// The geometry a NRRD header states, read without ITK.
std::array<double, 16> NrrdHeaderGeometry(const std::string& file, int sizes[3])
{
  std::ifstream in(file, std::ios::binary);
  std::array<double, 16> m{};
  m[15] = 1;
  for (std::string line; std::getline(in, line) && !line.empty();)
  {
    for (char& c : line)
      if (c == '(' || c == ')' || c == ',')
        c = ' ';
    std::istringstream fields(line.substr(line.find(':') + 1));
    if (line.rfind("sizes:", 0) == 0)
      fields >> sizes[0] >> sizes[1] >> sizes[2];
    else if (line.rfind("space directions:", 0) == 0)
      for (int c = 0; c < 3; ++c)
        fields >> m[c] >> m[4 + c] >> m[8 + c];
    else if (line.rfind("space origin:", 0) == 0)
      fields >> m[3] >> m[7] >> m[11];
  }
  return m;
}

TEST(VesselModels, NrrdFilesImportWithTheirHeadersGeometry)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: no real NRRD files";
  for (const char* name : { "liver_seg.nrrd", "liver_spine_seg.nrrd" })
  {
    const std::string file = data + "/dcmqi/" + name;
    int sizes[3] = {};
    const auto expected = NrrdHeaderGeometry(file, sizes);
    const auto structures = vp::ImportSegmentation(file, nullptr);
    ASSERT_FALSE(structures.empty()) << file;
    int dims[3];
    structures.front().Grid.Labels->GetDimensions(dims);
    EXPECT_EQ(std::vector<int>(dims, dims + 3), std::vector<int>(sizes, sizes + 3)) << file;
    for (int i = 0; i < 16; ++i)
      EXPECT_NEAR(structures.front().Grid.IjkToLps[i], expected[i], 1e-5) << file << " matrix element " << i;
    std::cout << name << ": " << structures.size() << " structure(s), first " << structures.front().Name << "\n";
  }
  EXPECT_EQ(vp::ImportSegmentation(data + "/dcmqi/liver_seg.nrrd", nullptr).size(), 1u);
  EXPECT_EQ(vp::ImportSegmentation(data + "/dcmqi/liver_spine_seg.nrrd", nullptr).size(), 2u);
}

TEST(VesselModels, NiftiLabelmapsImportWithTheirHeadersGeometryAndTotalSegmentatorLabels)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: no real NIfTI files";
  const std::string file = data + "/totalsegmentator/example_seg_dicom.nii.gz";
  // The header's sform (RAS), read with zlib; LPS flips the first two rows.
  gzFile gz = gzopen(file.c_str(), "rb");
  ASSERT_TRUE(gz);
  unsigned char header[348];
  ASSERT_EQ(gzread(gz, header, sizeof header), 348);
  gzclose(gz);
  short sformCode;
  std::memcpy(&sformCode, header + 254, 2);
  ASSERT_GT(sformCode, 0) << "this file places itself by its sform";
  float srow[12];
  std::memcpy(srow, header + 280, sizeof srow);
  const auto structures = vp::ImportSegmentation(file, nullptr);
  ASSERT_FALSE(structures.empty());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(structures.front().Grid.IjkToLps[4 * r + c], (r < 2 ? -1.0 : 1.0) * srow[4 * r + c], 1e-4)
        << "row " << r << " column " << c;
  const auto table = vp::VesselLabelTable::Default();
  std::map<std::string, int> classes;
  for (const auto& s : structures)
    ++classes[table.ClassOf(s)];
  EXPECT_EQ(classes["liver"], 1);
  EXPECT_EQ(classes["portal_vein"], 1);
  EXPECT_EQ(classes["hepatic_vein"], 1);
  EXPECT_GE(classes[""], 1) << "the aorta is listed as unknown";
}

// A Slicer segmentation file written by hand: two overlapping segments in two layers.
TEST(VesselModels, SlicerSegNrrdKeepsNamesLayersAndTerminology)
{
  const std::string file = vp::test::MakeTempDir("segnrrd") + "/vessels.seg.nrrd";
  {
    std::ofstream out(file, std::ios::binary);
    out << "NRRD0004\ntype: unsigned char\ndimension: 4\nspace: left-posterior-superior\n"
           "sizes: 2 4 3 2\nspace directions: none (0.5,0,0) (0,0.5,0) (0,0,2)\n"
           "kinds: list domain domain domain\nencoding: raw\nspace origin: (10,20,30)\n"
           "Segment0_Name:=Portal vein\nSegment0_LabelValue:=1\nSegment0_Layer:=0\n"
           "Segment0_Terminology:=Segmentation category and type - 3D Slicer General Anatomy list~SCT^123037004^Anatomical Structure~SCT^32764006^Portal vein~^^~Anatomic codes - DICOM master list~^^~^^\n"
           "Segment1_Name:=Vessel overlap\nSegment1_LabelValue:=3\nSegment1_Layer:=1\n\n";
    for (int v = 0; v < 24; ++v)
    {
      out.put(static_cast<char>(v % 2 == 0 ? 1 : 0)); // layer 0: segment 0 everywhere
      out.put(static_cast<char>(v < 12 ? 3 : 0));     // layer 1: segment 1 in the first half, overlapping
    }
  }
  const auto structures = vp::ImportSegmentation(file, nullptr);
  ASSERT_EQ(structures.size(), 2u);
  EXPECT_EQ(structures[0].Name, "Portal vein");
  EXPECT_EQ(structures[0].Type.Key(), "SCT:32764006");
  EXPECT_EQ(structures[1].Name, "Vessel overlap");
  EXPECT_EQ(structures[1].LabelValue, 3);
  EXPECT_NE(structures[0].Grid.Labels, structures[1].Grid.Labels) << "layers stay apart";
  EXPECT_NEAR(structures[0].Grid.IjkToLps[3], 10.0, 1e-9);
  EXPECT_NEAR(structures[0].Grid.IjkToLps[10], 2.0, 1e-9);
  EXPECT_EQ(vp::VesselLabelTable::Default().ClassOf(structures[0]), "portal_vein");
}

// Segment keys whose numbers do not parse are refused as bad input; found by the NRRD fuzz
// target, where a 70-digit segment index once escaped as std::out_of_range.
TEST(VesselModels, SlicerSegNrrdWithBadSegmentNumbersIsRefused)
{
  const std::string dir = vp::test::MakeTempDir("segnrrdbad");
  auto refusal = [&](const std::string& key) -> std::string {
    const std::string file = dir + "/bad.seg.nrrd";
    {
      std::ofstream out(file, std::ios::binary);
      out << "NRRD0004\ntype: unsigned char\ndimension: 3\nspace: left-posterior-superior\n"
             "sizes: 2 2 2\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n"
          << key << "\n\n";
      out << std::string(8, '\1');
    }
    try
    {
      vp::ImportSegmentation(file, nullptr);
    }
    catch (const vp::InputError& e)
    {
      return e.what();
    }
    return "imported";
  };
  EXPECT_NE(refusal("Segment0_Name:=a\nSegment" + std::string(70, '1') + "_Layer:=0").find("out of range"),
    std::string::npos);
  EXPECT_NE(refusal("Segment0_LabelValue:=3abc").find("not a whole number: '3abc'"), std::string::npos);
  EXPECT_NE(refusal("Segment0_Layer:=99999999999").find("not a whole number"), std::string::npos);
  EXPECT_EQ(refusal("Segment0_LabelValue:=1"), "imported");
}
} // namespace
