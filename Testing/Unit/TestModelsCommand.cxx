// `vesselproximity models` end to end: the files it writes, and for each bad input the one-line
// error that names it, a non-zero exit and nothing written.
#include "vpDicomLabelSeriesWriter.h"
#include "vpModelTestSupport.h"
#include "vpSegmentationImport.h"
#include "vpStlFormat.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include <fcntl.h>
#include <zlib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using vp::test::RunTool;
using vp::test::ToolRun;
namespace fs = std::filesystem;

// Structure folders as IRCADb lays them out: a tube "portalvein", a ball "venacava", a "bone".
class ModelsCommand : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("models");
    this->Masks = this->Dir + "/MASKS_DICOM";
    this->Geometry = { 0.8, 0, 0, -50, 0, 0.8, 0, 20, 0, 0, 1.25, -100, 0, 0, 0, 1 };
    this->WriteMask("portalvein", [](const double p[3]) { return std::hypot(p[0] + 30, p[1] - 40) < 5 ? 255 : 0; });
    this->WriteMask("venacava", [](const double p[3]) {
      return std::pow(p[0] + 25, 2) + std::pow(p[1] - 30, 2) + std::pow(p[2] + 85, 2) < 36 ? 1 : 0; });
    this->WriteMask("bone", [](const double p[3]) { return p[0] > -12 && p[1] > 40 ? 255 : 0; });
  }

  void WriteMask(const std::string& name, const std::function<int(const double p[3])>& label)
  {
    vp::LabelGrid grid = vp::test::MakeGrid(this->Dims, this->Geometry, label);
    grid.Identity = this->Patient; // one patient's structures share a study and a frame of reference
    vp::DicomLabelSeriesWriter::Write(grid, this->Masks + "/" + name, name);
  }

  // The run failed cleanly: exit 1, one line naming what, nothing written.
  void ExpectRefused(const std::string& input, const std::string& names, const std::string& problem)
  {
    const std::string out = this->Dir + "/out_refused";
    const ToolRun r = RunTool(this->Dir, "models " + input + " -o " + out);
    EXPECT_EQ(r.ExitCode, 1) << r.Err;
    // Progress lines ("models: ...") may come first; then exactly one line, the error.
    std::istringstream lines(r.Err);
    int others = 0;
    for (std::string l; std::getline(lines, l);)
      others += l.rfind("models:", 0) == 0 ? 0 : 1;
    EXPECT_EQ(others, 1) << r.Err;
    const std::string line = r.Err.substr(r.Err.find("error:"));
    EXPECT_NE(line.find(names), std::string::npos) << r.Err;
    EXPECT_NE(line.find(problem), std::string::npos) << r.Err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written for " << input;
  }

  std::string Dir, Masks;
  vp::ImageIdentity Patient = vp::DicomLabelSeriesWriter::NewIdentity("");
  int Dims[3] = { 40, 50, 30 };
  std::array<double, 16> Geometry{};
};

TEST_F(ModelsCommand, WritesOneClosedStlPerClassAndListsTheRest)
{
  const std::string out = this->Dir + "/models";
  const ToolRun r = RunTool(this->Dir, "models " + this->Masks + " -o " + out);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  EXPECT_NE(r.Err.find(": 3 structure(s) read in"), std::string::npos) << "progress on stderr: " << r.Err;
  EXPECT_NE(r.Err.find("bone"), std::string::npos) << "unknown structures are named";
  const auto doc = nlohmann::json::parse(vp::test::Slurp(out + "/models.json"));
  EXPECT_EQ(doc["space"], "LPS");
  ASSERT_EQ(doc["structures"].size(), 2u);
  EXPECT_EQ(doc["structures"][0]["class"], "portal_vein");
  EXPECT_EQ(doc["structures"][1]["class"], "hepatic_vein"); // the vena cava belongs there
  EXPECT_EQ(doc["structures"][1]["name"], "venacava");
  ASSERT_EQ(doc["unmapped"].size(), 1u);
  EXPECT_EQ(doc["unmapped"][0]["name"], "bone");
  for (const auto& s : doc["structures"])
  {
    // Flying edges on a padded grid: every model closed, and models.json says so.
    EXPECT_EQ(s["surface"]["closed"], true) << s["name"];
    EXPECT_EQ(s["surface"]["boundary_edges"], 0) << s["name"];
    EXPECT_EQ(s["surface"]["non_manifold_edges"], 0) << s["name"];
    EXPECT_EQ(s["surface"]["triangles"], s["triangles"]) << s["name"];
    const std::string stl = vp::test::Slurp(out + "/" + s["file"].get<std::string>());
    ASSERT_GT(stl.size(), 84u);
    EXPECT_EQ(vp::ParseSpaceTag(stl.substr(0, 80)), vp::MeshSpace::LPS);
    EXPECT_GT(s["triangles"].get<int>(), 100);
    EXPECT_NEAR(s["volume_mm3"].get<double>(), s["voxel_volume_mm3"].get<double>(), 0.15 * s["voxel_volume_mm3"].get<double>());
  }
  // The ball: centre (-25, 30, -85), radius 6 mm -> its volume.
  EXPECT_NEAR(doc["structures"][1]["volume_mm3"].get<double>(), 4.0 / 3.0 * M_PI * 216, 0.1 * 4.0 / 3.0 * M_PI * 216);

  const std::string ras = this->Dir + "/ras";
  ASSERT_EQ(RunTool(this->Dir, "models " + this->Masks + " -o " + ras + " --space RAS").ExitCode, 0);
  EXPECT_EQ(vp::ParseSpaceTag(vp::test::Slurp(ras + "/portal_vein.stl").substr(0, 80)), vp::MeshSpace::RAS);
  EXPECT_EQ(nlohmann::json::parse(vp::test::Slurp(ras + "/models.json"))["space"], "RAS");
}

// A labelmap of one value under a name nobody chose (Slicer hands a CLI its volume as a
// temporary file): a table that names the value makes it that structure (issue 33, item 3); a
// mask of another value stays unmapped, listed.
TEST_F(ModelsCommand, TheModelsBenchLaysEachSeriesEndToEndAndTimesBoth)
{
  const std::string report = this->Dir + "/models_bench.json";
  const ToolRun r =
    RunTool(this->Dir, "bench --engines models --models-input " + this->Masks + " --models-copies 3 --models-runs 1 -o " + report);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto doc = nlohmann::json::parse(vp::test::Slurp(report))["models"];
  EXPECT_EQ(doc["as_given"]["slices"], this->Dims[2]);
  EXPECT_EQ(doc["stacked"]["slices"], 3 * this->Dims[2]) << "three copies, one after another along the normal";
  EXPECT_TRUE(doc["voxels_match"].get<bool>());
  const auto& given = doc["as_given"]["classes"];
  const auto& stacked = doc["stacked"]["classes"];
  ASSERT_EQ(given.size(), 2u);
  ASSERT_EQ(stacked.size(), 2u);
  // The ball comes three times, whole; the tube runs through every slice, so it is three times as
  // long under the same two caps.
  EXPECT_EQ(stacked[1]["class"], "hepatic_vein");
  EXPECT_NEAR(stacked[1]["volume_mm3"].get<double>(), 3.0 * given[1]["volume_mm3"].get<double>(), 1e-6 * given[1]["volume_mm3"].get<double>());
  EXPECT_EQ(stacked[1]["triangles"], 3 * given[1]["triangles"].get<int>());
  EXPECT_NEAR(stacked[0]["volume_mm3"].get<double>(), 3.0 * given[0]["volume_mm3"].get<double>(), 0.05 * given[0]["volume_mm3"].get<double>());
  for (const char* part : { "read", "total", "write", "built_and_written" })
  {
    EXPECT_GT(doc["stacked"][part]["median_ms"].get<double>(), 0.0) << part;
  }
}

TEST_F(ModelsCommand, AOneValueLabelmapIsTheStructureItsValueNames)
{
  const std::string folder = this->Dir + "/single";
  vp::LabelGrid grid = vp::test::MakeGrid(this->Dims, this->Geometry, [](const double p[3]) { return std::hypot(p[0] + 30, p[1] - 40) < 5 ? 2 : 0; });
  grid.Identity = this->Patient;
  vp::DicomLabelSeriesWriter::Write(grid, folder + "/ABCDEF_inputVolume", "ABCDEF_inputVolume");
  const std::string table = vp::test::WriteBytes(this->Dir, "table.json",
    "{\"classes\": [{\"class\": \"portal_vein\", \"names\": [\"portal vein\"], \"values\": [2]}]}");
  const std::string out = this->Dir + "/single_out";
  const ToolRun r = RunTool(this->Dir, "models " + folder + "/ABCDEF_inputVolume --labels " + table + " -o " + out);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto doc = nlohmann::json::parse(vp::test::Slurp(out + "/models.json"));
  ASSERT_EQ(doc["structures"].size(), 1u);
  EXPECT_EQ(doc["structures"][0]["class"], "portal_vein");
  EXPECT_EQ(doc["structures"][0]["label"], 2);
  EXPECT_TRUE(vp::test::FileExists(out + "/portal_vein.stl"));
  // The default table names 2 for nothing: the structure is listed, not taken.
  const ToolRun plain = RunTool(this->Dir, "models " + folder + "/ABCDEF_inputVolume -o " + this->Dir + "/single_plain");
  EXPECT_EQ(plain.ExitCode, 1);
  EXPECT_NE(plain.Err.find("no vessel or liver structure"), std::string::npos) << plain.Err;
  EXPECT_NE(plain.Err.find("give the labelmap's colour table"), std::string::npos) << plain.Err;
  // A colour table names it (Slicer's colour file as it writes one), before any label table.
  const std::string colors = vp::test::WriteBytes(this->Dir, "colors.ctbl",
    "# Color table file colors.ctbl\n# 3 values\n0 Background 0 0 0 0\n2 Portal_vein 0 151 206 255\n");
  const ToolRun named = RunTool(this->Dir, "models " + folder + "/ABCDEF_inputVolume --colors " + colors + " -o " + this->Dir + "/single_colors");
  ASSERT_EQ(named.ExitCode, 0) << named.Err;
  EXPECT_TRUE(vp::test::FileExists(this->Dir + "/single_colors/portal_vein.stl"));
  // A colour file that is not one: one line naming it and the line.
  const std::string bad = vp::test::WriteBytes(this->Dir, "bad.ctbl", "2 portal vein 0 151 206 255\n");
  const ToolRun refused = RunTool(this->Dir, "models " + folder + "/ABCDEF_inputVolume --colors " + bad + " -o " + this->Dir + "/single_bad");
  EXPECT_EQ(refused.ExitCode, 1);
  EXPECT_NE(refused.Err.find("bad.ctbl: line 1: expected 'value name r g b a', got 7 field(s)"), std::string::npos) << refused.Err;
  EXPECT_FALSE(vp::test::FileExists(this->Dir + "/single_bad"));
}

// An output folder holds one run (issue 16): a re-run with fewer classes removes the class the
// new run has no more (the old hepatic_vein.stl beside a models.json without it was how a
// researcher measured against the wrong anatomy), keeps the user's own files, and an interrupt
// at any moment leaves one whole run: the old or the new, no temporary files.
TEST_F(ModelsCommand, AFolderHoldsOneWholeRunAfterAReRunOrAnInterrupt)
{
  const std::string out = this->Dir + "/models";
  ASSERT_EQ(RunTool(this->Dir, "models " + this->Masks + " -o " + out).ExitCode, 0);
  ASSERT_TRUE(fs::exists(out + "/hepatic_vein.stl"));
  std::ofstream(out + "/notes.txt") << "mine";
  const ToolRun fewer = RunTool(this->Dir, "models " + this->Masks + "/portalvein -o " + out);
  ASSERT_EQ(fewer.ExitCode, 0) << fewer.Err;
  EXPECT_FALSE(fs::exists(out + "/hepatic_vein.stl")) << "a class of the older run";
  EXPECT_TRUE(fs::exists(out + "/portal_vein.stl"));
  EXPECT_TRUE(fs::exists(out + "/notes.txt"));
  const auto listed = nlohmann::json::parse(vp::test::Slurp(out + "/models.json"))["files"];
  EXPECT_EQ(listed, nlohmann::json::array({ "portal_vein.stl", "models.json" }));

  // Interrupted at 40 moments, 8 ms apart, of a run that writes both classes over the one-class
  // run (here the run takes about 70 ms, the writing a few of them; under the sanitizers longer).
  for (int k = 0; k < 40; ++k)
  {
    const pid_t child = vp::test::StartTool({ "models", this->Masks, "-o", out });
    ASSERT_GE(child, 0);
    usleep(static_cast<useconds_t>(8000 * k));
    kill(child, SIGINT);
    int status = 0;
    waitpid(child, &status, 0);
    const auto doc = nlohmann::json::parse(vp::test::Slurp(out + "/models.json"));
    std::set<std::string> expected{ "notes.txt", ".vesselproximity-run.json" };
    for (const auto& name : doc["files"])
    {
      expected.insert(name.get<std::string>());
    }
    std::set<std::string> found;
    for (const auto& entry : fs::directory_iterator(out))
    {
      found.insert(entry.path().filename().string());
    }
    EXPECT_EQ(found, expected) << "interrupted after " << 8 * k << " ms: the run's files, the user's, nothing else";
    EXPECT_TRUE(doc["files"].size() == 2u || doc["files"].size() == 3u) << doc["files"];
  }
}

// Inputs that are not files (issue 16): a FIFO with no writer blocked the open for ever, so it is
// refused before anything opens it, as /dev/zero is.
TEST_F(ModelsCommand, ADeviceOrAPipeIsRefusedBeforeItIsOpened)
{
  const std::string fifo = this->Dir + "/labels.nrrd";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  this->ExpectRefused(fifo, fifo, "is not a regular file (a device, pipe or socket) nor a DICOM series folder");
  this->ExpectRefused("/dev/zero", "/dev/zero", "is not a regular file");
}

// A 100-byte NRRD whose header claims 600^3 raw voxels (issue 16): refused from its size before
// the image is allocated (it took 256 MB first), in bounded memory.
TEST_F(ModelsCommand, ARawLabelmapClaimingMoreVoxelsThanItHoldsIsRefusedBeforeAllocating)
{
  const std::string nrrd = this->Dir + "/claims.nrrd";
  std::ofstream(nrrd, std::ios::binary) << "NRRD0004\ntype: unsigned char\ndimension: 3\nsizes: 600 600 600\n"
                                           "spacings: 1 1 1\nencoding: raw\n\n" << std::string(3, '\1');
  this->ExpectRefused(nrrd, nrrd, "the header claims 216000000 voxels (216000000 bytes, uncompressed), but the file is only 95 bytes");
  struct rusage usage = {};
  getrusage(RUSAGE_CHILDREN, &usage);
  EXPECT_LT(usage.ru_maxrss, 200L * 1024L) << "kB at most, of the command (256 MB and more before)";
}

namespace
{
/// bytes gzip-compressed into file (zlib's gzip writer, as .nii.gz and NRRD's gzip encoding store).
void WriteGzip(const std::string& file, const std::string& bytes, const char* mode = "wb")
{
  gzFile out = gzopen(file.c_str(), mode);
  ASSERT_NE(out, nullptr);
  ASSERT_EQ(gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size())), static_cast<int>(bytes.size()));
  ASSERT_EQ(gzclose(out), Z_OK);
}

/// A NIfTI-1 header (348 bytes and the 4-byte extension flag) claiming n^3 unsigned bytes.
std::string NiftiHeader(short n)
{
  std::string h(352, '\0');
  auto put = [&](std::size_t at, const auto& value) { std::memcpy(&h[at], &value, sizeof(value)); };
  put(0, std::int32_t(348));
  const std::int16_t dim[8] = { 3, n, n, n, 1, 1, 1, 1 };
  std::memcpy(&h[40], dim, sizeof(dim));
  put(70, std::int16_t(2)); // DT_UNSIGNED_CHAR
  put(72, std::int16_t(8));
  const float pixdim[8] = { 1, 1, 1, 1, 1, 1, 1, 1 };
  std::memcpy(&h[76], pixdim, sizeof(pixdim));
  put(108, 352.0f); // vox_offset
  std::memcpy(&h[344], "n+1\0", 4);
  return h;
}
} // namespace

// The same for gzip-compressed voxels (issue 16): deflate gives at most 1032 bytes per byte, so a
// small .nii.gz or gzip NRRD claiming 600^3 voxels is refused from its size, before ITK allocates.
TEST_F(ModelsCommand, ACompressedLabelmapClaimingMoreThanGzipCanHoldIsRefusedBeforeAllocating)
{
  const std::string nii = this->Dir + "/claims.nii.gz";
  WriteGzip(nii, NiftiHeader(600) + std::string(64, '\1'));
  this->ExpectRefused(nii, nii, "the header claims 216000000 voxels (216000000 bytes), more than gzip can hold in a file of");
  const std::string nrrd = this->Dir + "/claims_gz.nrrd";
  std::ofstream(nrrd, std::ios::binary) << "NRRD0004\ntype: unsigned char\ndimension: 3\nsizes: 600 600 600\n"
                                           "spacings: 1 1 1\nencoding: gzip\n\n";
  WriteGzip(nrrd, std::string(1000, '\1'), "ab");
  this->ExpectRefused(nrrd, nrrd, "more than gzip can hold in a file of");
  struct rusage usage = {};
  getrusage(RUSAGE_CHILDREN, &usage);
  EXPECT_LT(usage.ru_maxrss, 200L * 1024L) << "kB at most, of the command";
  // What gzip can hold is still read: 40^3 voxels in a few hundred bytes.
  const std::string small = this->Dir + "/small.nii.gz";
  WriteGzip(small, NiftiHeader(40) + std::string(40 * 40 * 40, '\0'));
  const ToolRun r = RunTool(this->Dir, "models " + small + " -o " + this->Dir + "/out_small");
  EXPECT_EQ(r.Err.find("more than gzip can hold"), std::string::npos) << r.Err;
}

TEST_F(ModelsCommand, EachBadSeriesGetsItsOneLineAndWritesNothing)
{
  // A CT series: negative Hounsfield values.
  const std::string ct = this->Dir + "/ct";
  vp::LabelGrid image = vp::test::MakeGrid(this->Dims, this->Geometry, [](const double p[3]) { return int(p[0] + 60); });
  vp::DicomLabelSeriesWriter::Write(image, ct, "ct");
  for (int k = 0; k < this->Dims[2]; ++k)
  {
    // Stored values as a CT keeps them: signed, with air at -1000.
    DcmFileFormat file;
    const std::string path = ct + "/image_" + std::to_string(k);
    ASSERT_TRUE(file.loadFile(path.c_str()).good());
    std::vector<Uint16> hu(static_cast<std::size_t>(this->Dims[0] * this->Dims[1]));
    for (std::size_t i = 0; i < hu.size(); ++i)
      hu[i] = static_cast<Uint16>(static_cast<Sint16>(-1000 + static_cast<int>(i % 1500)));
    auto* d = file.getDataset();
    d->putAndInsertUint16(DCM_BitsAllocated, 16);
    d->putAndInsertUint16(DCM_BitsStored, 16);
    d->putAndInsertUint16(DCM_HighBit, 15);
    d->putAndInsertUint16(DCM_PixelRepresentation, 1);
    d->putAndInsertUint16Array(DCM_PixelData, hu.data(), static_cast<unsigned long>(hu.size()));
    ASSERT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
  }
  this->ExpectRefused(ct, ct, "an image, not a labelmap");

  // Slice problems, each in a copy of the portal vein series.
  auto copy = [&](const std::string& name) {
    const std::string to = this->Dir + "/" + name;
    fs::copy(this->Masks + "/portalvein", to);
    return to;
  };
  auto edit = [&](const std::string& file, const DcmTagKey& tag, const std::string& value) {
    DcmFileFormat f;
    ASSERT_TRUE(f.loadFile(file.c_str()).good());
    f.getDataset()->putAndInsertString(tag, value.c_str());
    ASSERT_TRUE(f.saveFile(file.c_str(), EXS_LittleEndianExplicit).good());
  };
  const std::string truncated = copy("truncated");
  fs::resize_file(truncated + "/image_5", fs::file_size(truncated + "/image_5") / 2);
  this->ExpectRefused(truncated, "image_5", "not a readable DICOM file");
  const std::string missing = copy("missing");
  fs::remove(missing + "/image_12");
  this->ExpectRefused(missing, missing, "missing slice");
  const std::string uneven = copy("uneven");
  edit(uneven + "/image_12", DCM_ImagePositionPatient, "-50\\20\\-84.5");
  this->ExpectRefused(uneven, uneven, "uneven slice spacing");
  const std::string turned = copy("turned");
  edit(turned + "/image_3", DCM_ImageOrientationPatient, "0\\1\\0\\1\\0\\0");
  this->ExpectRefused(turned, turned, "different orientations");
  const std::string spaced = copy("spaced");
  edit(spaced + "/image_3", DCM_PixelSpacing, "0.9\\0.9");
  this->ExpectRefused(spaced, spaced, "different pixel spacings");
  // Rows x Columns far beyond the pixel data (the fuzzer's: the reader once allocated them first).
  const std::string huge = copy("huge");
  edit(huge + "/image_3", DCM_Rows, "8000");
  edit(huge + "/image_3", DCM_Columns, "8000");
  this->ExpectRefused(huge, "image_3", "pixel data missing or shorter than Rows x Columns");
  // Issue 29: slices of 16384 x 16384 took gigabytes; a PixelSpacing of 1e-300 gave a model of no
  // volume. Both are refused from the headers.
  const std::string wide = copy("wide");
  edit(wide + "/image_0", DCM_Rows, "16384");
  edit(wide + "/image_0", DCM_Columns, "16384");
  this->ExpectRefused(wide, "image_0", "16384 x 16384 pixels: a slice of a labelmap is at most 8192 x 8192");
  const std::string tiny = copy("tiny");
  for (const auto& slice : fs::directory_iterator(tiny))
  {
    edit(slice.path().string(), DCM_PixelSpacing, "1e-300\\1e-300");
  }
  this->ExpectRefused(tiny, tiny, "a voxel 1e-300 mm long along its column (i) axis");

  // An empty structure among good ones.
  this->WriteMask("portalvein1", [](const double*) { return 0; });
  this->ExpectRefused(this->Masks, this->Masks + "/portalvein1", "empty");
  fs::remove_all(this->Masks + "/portalvein1");

  // Not a labelmap at all; a single DICOM file; no DICOM in a folder.
  const std::string text = this->Dir + "/notes.txt";
  std::ofstream(text) << "hello\n";
  this->ExpectRefused(text, text, "not a labelmap");
  this->ExpectRefused(this->Masks + "/portalvein/image_0", "image_0", "not a segmentation");
  fs::create_directories(this->Dir + "/nothing");
  this->ExpectRefused(this->Dir + "/nothing", this->Dir + "/nothing", "no DICOM files");
}

TEST_F(ModelsCommand, RealImagesAreRefusedAsLabelmaps)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: no real CT files";
  const std::string jpeg2000 = data + "/totalsegmentator/example_ct_dicom";
  this->ExpectRefused(jpeg2000, jpeg2000, "JPEG 2000");
  const std::string ct = data + "/totalsegmentator/example_ct_sm.nii.gz";
  this->ExpectRefused(ct, ct, "not a labelmap");
}

// A DICOM SEG in, a model of each segment the table knows out.
TEST_F(ModelsCommand, BuildsTheLiverOfADicomSeg)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: the DICOM SEG files are in ../shared/data";
  const std::string out = this->Dir + "/seg_models";
  const ToolRun r = RunTool(this->Dir, "models " + data + "/dcmqi/liver.dcm -o " + out);
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto json = nlohmann::json::parse(vp::test::Slurp(out + "/models.json"));
  ASSERT_EQ(json["structures"].size(), 1u);
  EXPECT_EQ(json["structures"][0]["name"], "Liver");
  EXPECT_EQ(json["structures"][0]["class"], "liver");
  EXPECT_TRUE(fs::exists(out + "/liver.stl"));
  // Three 1 mm slices of liver: the closed slab encloses the voxels' volume (within 5%: the
  // smoothing moves the surface by a fraction of a voxel, and a 3-slice slab is mostly surface).
  const auto& liver = json["structures"][0];
  EXPECT_EQ(liver["voxels"], 107098);
  EXPECT_NEAR(liver["volume_mm3"].get<double>() / liver["voxel_volume_mm3"].get<double>(), 1.0, 0.05);
}

// Each broken copy of a small real SEG (highdicom's, 16 x 16 x 3 binary) is refused in one line.
TEST_F(ModelsCommand, EachBadSegmentationGetsItsOneLineAndWritesNothing)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: the DICOM SEG files are in ../shared/data";
  const std::string original = data + "/highdicom/seg_image_ct_binary.dcm";
  // Its one segment ("first segment", coded as bone) must be wanted for its voxels to be read.
  const std::string table = this->Dir + "/table.json";
  std::ofstream(table) << "{\"classes\": [{\"class\": \"liver\", \"names\": [\"first segment\"]}]}";
  const std::string withTable = " --labels " + table;
  // A copy of the SEG, changed by edit, saved as name.
  auto broken = [&](const std::string& name, const std::function<void(DcmDataset&)>& edit) {
    DcmFileFormat f;
    EXPECT_TRUE(f.loadFile(original.c_str()).good());
    edit(*f.getDataset());
    const std::string path = this->Dir + "/" + name;
    EXPECT_TRUE(f.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
    return path + withTable;
  };
  auto frameItem = [](DcmDataset& d, long frame, const DcmTagKey& sequence) {
    DcmItem* perFrame = nullptr;
    DcmItem* item = nullptr;
    d.findAndGetSequenceItem(DCM_PerFrameFunctionalGroupsSequence, perFrame, frame);
    if (perFrame)
      perFrame->findAndGetSequenceItem(sequence, item, 0);
    return item;
  };
  ASSERT_NE([&] { DcmFileFormat f; f.loadFile(original.c_str()); return frameItem(*f.getDataset(), 1, DCM_PlanePositionSequence); }(), nullptr)
    << "the plane positions are per frame in this file";

  this->ExpectRefused(broken("offgrid.dcm", [&](DcmDataset& d) {
    frameItem(d, 1, DCM_PlanePositionSequence)->putAndInsertString(DCM_ImagePositionPatient, "-125\\-128.1\\103.8");
  }), "offgrid.dcm", "do not lie on one grid of slices");
  this->ExpectRefused(broken("sheared.dcm", [&](DcmDataset& d) {
    frameItem(d, 2, DCM_PlanePositionSequence)->putAndInsertString(DCM_ImagePositionPatient, "-120\\-128.1\\105.52");
  }), "sheared.dcm", "not stacked along their normal");
  this->ExpectRefused(broken("unplaced.dcm", [&](DcmDataset& d) {
    DcmItem* perFrame = nullptr;
    d.findAndGetSequenceItem(DCM_PerFrameFunctionalGroupsSequence, perFrame, 2);
    delete perFrame->remove(DCM_PlanePositionSequence);
  }), "unplaced.dcm", "frame 3 has no plane position");
  this->ExpectRefused(broken("empty.dcm", [&](DcmDataset& d) {
    const Uint8* bits = nullptr;
    unsigned long n = 0;
    d.findAndGetUint8Array(DCM_PixelData, bits, &n);
    const std::vector<Uint8> zeros(n, 0);
    d.putAndInsertUint8Array(DCM_PixelData, zeros.data(), n);
  }), "empty.dcm", "segment 'first segment' is empty");
  this->ExpectRefused(broken("short.dcm", [&](DcmDataset& d) {
    const Uint8* bits = nullptr;
    unsigned long n = 0;
    d.findAndGetUint8Array(DCM_PixelData, bits, &n);
    const std::vector<Uint8> half(bits, bits + n / 2);
    d.putAndInsertUint8Array(DCM_PixelData, half.data(), n / 2);
  }), "short.dcm", "Invalid Pixel Data");
  // Issue 29: NumberOfFrames 0 beside the per-frame groups crashed in DcmSegmentation::getFrame.
  this->ExpectRefused(broken("frames0.dcm", [&](DcmDataset& d) { d.putAndInsertString(DCM_NumberOfFrames, "0"); }),
    "frames0.dcm", "NumberOfFrames (0) does not match the 3 per-frame functional groups");
  const std::string truncated = this->Dir + "/truncated.dcm";
  fs::copy_file(original, truncated);
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  this->ExpectRefused(truncated + withTable, "truncated.dcm", "not a readable DICOM file");
}

// FRACTIONAL: inside from half of MaximumFractionalValue up, on the real file with its values
// replaced by a ramp, so voxels sit on both sides of the threshold.
TEST(DicomSegFractional, InsideFromHalfTheMaximumUp)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
    GTEST_SKIP() << "VP_TEST_DATA not set: the DICOM SEG files are in ../shared/data";
  DcmFileFormat f;
  ASSERT_TRUE(f.loadFile((data + "/highdicom/seg_image_ct_binary_fractional.dcm").c_str()).good());
  DcmDataset& d = *f.getDataset();
  const Uint8* stored = nullptr;
  unsigned long n = 0;
  ASSERT_TRUE(d.findAndGetUint8Array(DCM_PixelData, stored, &n).good());
  ASSERT_EQ(n, 3u * 16u * 16u);
  std::vector<Uint8> ramp(n);
  for (unsigned long i = 0; i < n; ++i)
    ramp[i] = static_cast<Uint8>(i % 256); // each 16 x 16 frame: 0, 1, ..., 255
  d.putAndInsertUint8Array(DCM_PixelData, ramp.data(), n);
  for (const auto& [maximum, inside] : std::vector<std::pair<Uint16, std::size_t>>{ { 255, 128 }, { 100, 206 } })
  {
    d.putAndInsertUint16(DCM_MaximumFractionalValue, maximum);
    const std::string path = vp::test::MakeTempDir("fractional") + "/ramp.dcm";
    ASSERT_TRUE(f.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
    const auto seg = vp::ImportSegmentation(path, nullptr);
    ASSERT_EQ(seg.size(), 1u);
    vtkImageData* labels = seg[0].Grid.Labels;
    std::size_t count = 0;
    for (vtkIdType i = 0; i < labels->GetNumberOfPoints(); ++i)
      count += static_cast<const unsigned char*>(labels->GetScalarPointer())[i] != 0;
    // Values v with 2v >= maximum, per frame: 255 -> 128..255; 100 -> 50..255.
    EXPECT_EQ(count, 3 * inside) << "maximum " << maximum;
  }
}

TEST_F(ModelsCommand, BadOptionsAreRefused)
{
  this->ExpectRefused(this->Masks + " --smoothing 2", "--smoothing", "between 0 and 1");
  this->ExpectRefused(this->Masks + " --space XYZ", "--space", "must be one of LPS, RAS");
  this->ExpectRefused(this->Masks + " --labels " + this->Dir + "/none.json", "none.json", "no such file");
  const std::string table = this->Dir + "/table.json";
  std::ofstream(table) << "{\"classes\": [{\"class\": \"liver\", \"names\": [\"liver\"]}]}";
  this->ExpectRefused(this->Masks + " --labels " + table, this->Masks, "no vessel or liver structure");

  // An output "folder" that is a file: refused after building, before any model is written.
  const std::string file = this->Dir + "/taken";
  std::ofstream(file) << "x";
  const ToolRun r = RunTool(this->Dir, "models " + this->Masks + " -o " + file);
  EXPECT_EQ(r.ExitCode, 1);
  EXPECT_NE(r.Err.find(file + ": cannot create folder"), std::string::npos) << r.Err;
  EXPECT_EQ(vp::test::Slurp(file), "x");
}
} // namespace

// Issue 31: two patients' masks in one run made one model per class of both; now refused in one
// line naming the flag that allows it, and nothing written. One patient's masks, whose series
// IRCADb names "liver_01^artery", "liver_01^liver", ... each with its own study, pass.
TEST_F(ModelsCommand, TwoPatientsInOneRunAreRefusedUnlessMixingIsAllowed)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  const std::string p1 = extracted + "/ircadb/3Dircadb1.1/MASKS_DICOM", p4 = extracted + "/ircadb/3Dircadb1.4/MASKS_DICOM";
  if (extracted.empty() || !fs::exists(p1) || !fs::exists(p4))
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: the IRCADb masks are in ../shared/data";
  }
  this->ExpectRefused(p1 + " " + p4, "--allow-mixed: " + p1 + "/artery is patient 'liver_01^artery'",
    p4 + "/artery is patient 'liver_04^artery', study");
  const ToolRun mixed = RunTool(this->Dir, "models " + p1 + " " + p4 + " --allow-mixed -o " + this->Dir + "/mixed");
  EXPECT_EQ(mixed.ExitCode, 0) << mixed.Err;
  const ToolRun one = RunTool(this->Dir, "models " + p1 + " -o " + this->Dir + "/one");
  EXPECT_EQ(one.ExitCode, 0) << one.Err;
}
