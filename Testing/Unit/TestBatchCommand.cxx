// `vesselproximity batch` end to end: a cohort of cases from a manifest, each whole in its
// folder, resumed, sharded and merged; each bad manifest refused in one line.
#include "vpAnalyticShapes.h"
#include "vpCohortRun.h"
#include "vpDangerBands.h"
#include "vpDicomLabelSeriesWriter.h"
#include "vpInputError.h"
#include "vpModelTestSupport.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <algorithm>
#include <array>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <csignal>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using vp::test::RunTool;
using vp::test::Slurp;
using vp::test::ToolRun;
namespace fs = std::filesystem;

std::vector<std::vector<std::string>> Cells(const std::string& csv)
{
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);)
  {
    rows.push_back(vp::SplitCsvLine(line, "test"));
  }
  return rows;
}

// A patient as IRCADb lays one out: a portal vein along z (radius 5 mm about x = -30, y = 40) and
// a ball of vena cava; a capped cylinder for a scalpel; a tip driven along x through the vein.
class BatchCommand : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("batch");
    const std::array<double, 16> geometry = { 0.8, 0, 0, -50, 0, 0.8, 0, 20, 0, 0, 1.25, -100, 0, 0, 0, 1 };
    const int dims[3] = { 40, 50, 30 };
    const vp::ImageIdentity patient = vp::DicomLabelSeriesWriter::NewIdentity("");
    this->Patient = patient;
    auto write = [&](const std::string& name, const std::function<int(const double p[3])>& label) {
      vp::LabelGrid grid = vp::test::MakeGrid(dims, geometry, label);
      grid.Identity = patient;
      vp::DicomLabelSeriesWriter::Write(grid, this->Dir + "/p1/MASKS_DICOM/" + name, name);
    };
    write("portalvein", [](const double p[3]) { return std::hypot(p[0] + 30, p[1] - 40) < 5 ? 255 : 0; });
    write("venacava", [](const double p[3]) {
      return std::pow(p[0] + 25, 2) + std::pow(p[1] - 30, 2) + std::pow(p[2] + 85, 2) < 36 ? 1 : 0; });
    const double z[3] = { 0, 0, 1 }, shaft[3] = { 0, 0, 20 };
    vp::test::WriteMeshFile(this->Dir, "tool.stl", vp::MakeCappedCylinder(shaft, z, 1.0, 40.0, 16));
    std::ofstream(this->Dir + "/tool.json") << R"({"tip_mm": [0, 0, 0], "axis": [0, 0, -1]})";
    const double centre[3] = { -30, 60, -80 };
    vp::test::WriteMeshFile(this->Dir, "lesion.stl", vp::MakeSphere(centre, 4.0, 24, 48));
    // Along x at y = 40, z = -80: through the portal vein (x = -48 to -24; its wall at x = -35
    // and -25), and towards it only (to x = -42).
    std::ostringstream in, near;
    in << "time,x,y,z,qw,qx,qy,qz\n";
    near << "time,x,y,z,qw,qx,qy,qz\n";
    for (int i = 0; i <= 30; ++i)
    {
      in << i * 0.05 << "," << -48 + 0.8 * i << ",40,-80,1,0,0,0\n";
      near << i * 0.05 << "," << -48 + 0.2 * i << ",40,-80,1,0,0,0\n";
    }
    std::ofstream(this->Dir + "/p1/in.csv") << in.str();
    std::ofstream(this->Dir + "/p1/near.csv") << near.str();
    std::ofstream(this->Dir + "/p1/tips.csv") << "x,y,z\n-30,52,-80\n-20,40,-60\n";
    this->Manifest = this->WriteManifest("manifest.csv",
      "case,segmentation,poses,tips,plan,scalpel\n"
      "into,p1/MASKS_DICOM,p1/in.csv,p1/tips.csv,lesion.stl,tool.stl\n"
      "# a comment, then a case that only approaches\n"
      "near,p1/MASKS_DICOM,p1/near.csv,,,tool.stl\n"
      "missing,p9/MASKS_DICOM,,,,\n");
  }
  std::string WriteManifest(const std::string& name, const std::string& text)
  {
    std::ofstream(this->Dir + "/" + name) << text;
    return this->Dir + "/" + name;
  }
  std::string Dir, Manifest;
  vp::ImageIdentity Patient;
};
} // namespace

TEST_F(BatchCommand, EachCaseIsComputedWholeAndItsRowsAreItsRecords)
{
  const std::string out = this->Dir + "/cohort";
  const ToolRun r = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out + " -j 2");
  EXPECT_EQ(r.ExitCode, 1) << "one case failed: " << r.Err;
  EXPECT_NE(r.Out.find("3 case(s): 2 computed, 0 whole already, 1 failed"), std::string::npos) << r.Out;
  EXPECT_NE(r.Err.find("missing failed: " + this->Dir + "/p9/MASKS_DICOM: "), std::string::npos) << r.Err;
  const auto rows = Cells(Slurp(out + "/cohort.csv"));
  // Each case a row per vessel class, the artery's saying that there is none, then one per
  // tumour with its own margin; the failed case one.
  ASSERT_EQ(rows.size(), 1u + 3 + 1 + 3 + 1) << Slurp(out + "/cohort.csv");
  EXPECT_EQ(rows[3], std::vector<std::string>({ "into", "hepatic_artery", "", "", "", "", "", "no hepatic_artery in this case's segmentation" }));
  EXPECT_EQ(rows[4][1], "lesion");
  EXPECT_EQ(rows[4][6], rows[1][6]) << "the case's one tumour holds its smallest margin";
  EXPECT_EQ(rows[0], std::vector<std::string>({ "case", "class", "tip_min_mm", "surface_min_mm", "penetration_max_mm3",
                       "breach_frames", "margin_min_mm", "error" }));
  // The picture shows the margin kept around the "into" case's lesion, in the tumour's colour.
  vtkNew<vtkPNGReader> png;
  png->SetFileName((out + "/cohort.png").c_str());
  png->Update();
  vtkImageData* picture = png->GetOutput();
  int dims[3];
  picture->GetDimensions(dims);
  ASSERT_GT(dims[0], 0) << "cohort.png is a PNG";
  int tumourPixels = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0] * 3 / 4; ++x) // the plot, not the legend at the right
    {
      const auto* p = static_cast<const unsigned char*>(picture->GetScalarPointer(x, y, 0));
      tumourPixels += p[0] == vp::TumourDisplayColour[0] && p[1] == vp::TumourDisplayColour[1] && p[2] == vp::TumourDisplayColour[2];
    }
  }
  EXPECT_GT(tumourPixels, 20) << "the margin's mark";
  EXPECT_FALSE(fs::exists(out + "/missing")) << "a failed case leaves no folder";
  for (const std::string name : { "into", "near" })
  {
    const std::string folder = out + "/" + name;
    for (const char* file : { "case.json", "frames.csv", "summary.json", "distance.png", "models/portal_vein.stl",
           "models/hepatic_vein.stl", "models/models.json" })
    {
      EXPECT_TRUE(fs::exists(folder + "/" + file)) << folder << "/" << file;
    }
    // Each row is the case's own record: its summary's closest approach (signed), the frames
    // whose class level is a breach, the largest penetration volume.
    const nlohmann::json summary = nlohmann::json::parse(Slurp(folder + "/summary.json"));
    const auto frames = Cells(Slurp(folder + "/frames.csv"));
    for (const auto& row : rows)
    {
      if (row[0] != name || row[1] == "hepatic_artery" || row[1] == "lesion")
      {
        continue;
      }
      const std::string& cls = row[1];
      const auto& tip = summary["classes"][cls]["tip_minimum"];
      double expected = tip["inside"].get<bool>() ? -tip["distance_mm"].get<double>() : tip["distance_mm"].get<double>();
      if (name == std::string("into"))
      {
        // The tips too: (-30, 52, -80) is 12 mm from the vein's axis, 7 from its wall, farther than the track.
        const nlohmann::json distance = nlohmann::json::parse(Slurp(folder + "/distance.json"));
        for (const auto& t : distance["results"])
        {
          const auto& c = t["classes"][cls];
          if (!c["distance_mm"].is_null())
          {
            expected = std::min(expected, c["inside"].get<bool>() ? -c["distance_mm"].get<double>() : c["distance_mm"].get<double>());
          }
        }
      }
      EXPECT_NEAR(std::stod(row[2]), expected, 1e-4) << name << " " << cls;
      EXPECT_NEAR(std::stod(row[3]), summary["classes"][cls]["surface_minimum"]["distance_mm"].get<double>(), 1e-4);
      EXPECT_NEAR(std::stod(row[4]), summary["classes"][cls]["penetration_maximum"]["volume_mm3"].get<double>(), 1e-4);
      auto column = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(frames[0].begin(), frames[0].end(), name) - frames[0].begin());
      };
      // A breach by the tip or by the whole instrument.
      const std::size_t tipLevel = column(cls + "_level"), instrumentLevel = column(cls + "_instrument_level");
      ASSERT_LT(instrumentLevel, frames[0].size());
      int breaches = 0;
      for (std::size_t f = 1; f < frames.size(); ++f)
      {
        breaches += frames[f][tipLevel] == "breach" || frames[f][instrumentLevel] == "breach" ? 1 : 0;
      }
      EXPECT_EQ(std::stoi(row[5]), breaches) << name << " " << cls;
      if (name == std::string("into") && cls == "portal_vein")
      {
        EXPECT_GT(breaches, 5) << "the tip goes through the vein";
        EXPECT_LT(std::stod(row[2]), -3.5) << "near the axis: 5 mm inside, the model's wall within a voxel";
        // The plan's tumour: a ball of radius 4 mm at y = 60, 20 mm from the tip's line (passing
        // x = -30 within 0.4 mm; the ball's facets within 0.04 mm).
        EXPECT_NEAR(std::stod(row[6]), summary["tumour"]["tumours"][0]["margin_min_mm"].get<double>(), 1e-4);
        EXPECT_NEAR(std::stod(row[6]), 16.0, 0.06);
      }
      EXPECT_EQ(row[7], "");
      if (name == std::string("near"))
      {
        EXPECT_EQ(row[6], "") << "no plan, no margin";
      }
    }
  }
  EXPECT_EQ(rows.back()[0], "missing");
  EXPECT_EQ(rows.back()[7].rfind(this->Dir + "/p9/MASKS_DICOM: ", 0), 0u) << rows.back()[7];
}

TEST_F(BatchCommand, ARunAgainResumesFromTheWholeCasesAndRedoesAChangedOne)
{
  const std::string out = this->Dir + "/cohort";
  ASSERT_EQ(RunTool(this->Dir, "batch " + this->Manifest + " -o " + out).ExitCode, 1);
  const std::string first = Slurp(out + "/cohort.csv");
  const auto written = fs::last_write_time(out + "/into/case.json");
  const ToolRun again = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  EXPECT_NE(again.Out.find("3 case(s): 0 computed, 2 whole already, 1 failed"), std::string::npos) << again.Out;
  EXPECT_EQ(Slurp(out + "/cohort.csv"), first);
  EXPECT_EQ(fs::last_write_time(out + "/into/case.json"), written) << "a whole case is not computed again";
  // A changed input (a later time) makes its case run again; the other stays.
  fs::last_write_time(this->Dir + "/p1/near.csv", fs::last_write_time(this->Dir + "/p1/near.csv") + std::chrono::seconds(5));
  const ToolRun changed = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  EXPECT_NE(changed.Out.find("3 case(s): 1 computed, 1 whole already, 1 failed"), std::string::npos) << changed.Out;
  EXPECT_NE(changed.Err.find("near done"), std::string::npos) << changed.Err;
  EXPECT_EQ(Slurp(out + "/cohort.csv"), first) << "the same inputs' numbers";
}

// A case is whole only while everything it read and wrote is as it was: a mask replaced inside
// the segmentation folder (same name, same size, its time put back) changes the numbers and is
// computed again; a deleted frames.csv likewise; an overwritten distance.json makes its case not
// whole, and is the user's (not written over); each is said.
TEST_F(BatchCommand, ACaseWhoseInputsOrOutputsChangedIsComputedAgainAndSaysWhy)
{
  const std::string out = this->Dir + "/cohort";
  ASSERT_EQ(RunTool(this->Dir, "batch " + this->Manifest + " -o " + out).ExitCode, 1);
  const auto rowOf = [&](const std::string& csv, const std::string& prefix) {
    std::istringstream lines(csv);
    for (std::string line; std::getline(lines, line);)
    {
      if (line.rfind(prefix, 0) == 0)
      {
        return line;
      }
    }
    return std::string();
  };
  const std::string before = rowOf(Slurp(out + "/cohort.csv"), "near,portal_vein,");
  // The portal vein moved 6 mm along x, written over the same files (same sizes), times put back.
  const std::string vein = this->Dir + "/p1/MASKS_DICOM/portalvein";
  std::map<std::string, fs::file_time_type> times;
  for (const auto& f : fs::directory_iterator(vein))
  {
    times[f.path().string()] = fs::last_write_time(f.path());
  }
  const std::array<double, 16> geometry = { 0.8, 0, 0, -50, 0, 0.8, 0, 20, 0, 0, 1.25, -100, 0, 0, 0, 1 };
  const int dims[3] = { 40, 50, 30 };
  vp::LabelGrid grid = vp::test::MakeGrid(dims, geometry, [](const double p[3]) { return std::hypot(p[0] + 24, p[1] - 40) < 5 ? 255 : 0; });
  grid.Identity = this->Patient;
  fs::remove_all(this->Dir + "/moved");
  vp::DicomLabelSeriesWriter::Write(grid, this->Dir + "/moved", "portalvein");
  for (const auto& [file, time] : times)
  {
    const std::string moved = this->Dir + "/moved/" + fs::path(file).filename().string();
    ASSERT_TRUE(fs::exists(moved)) << moved;
    ASSERT_EQ(fs::file_size(moved), fs::file_size(file)) << "the same size, so that only the content tells";
    fs::copy_file(moved, file, fs::copy_options::overwrite_existing);
    fs::last_write_time(file, time);
  }
  const ToolRun masks = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  EXPECT_NE(masks.Out.find("3 case(s): 2 computed, 0 whole already, 1 failed"), std::string::npos) << masks.Out;
  EXPECT_NE(masks.Err.find("near: computed again: an input changed since its run"), std::string::npos) << masks.Err;
  EXPECT_NE(rowOf(Slurp(out + "/cohort.csv"), "near,portal_vein,"), before) << "the new vein's numbers";

  fs::remove(out + "/near/frames.csv");
  std::ofstream(out + "/into/distance.json") << "{}";
  const ToolRun outputs = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  EXPECT_NE(outputs.Out.find("3 case(s): 1 computed, 0 whole already, 2 failed"), std::string::npos) << outputs.Out;
  EXPECT_NE(outputs.Err.find("near: computed again: frames.csv is gone"), std::string::npos) << outputs.Err;
  EXPECT_TRUE(fs::exists(out + "/near/frames.csv"));
  // The edited distance.json is the user's now: the case is not whole, and its run will not
  // write over the file (RunFolder), which it says.
  EXPECT_NE(outputs.Err.find("into: computed again: distance.json changed since it was written"), std::string::npos) << outputs.Err;
  EXPECT_NE(outputs.Err.find("into failed: " + out + "/into/distance.json: was not written by a run here"), std::string::npos)
    << outputs.Err;
  EXPECT_EQ(Slurp(out + "/into/distance.json"), "{}");
}

TEST_F(BatchCommand, ShardsMergeIntoTheCohortOfOneRun)
{
  const std::string whole = this->Dir + "/whole", shards = this->Dir + "/shards";
  ASSERT_EQ(RunTool(this->Dir, "batch " + this->Manifest + " -o " + whole).ExitCode, 1);
  for (const char* shard : { "1/2", "2/2" })
  {
    const ToolRun r = RunTool(this->Dir, "batch " + this->Manifest + " -o " + shards + " --shard " + shard);
    EXPECT_NE(r.Out.find("wrote " + shards + "/cohort-" + std::string(1, shard[0]) + "-of-2.csv"), std::string::npos) << r.Out;
    EXPECT_FALSE(fs::exists(shards + "/cohort.csv")) << "a shard writes its own table only";
  }
  EXPECT_EQ(Cells(Slurp(shards + "/cohort-2-of-2.csv")).size(), 4u) << "the case 'near' (second of three), three classes";
  const ToolRun merged = RunTool(this->Dir, "batch " + this->Manifest + " -o " + this->Dir + "/merged --merge " + shards);
  EXPECT_EQ(merged.ExitCode, 1) << "the failed case is in no shard: " << merged.Err;
  const auto a = Cells(Slurp(whole + "/cohort.csv")), b = Cells(Slurp(this->Dir + "/merged/cohort.csv"));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
  {
    EXPECT_EQ(a[i], b[i]) << "row " << i;
  }
  EXPECT_EQ(b.back()[7].rfind("not whole in any merged folder", 0), 0u) << b.back()[7];
  EXPECT_TRUE(fs::exists(this->Dir + "/merged/cohort.png"));
}

TEST_F(BatchCommand, EachBadManifestOrOptionGetsItsOneLineAndWritesNothing)
{
  const std::string out = this->Dir + "/bad";
  const std::vector<std::pair<std::string, std::string>> manifests = {
    { "case,segmentation,notes\nx,y,z\n", "line 1: unknown column 'notes'" },
    { "case,poses\nx,y\n", "line 1: the header must name the columns case and segmentation" },
    { "case,segmentation\nx,y,z\n", "line 2: 3 cells where the header names 2" },
    { "case,segmentation\nx,a\nx,b\n", "line 3: case 'x' is given twice" },
    { "case,segmentation\nup/../x,a\n", "line 2: case 'up/../x': a case name holds letters" },
    { "case,segmentation\n../up,a\n", "line 2: case '../up': a case name cannot start with '.' or '-'" },
    { "case,segmentation\n.hidden,a\n", "line 2: case '.hidden': a case name cannot start with '.' or '-'" },
    { "case,segmentation\nx,\"a,b\n", "line 2: a quote is not closed" },
    { "case,segmentation\n", "no case" },
    { "case,segmentation,plan\nx,a,b;;c\n", "line 2: an empty entry in the plan" },
    { "case,case,segmentation\n", "line 1: column 'case' is named twice" },
    { "case,segmentation,plan\nx,a,t.stl\n", "line 2: case 'x' has a plan but no poses" },
    { "case,segmentation,poses,pose_units\nx,a,p.csv,cm\n", "line 2: declares pose-units 'cm'; expected mm or m" },
    { "case,segmentation,poses,pose_space\nx,a,p.csv,XYZ\n", "line 2: declares pose-space 'XYZ'; expected LPS or RAS" },
    { "case,segmentation,poses,time_units\nx,a,p.csv,h\n", "line 2: declares time-units 'h'; expected s or ms" },
    { "case,segmentation,tool\nx,a,Stylus\n", "line 2: case 'x' says how to read poses but gives none" },
  };
  for (const auto& [text, problem] : manifests)
  {
    const std::string file = this->WriteManifest("bad.csv", text);
    const ToolRun r = RunTool(this->Dir, "batch " + file + " -o " + out);
    EXPECT_EQ(r.ExitCode, 1) << text;
    EXPECT_EQ(r.Err.rfind("vesselproximity: error: " + file + ": ", 0), 0u) << r.Err;
    EXPECT_NE(r.Err.find(problem), std::string::npos) << r.Err;
    EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << r.Err;
    EXPECT_FALSE(fs::exists(out)) << text;
  }
  for (const auto& [options, problem] : std::vector<std::pair<std::string, std::string>>{
         { "--shard 3/2", "--shard: expected K/N with 1 <= K <= N" },
         { "--shard 1/x", "--shard: expected K/N" },
         { "-j 0", "expected 1 to 256 cases at once" },
         { "--merge a, --shard 1/1", "--merge: an empty folder" },
         { "--merge a --shard 1/2", "a merge gathers every shard" },
         { "--merge " + this->Dir + "/nonexistent", this->Dir + "/nonexistent: is no folder to merge from" } })
  {
    const ToolRun r = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out + " " + options);
    EXPECT_EQ(r.ExitCode, 1) << options;
    EXPECT_NE(r.Err.find(problem), std::string::npos) << r.Err;
    EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << r.Err;
    EXPECT_FALSE(fs::exists(out)) << options;
  }
  // Quoted cells hold commas; a quote inside is doubled.
  const auto cells = vp::SplitCsvLine(R"(a,"b,c","say ""hi""",  d  )", "test");
  EXPECT_EQ(cells, std::vector<std::string>({ "a", "b,c", "say \"hi\"", "d" }));
  EXPECT_THROW(vp::SplitCsvLine(R"("a"b)", "test"), vp::InputError);
}

// One batch at a time writes a cohort folder: with its lock held (here by the test, as a running
// batch holds it) a second is refused at once, naming the holder; a folder that holds the manifest
// is refused, whatever its name; neither writes a thing.
TEST_F(BatchCommand, ASecondBatchIntoTheSameFolderAndAFolderHoldingItsManifestAreRefused)
{
  const std::string out = this->Dir + "/locked";
  fs::create_directories(out);
  const int held = ::open((out + "/.vesselproximity-batch.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  ASSERT_EQ(::pwrite(held, "4242", 4, 0), 4);
  const ToolRun second = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  ::close(held);
  EXPECT_EQ(second.ExitCode, 1);
  EXPECT_NE(second.Err.find(out + ": another batch (process 4242) is writing this cohort folder"), std::string::npos) << second.Err;
  EXPECT_EQ(std::count(second.Err.begin(), second.Err.end(), '\n'), 1) << second.Err;
  EXPECT_FALSE(fs::exists(out + "/cohort.csv"));
  EXPECT_FALSE(fs::exists(out + "/into"));

  const ToolRun inside = RunTool(this->Dir, "batch " + this->Manifest + " -o " + this->Dir);
  EXPECT_EQ(inside.ExitCode, 1);
  EXPECT_NE(inside.Err.find(this->Dir + ": holds the manifest"), std::string::npos) << inside.Err;
  EXPECT_FALSE(fs::exists(this->Dir + "/cohort.csv"));
}

// Ctrl-C at 12 moments of a cohort's run, two cases at a time: each case folder is whole or
// absent, no staging folder is left, the table is written only by a run that ended by itself,
// and a run again takes the whole cases as they are.
TEST_F(BatchCommand, AnInterruptedCohortKeepsItsWholeCasesAndNoPart)
{
  int signalled = 0;
  for (int k = 0; k < 12; ++k)
  {
    const std::string out = this->Dir + "/interrupted" + std::to_string(k);
    const pid_t child = vp::test::StartTool({ "batch", this->Manifest, "-o", out, "-j", "2" });
    ASSERT_GE(child, 0);
    usleep(static_cast<useconds_t>(15000 * k));
    kill(child, SIGINT);
    int status = 0;
    waitpid(child, &status, 0);
    const bool byItself = WIFEXITED(status);
    signalled += WIFSIGNALED(status) && WTERMSIG(status) == SIGINT ? 1 : 0;
    EXPECT_TRUE(byItself || (WIFSIGNALED(status) && WTERMSIG(status) == SIGINT)) << "status " << status;
    EXPECT_EQ(fs::exists(out + "/cohort.csv"), byItself) << "after " << 15 * k << " ms";
    if (!fs::exists(out))
    {
      continue;
    }
    for (const auto& entry : fs::directory_iterator(out))
    {
      const std::string name = entry.path().filename().string();
      if (entry.is_directory())
      {
        EXPECT_TRUE(fs::exists(entry.path() / "case.json")) << name << " after " << 15 * k << " ms: whole or absent";
        for (const auto& inner : fs::directory_iterator(entry.path()))
        {
          EXPECT_EQ(inner.path().filename().string().rfind(".vesselproximity-partial-", 0), std::string::npos)
            << inner.path() << " after " << 15 * k << " ms";
        }
      }
    }
  }
  EXPECT_GT(signalled, 0) << "some run was stopped by the signal";
  // The last folder finished by a run again: its whole cases are taken as they are.
  const std::string out = this->Dir + "/interrupted0";
  const ToolRun again = RunTool(this->Dir, "batch " + this->Manifest + " -o " + out);
  EXPECT_EQ(again.ExitCode, 1) << again.Err;
  EXPECT_TRUE(fs::exists(out + "/cohort.csv"));
  EXPECT_EQ(Cells(Slurp(out + "/cohort.csv")).size(), 9u);
}

// The cohort on a real one-node Slurm cluster (Debian's slurm-wlm, started here in a folder of its
// own: Testing/Cluster/vpSlurmCluster.sh): an array job of two tasks, one shard each, merged,
// equals one run on this machine.
TEST_F(BatchCommand, ASlurmArrayJobMergesToTheCohortOfOneRun)
{
  if (std::system("command -v slurmctld >/dev/null 2>&1 && command -v sbatch >/dev/null 2>&1") != 0)
  {
    GTEST_SKIP() << "slurm-wlm is not installed (.ci/install-deps installs it): the cohort was not run on a cluster";
  }
  const std::string script = std::string(VP_SOURCE_DIR) + "/Testing/Cluster/vpSlurmCluster.sh";
  const std::string cluster = this->Dir + "/slurm";
  ASSERT_EQ(std::system(("bash " + script + " start " + cluster + " >" + this->Dir + "/slurm.out 2>&1").c_str()), 0)
    << Slurp(this->Dir + "/slurm.out") << Slurp(cluster + "/slurmctld.log") << Slurp(cluster + "/slurmd.log");
  struct Stop
  {
    std::string Command;
    ~Stop() { std::system(this->Command.c_str()); }
  } stop{ "bash " + script + " stop " + cluster };
  const std::string manifest = this->WriteManifest("two.csv",
    "case,segmentation,poses,tips,plan,scalpel\n"
    "into,p1/MASKS_DICOM,p1/in.csv,p1/tips.csv,lesion.stl,tool.stl\n"
    "near,p1/MASKS_DICOM,p1/near.csv,,,tool.stl\n");
  const std::string env = "SLURM_CONF=" + cluster + "/slurm.conf ";
  const std::string job = env + "timeout 300 sbatch --wait --array=1-2 -o " + cluster + "/task-%a.out --wrap '" +
    VP_EXECUTABLE + " batch " + manifest + " -o " + this->Dir + "/onslurm --shard $SLURM_ARRAY_TASK_ID/2' >" + this->Dir +
    "/sbatch.out 2>&1";
  ASSERT_EQ(std::system(job.c_str()), 0) << Slurp(this->Dir + "/sbatch.out") << Slurp(cluster + "/task-1.out")
                                         << Slurp(cluster + "/task-2.out");
  EXPECT_NE(Slurp(cluster + "/task-1.out").find("wrote " + this->Dir + "/onslurm/cohort-1-of-2.csv"), std::string::npos);
  EXPECT_NE(Slurp(cluster + "/task-2.out").find("wrote " + this->Dir + "/onslurm/cohort-2-of-2.csv"), std::string::npos);
  const ToolRun merged = RunTool(this->Dir, "batch " + manifest + " -o " + this->Dir + "/onslurm --merge " + this->Dir + "/onslurm");
  ASSERT_EQ(merged.ExitCode, 0) << merged.Err;
  const ToolRun here = RunTool(this->Dir, "batch " + manifest + " -o " + this->Dir + "/here");
  ASSERT_EQ(here.ExitCode, 0) << here.Err;
  EXPECT_EQ(Slurp(this->Dir + "/onslurm/cohort.csv"), Slurp(this->Dir + "/here/cohort.csv"));
  EXPECT_EQ(Cells(Slurp(this->Dir + "/here/cohort.csv")).size(), 8u);
}

// The manifest says how each case's poses are read, as track's options do: the same poses in
// metres and milliseconds, so declared, give the rows of the file in millimetres and seconds, and
// a changed declaration is a changed input (the case is computed again).
TEST_F(BatchCommand, ManifestColumnsSayHowTheCasesPosesAreRead)
{
  std::ostringstream metres;
  metres << "time,x,y,z,qw,qx,qy,qz\n";
  for (int i = 0; i <= 30; ++i)
  {
    metres << i * 50 << "," << (-48 + 0.8 * i) / 1000.0 << ",0.040,-0.080,1,0,0,0\n";
  }
  std::ofstream(this->Dir + "/p1/in-m.csv") << metres.str();
  const std::string manifest = this->WriteManifest("units.csv",
    "case,segmentation,poses,scalpel,pose_units,time_units,pose_space\n"
    "mm,p1/MASKS_DICOM,p1/in.csv,tool.stl,,,\n"
    "metres,p1/MASKS_DICOM,p1/in-m.csv,tool.stl,m,ms,LPS\n");
  const ToolRun r = RunTool(this->Dir, "batch " + manifest + " -o " + this->Dir + "/units");
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto rows = Cells(Slurp(this->Dir + "/units/cohort.csv"));
  ASSERT_EQ(rows.size(), 1u + 3 + 3);
  for (std::size_t k = 1; k <= 3; ++k)
  {
    auto mm = rows[k], m = rows[k + 3];
    EXPECT_EQ(mm[0], "mm");
    EXPECT_EQ(m[0], "metres");
    mm.erase(mm.begin());
    m.erase(m.begin());
    EXPECT_EQ(mm, m) << "the same poses, read as declared";
  }
  const auto frames = Cells(Slurp(this->Dir + "/units/metres/frames.csv"));
  EXPECT_EQ(frames[2][1], "0.050000") << "50 ms is 0.05 s";
  const auto record = nlohmann::json::parse(Slurp(this->Dir + "/units/metres/case.json"));
  EXPECT_EQ(record["inputs"]["pose_reading"]["mm_per_unit"], 1000.0);
  // Declared otherwise, the case is not the one computed.
  this->WriteManifest("units.csv", "case,segmentation,poses,scalpel,pose_units,time_units,pose_space\n"
                                   "metres,p1/MASKS_DICOM,p1/in-m.csv,tool.stl,m,s,LPS\n");
  const ToolRun again = RunTool(this->Dir, "batch " + manifest + " -o " + this->Dir + "/units");
  EXPECT_NE(again.Out.find("1 computed, 0 whole already"), std::string::npos) << again.Out;
}

// IRCADb patients 1 and 4 with no plan: each tumour of their own segmentations is a row with the
// margin the case's poses kept from it, the same as the case's summary says; the tip driven
// through patient 1's third tumour is inside it.
TEST(BatchCommandIrcadb, ACohortWithoutAPlanReportsEachTumoursMarginFromTheSegmentation)
{
  const std::string data = vp::test::ExtractedDataDir() + "/ircadb/";
  if (vp::test::ExtractedDataDir().empty() || !vp::test::FileExists(data + "3Dircadb1.4/MASKS_DICOM/.extracted"))
  {
    GTEST_SKIP() << "IRCADb masks not extracted (set VP_TEST_DATA to ../shared/data and re-run cmake)";
  }
  const std::string dir = vp::test::MakeTempDir("cohort-tumours");
  std::string manifest = "case,segmentation,poses\n";
  for (const char* patient : { "1", "4" })
  {
    const std::string masks = data + "3Dircadb1." + patient + "/MASKS_DICOM";
    const ToolRun models = RunTool(dir, "models " + masks + " -o " + dir + "/models" + patient);
    ASSERT_EQ(models.ExitCode, 0) << models.Err;
    const auto json = nlohmann::json::parse(Slurp(dir + "/models" + patient + "/models.json"));
    std::array<double, 3> c{};
    for (const auto& s : json["structures"])
    {
      c = s["id"] == "tumour_03" ? s["centroid_mm"].get<std::array<double, 3>>() : c;
    }
    // The tip along -z down onto the tumour's centroid and 1 mm past it: the tool points down.
    std::ostringstream poses;
    poses << "time,x,y,z,qw,qx,qy,qz\n";
    for (int i = 0; i <= 20; ++i)
    {
      poses << 0.1 * i << "," << c[0] << "," << c[1] << "," << c[2] - 20 + i * 1.05 << ",0,1,0,0\n";
    }
    std::ofstream(dir + "/poses" + patient + ".csv") << poses.str();
    manifest += std::string("p") + patient + "," + masks + "," + dir + "/poses" + patient + ".csv\n";
  }
  std::ofstream(dir + "/manifest.csv") << manifest;
  const ToolRun r = RunTool(dir, "batch " + dir + "/manifest.csv -o " + dir + "/cohort -j 2");
  ASSERT_EQ(r.ExitCode, 0) << r.Err;
  const auto rows = Cells(Slurp(dir + "/cohort/cohort.csv"));
  std::map<std::string, std::map<std::string, std::string>> margin;
  for (const auto& row : rows)
  {
    if (row[1].rfind("tumour_", 0) == 0)
    {
      margin[row[0]][row[1]] = row[6];
    }
  }
  ASSERT_EQ(margin["p1"].size(), 7u) << Slurp(dir + "/cohort/cohort.csv");
  ASSERT_EQ(margin["p4"].size(), 8u);
  for (const char* patient : { "p1", "p4" })
  {
    const auto summary = nlohmann::json::parse(Slurp(dir + "/cohort/" + patient + "/summary.json"));
    ASSERT_EQ(summary["tumour"]["tumours"].size(), margin[patient].size()) << summary["tumour"].dump();
    for (const auto& t : summary["tumour"]["tumours"])
    {
      EXPECT_NEAR(std::stod(margin[patient][t["id"].get<std::string>()]), t["margin_min_mm"].get<double>(), 1e-4)
        << patient << " " << t["id"];
    }
    EXPECT_LT(std::stod(margin[patient]["tumour_03"]), 0.0) << patient << ": the tip went into its third tumour";
  }
  fs::remove_all(dir);
}
