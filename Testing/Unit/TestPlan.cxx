// `vesselproximity plan` end to end on analytic shapes: the planned approach's numbers against the
// geometry, the same numbers from `track` replaying plan.csv, the cone search finding a safer
// direction, and the one-line refusals that leave nothing behind.
#include "vpAnalyticShapes.h"
#include "vpApproachGeometry.h"
#include "vpModelTestSupport.h"
#include "vpPoseFile.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace
{
namespace fs = std::filesystem;
using vp::test::RunTool;
using vp::test::Slurp;
using vp::test::ToolRun;

/// A CSV file's rows as cells (comment lines skipped), the first its header.
std::vector<std::vector<std::string>> ReadRows(const std::string& path)
{
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(Slurp(path));
  for (std::string line; std::getline(in, line);)
  {
    if (!line.empty() && line[0] != '#')
    {
      rows.push_back(vp::test::SplitCsvLine(line));
    }
  }
  return rows;
}

std::size_t Column(const std::vector<std::string>& header, const std::string& name)
{
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << "no column " << name;
  return static_cast<std::size_t>(it - header.begin());
}

/// The smallest number of a column of frames.csv (empty cells, out of range, skipped).
double ColumnMinimum(const std::vector<std::vector<std::string>>& rows, const std::string& name)
{
  const std::size_t c = Column(rows.front(), name);
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t r = 1; r < rows.size(); ++r)
  {
    if (c < rows[r].size() && !rows[r][c].empty())
    {
      smallest = std::min(smallest, std::stod(rows[r][c]));
    }
  }
  return smallest;
}

/// One line of stderr, naming what it must.
void ExpectOneLineRefusal(const ToolRun& run, const std::string& names, const std::string& out)
{
  EXPECT_EQ(run.ExitCode, 1) << run.Err;
  EXPECT_EQ(std::count(run.Err.begin(), run.Err.end(), '\n'), 1) << run.Err;
  EXPECT_NE(run.Err.find(names), std::string::npos) << run.Err;
  EXPECT_FALSE(fs::exists(out)) << "nothing written: " << out;
}

/// A models folder of analytic shapes: a sphere target of radius 10 at the origin ("tumour_01"), a
/// torus ("ring_01": a line along its axis through its centre misses it), and vessels; a thin
/// cylindrical instrument (radius 1, 80 mm long, its tip at its model's origin, axis +z).
class Plan : public ::testing::Test
{
protected:
  static constexpr double ToolRadiusMm = 1.0;

  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("plan");
    this->Models = this->Dir + "/models";
    fs::create_directories(this->Models);
    const double origin[3] = { 0, 0, 0 }, z[3] = { 0, 0, 1 };
    vp::test::WriteMeshFile(this->Models, "tumour_01.stl", vp::MakeSphere(origin, 10.0, 48, 96));
    const double ring[3] = { 0, -60, 0 };
    vp::test::WriteMeshFile(this->Models, "ring_01.stl", vp::MakeTorus(ring, z, 8.0, 2.0, 64, 24));
    const double shaft[3] = { 0, 0, -40 };
    this->Tool = vp::test::WriteMeshFile(this->Dir, "Tool.stl", vp::MakeCappedCylinder(shaft, z, ToolRadiusMm, 80.0, 64));
    std::ofstream(this->Dir + "/Tool.json") << R"({"tip_mm": [0, 0, 0], "axis": [0, 0, 1]})";
  }
  void TearDown() override { fs::remove_all(this->Dir); }

  /// models.json listing the target, the torus and the given vessels (class = id = file stem).
  void WriteModelsJson(const std::vector<std::string>& vessels)
  {
    nlohmann::json doc = { { "structures", nlohmann::json::array() } };
    for (const std::string& v : vessels)
    {
      doc["structures"].push_back({ { "id", v }, { "class", v }, { "role", "vessel" }, { "file", v + ".stl" } });
    }
    for (const char* t : { "tumour_01", "ring_01" })
    {
      doc["structures"].push_back({ { "id", t }, { "class", "tumour" }, { "role", "tumour" }, { "file", std::string(t) + ".stl" } });
    }
    std::ofstream(this->Models + "/models.json") << doc.dump(2);
  }

  ToolRun PlanRun(const std::string& arguments, const std::string& out)
  {
    return RunTool(this->Dir, "plan --models " + this->Models + " --target tumour_01 -o " + out + " " + arguments);
  }

  /// track replaying a plan's poses against the folder's vessels, the target as its tumour.
  ToolRun Track(const std::string& vessels, const std::string& poses, const std::string& scalpel, const std::string& out)
  {
    return RunTool(this->Dir, "track --method exact --vessels " + vessels + " --scalpel " + scalpel + " --poses " + poses +
        " --tumour tumour_01=" + this->Models + "/tumour_01.stl -o " + out);
  }

  std::string Dir, Models, Tool;
};

// The instrument comes along +x to the sphere through its centre, beside a vessel parallel to its
// path 15 mm off it (radius 2) that begins 20.5 mm ahead of the entry, and passes a ball (radius 3)
// whose centre is 22.36 mm from the path: the whole instrument's closest approach is the axes'
// distance less both radii, reached at the first pose whose tip is level with the vessel's start
// (the ball's: with its centre). track, replaying plan.csv, finds the same per-class minimum.
TEST_F(Plan, ClosestApproachIsTheGeometrysAndTrackReplaysIt)
{
  const double axisX[3] = { 1, 0, 0 };
  const double vesselCentre[3] = { (-49.5 + 30.0) / 2.0, 15.0, 0.0 };
  vp::test::WriteMeshFile(this->Models, "portal_vein.stl", vp::MakeCappedCylinder(vesselCentre, axisX, 2.0, 79.5, 64));
  const double ball[3] = { -30.0, -20.0, 10.0 };
  vp::test::WriteMeshFile(this->Models, "hepatic_vein.stl", vp::MakeSphere(ball, 3.0, 96, 192));
  this->WriteModelsJson({ "portal_vein", "hepatic_vein" });
  const std::string out = this->Dir + "/plan";
  const ToolRun plan = this->PlanRun("--from-direction 2,0,0 --stand-off-mm 60 --scalpel " + this->Tool, out);
  ASSERT_EQ(plan.ExitCode, 0) << plan.Err;

  const nlohmann::json json = nlohmann::json::parse(Slurp(out + "/plan.json"));
  EXPECT_EQ(json.at("target"), "tumour_01");
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(json.at("direction")[a].get<double>(), axisX[a], 1e-12);
    EXPECT_NEAR(json.at("entry")[a].get<double>(), a == 0 ? -70.0 : 0.0, 1e-6);
    EXPECT_NEAR(json.at("target_surface_point")[a].get<double>(), a == 0 ? -10.0 : 0.0, 1e-6);
    EXPECT_NEAR(json.at("end")[a].get<double>(), a == 0 ? -5.0 : 0.0, 1e-6);
  }
  EXPECT_EQ(json.at("margin_mm").get<double>(), 5.0);
  EXPECT_EQ(json.at("poses").get<int>(), 66); // 65 mm, a pose every mm and one at the entry
  const nlohmann::json& portal = json.at("classes").at("portal_vein");
  EXPECT_NEAR(portal.at("closest_mm").get<double>(), 15.0 - 2.0 - ToolRadiusMm, 0.005); // facets: 3 x (1 - cos(pi/64))
  EXPECT_EQ(portal.at("step").get<int>(), 21); // the tip at x = -49, the first pose past the vessel's start
  EXPECT_NEAR(portal.at("point")[1].get<double>(), 13.0, 0.005);
  const nlohmann::json& hepatic = json.at("classes").at("hepatic_vein");
  EXPECT_NEAR(hepatic.at("closest_mm").get<double>(), std::sqrt(500.0) - 3.0 - ToolRadiusMm, 0.005);
  EXPECT_EQ(hepatic.at("step").get<int>(), 40); // the tip at x = -30, level with the ball's centre
  EXPECT_EQ(json.at("clearance_class"), "portal_vein");
  EXPECT_NEAR(json.at("tip_target_signed_mm").get<double>(), -5.0, 0.01);
  EXPECT_GT(fs::file_size(out + "/plan.png"), 10000u);

  // plan.csv: a pose file whose first pose puts the tip at the entry, the tool's +z turned onto +x.
  const auto poses = ReadRows(out + "/plan.csv");
  ASSERT_EQ(poses.size(), 67u);
  EXPECT_EQ(poses.front(), (std::vector<std::string>{ "time", "x", "y", "z", "qw", "qx", "qy", "qz" }));
  EXPECT_NEAR(std::stod(poses[1][1]), -70.0, 1e-9);
  EXPECT_NEAR(std::stod(poses[1][4]), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(std::stod(poses[1][6]), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(std::stod(poses.back()[1]), -5.0, 1e-9);

  const ToolRun track = this->Track("portal_vein=" + this->Models + "/portal_vein.stl,hepatic_vein=" + this->Models + "/hepatic_vein.stl",
    out + "/plan.csv", this->Tool, this->Dir + "/track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  const auto frames = ReadRows(this->Dir + "/track/frames.csv");
  ASSERT_EQ(frames.size(), 67u);
  for (const char* c : { "portal_vein", "hepatic_vein" })
  {
    EXPECT_NEAR(ColumnMinimum(frames, std::string(c) + "_surface_mm"), json.at("classes").at(c).at("closest_mm").get<double>(), 0.01) << c;
  }
  EXPECT_NEAR(std::stod(frames.back()[Column(frames.front(), "tumour_mm")]), -5.0, 0.01); // the margin's depth, reached
}

// Without --scalpel the built-in CUSA handpiece approaches; its files are written beside the plan,
// and track replaying the plan with them finds the same per-class minimum.
TEST_F(Plan, BuiltInHandpieceIsWrittenForTheReplayAndAgrees)
{
  const double axisX[3] = { 1, 0, 0 };
  const double vesselCentre[3] = { -30.0, 16.0, 0.0 };
  vp::test::WriteMeshFile(this->Models, "portal_vein.stl", vp::MakeCappedCylinder(vesselCentre, axisX, 2.0, 60.0, 64));
  this->WriteModelsJson({ "portal_vein" });
  const std::string out = this->Dir + "/plan";
  const ToolRun plan = this->PlanRun("--entry -80,0,0 --step-mm 2.5 --no-picture", out);
  ASSERT_EQ(plan.ExitCode, 0) << plan.Err;
  ASSERT_TRUE(fs::exists(out + "/scalpel/CusaHandpiece.stl"));
  EXPECT_FALSE(fs::exists(out + "/plan.png"));
  const nlohmann::json json = nlohmann::json::parse(Slurp(out + "/plan.json"));
  EXPECT_EQ(json.at("poses").get<int>(), 31); // 70 + 5 mm in 2.5 mm steps, and the entry
  const double closest = json.at("classes").at("portal_vein").at("closest_mm").get<double>();
  EXPECT_LT(closest, 16.0 - 2.0 - 1.4); // the body is wider than its tip tube
  const ToolRun track = this->Track("portal_vein=" + this->Models + "/portal_vein.stl", out + "/plan.csv",
    out + "/scalpel/CusaHandpiece.stl", this->Dir + "/track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  EXPECT_NEAR(ColumnMinimum(ReadRows(this->Dir + "/track/frames.csv"), "portal_vein_surface_mm"), closest, 0.01);
}

// A vessel runs beside the asked path, 2 mm from the instrument: tilted away from it, within 15
// degrees, the instrument keeps more than a millimetre more, and the search finds such a direction.
TEST_F(Plan, ConeSearchFindsASaferDirection)
{
  const double axisX[3] = { 1, 0, 0 };
  const double vesselCentre[3] = { -47.5, 4.0, 0.0 };
  vp::test::WriteMeshFile(this->Models, "portal_vein.stl", vp::MakeCappedCylinder(vesselCentre, axisX, 1.0, 65.0, 64));
  this->WriteModelsJson({ "portal_vein" });
  const std::string out = this->Dir + "/plan";
  const ToolRun plan = this->PlanRun("--from-direction 1,0,0 --stand-off-mm 60 --search-deg 15 --no-picture --scalpel " + this->Tool, out);
  ASSERT_EQ(plan.ExitCode, 0) << plan.Err;
  const nlohmann::json json = nlohmann::json::parse(Slurp(out + "/plan.json"));
  const double asked = json.at("clearance_mm").get<double>();
  EXPECT_NEAR(asked, 4.0 - 1.0 - ToolRadiusMm, 0.005);
  const nlohmann::json& search = json.at("search");
  EXPECT_GE(search.at("directions").get<int>(), 30);
  const nlohmann::json& safest = search.at("safest");
  EXPECT_GT(safest.at("clearance_mm").get<double>(), asked + 1.0);
  EXPECT_GT(safest.at("angle_deg").get<double>(), 0.0);
  EXPECT_LE(safest.at("angle_deg").get<double>(), 15.0 + 1e-9);
  // Travelling towards +y through the target's centre, it comes from the -y side: away from the vessel.
  EXPECT_GT(safest.at("direction")[1].get<double>(), 0.0);
  EXPECT_NEAR(search.at("safer_by_mm").get<double>(), safest.at("clearance_mm").get<double>() - asked, 1e-12);
  // The safest approach's poses replay to its numbers too.
  const ToolRun track = this->Track("portal_vein=" + this->Models + "/portal_vein.stl", out + "/safest.csv", this->Tool, this->Dir + "/track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  EXPECT_NEAR(ColumnMinimum(ReadRows(this->Dir + "/track/frames.csv"), "portal_vein_surface_mm"),
    safest.at("classes").at("portal_vein").at("closest_mm").get<double>(), 0.01);
}

// An instrument whose tip is not at its model's origin and whose axis is not +z is still advanced
// tip first along the approach: track's tip and axis columns follow the planned line, from the
// entry to the margin past the target's surface, whatever the direction.
TEST_F(Plan, TipAndAxisOfTheScalpelDefinitionLieOnTheApproach)
{
  const double axisX[3] = { 1, 0, 0 }, axisY[3] = { 0, 1, 0 };
  const double vesselCentre[3] = { -30.0, 16.0, 0.0 };
  vp::test::WriteMeshFile(this->Models, "portal_vein.stl", vp::MakeCappedCylinder(vesselCentre, axisX, 2.0, 60.0, 32));
  this->WriteModelsJson({ "portal_vein" });
  const double shaft[3] = { 5.0, -35.0, 7.0 }; // the tip at (5, 5, 7), the shaft behind it along -y
  const std::string tool = vp::test::WriteMeshFile(this->Dir, "Offset.stl", vp::MakeCappedCylinder(shaft, axisY, 1.0, 80.0, 32));
  std::ofstream(this->Dir + "/Offset.json") << R"({"tip_mm": [5, 5, 7], "axis": [0, 1, 0]})";
  const std::string out = this->Dir + "/plan";
  const ToolRun plan = this->PlanRun("--from-direction -1,2,-2 --stand-off-mm 30 --margin-mm 3 --no-picture --scalpel " + tool, out);
  ASSERT_EQ(plan.ExitCode, 0) << plan.Err;
  const nlohmann::json json = nlohmann::json::parse(Slurp(out + "/plan.json"));
  const ToolRun track = this->Track("portal_vein=" + this->Models + "/portal_vein.stl", out + "/plan.csv", tool, this->Dir + "/track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  const auto frames = ReadRows(this->Dir + "/track/frames.csv");
  const double direction[3] = { -1.0 / 3.0, 2.0 / 3.0, -2.0 / 3.0 };
  for (int a = 0; a < 3; ++a)
  {
    const std::string axis(1, "xyz"[a]);
    EXPECT_NEAR(std::stod(frames[1][Column(frames.front(), "tip_" + axis)]), json.at("entry")[a].get<double>(), 1e-3);
    EXPECT_NEAR(std::stod(frames.back()[Column(frames.front(), "tip_" + axis)]), json.at("end")[a].get<double>(), 1e-3);
    EXPECT_NEAR(json.at("end")[a].get<double>(), -7.0 * direction[a], 0.03); // 3 mm inside the sphere of radius 10
    EXPECT_NEAR(std::stod(frames.back()[Column(frames.front(), "axis_" + axis)]), direction[a], 1e-5);
  }
  EXPECT_NEAR(std::stod(frames.back()[Column(frames.front(), "tumour_mm")]), -3.0, 0.03);
}

// The geometry the planner builds on: the turn of the tool's axis onto the approach (opposite
// vectors too), the cone's rings, the centre of an enclosed volume, the way out of a box.
TEST(PlanGeometry, TurnsConeCentreAndBox)
{
  const vp::Vector3 z{ 0, 0, 1 };
  for (const vp::Vector3& to : { vp::Vector3{ 1, 0, 0 }, vp::Vector3{ 0, 0, -1 }, vp::Normalized({ -1, 2, -2 }), z })
  {
    const std::array<double, 4> q = vp::QuaternionTurning(z, to);
    const std::array<double, 16> m = vp::PoseFromQuaternion({ 0, 0, 0 }, q);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(m[4 * a + 2], to[a], 1e-12); // the third column: where +z goes
    }
  }
  const std::vector<vp::ConeDirection> cone = vp::ConeDirections(z, 15.0, 5.0);
  EXPECT_EQ(cone.size(), 7u + 13u + 19u); // about 5 degrees apart around rings of 5, 10 and 15 degrees
  for (const vp::ConeDirection& d : cone)
  {
    EXPECT_NEAR(std::acos(d.Direction[2]) * 180.0 / 3.14159265358979323846, d.AngleDeg, 1e-9);
  }
  const double centre[3] = { 3, -4, 12 };
  const vp::Vector3 found = vp::EnclosedVolumeCentre(vp::MakeSphere(centre, 5.0, 24, 48));
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(found[a], centre[a], 1e-9);
  }
  EXPECT_NEAR(vp::DistanceOutOfBox({ 0, 0, 0 }, { 0, -1, 0 }, { -10, 10, -20, 30, -5, 5 }), 20.0, 1e-12);
  EXPECT_EQ(vp::DistanceOutOfBox({ 0, 40, 0 }, { 0, -1, 0 }, { -10, 10, -20, 30, -5, 5 }), 0.0);
}

// Every bad request: one line naming the option, exit 1, no output folder.
TEST_F(Plan, BadRequestsAreRefusedInOneLineWithNothingWritten)
{
  const double vesselCentre[3] = { -30.0, 16.0, 0.0 };
  const double axisX[3] = { 1, 0, 0 };
  vp::test::WriteMeshFile(this->Models, "portal_vein.stl", vp::MakeCappedCylinder(vesselCentre, axisX, 2.0, 60.0, 32));
  this->WriteModelsJson({ "portal_vein" });
  const std::string out = this->Dir + "/refused";
  const std::string scalpel = " --no-picture --scalpel " + this->Tool;
  const ToolRun unknown = RunTool(this->Dir, "plan --models " + this->Models + " --target tumour_99 --entry -80,0,0 -o " + out + scalpel);
  ExpectOneLineRefusal(unknown, "--target", out);
  EXPECT_NE(unknown.Err.find("portal_vein, tumour_01, ring_01"), std::string::npos) << unknown.Err;
  ExpectOneLineRefusal(this->PlanRun("--entry 3,1,0" + scalpel, out), "--entry: lies inside the target", out);
  ExpectOneLineRefusal(this->PlanRun("--from-direction 0,0,0" + scalpel, out), "--from-direction: has zero length", out);
  ExpectOneLineRefusal(this->PlanRun("--entry -80,0,0 --from-direction 1,0,0" + scalpel, out), "--entry/--from-direction", out);
  ExpectOneLineRefusal(this->PlanRun(scalpel, out), "--entry/--from-direction", out);
  ExpectOneLineRefusal(this->PlanRun("--entry -80,0,0 --step-mm 0" + scalpel, out), "--step-mm", out);
  ExpectOneLineRefusal(this->PlanRun("--entry -80,0,0 --margin-mm 60" + scalpel, out), "--margin-mm", out);
  ExpectOneLineRefusal(this->PlanRun("--entry -80,0,0 --search-deg 90" + scalpel, out), "--search-deg", out);
  ExpectOneLineRefusal(this->PlanRun("--entry -80,0,0 --stand-off-mm 30" + scalpel, out), "--stand-off-mm: goes with a direction", out);
  const ToolRun misses = RunTool(this->Dir, "plan --models " + this->Models + " --target ring_01 --from-direction 0,0,1 -o " + out + scalpel);
  ExpectOneLineRefusal(misses, "--from-direction: the line along it through the centre of 'ring_01' misses the target", out);
  const std::string lonely = this->Dir + "/lonely";
  fs::create_directories(lonely);
  fs::copy_file(this->Models + "/tumour_01.stl", lonely + "/tumour_01.stl");
  std::ofstream(lonely + "/models.json") << R"({"structures": [{"id": "tumour_01", "class": "tumour", "file": "tumour_01.stl"}]})";
  const ToolRun noVessel = RunTool(this->Dir, "plan --models " + lonely + " --target tumour_01 --entry -80,0,0 -o " + out + scalpel);
  ExpectOneLineRefusal(noVessel, "lists no vessel besides the target", out);
}
} // namespace

namespace
{
// IRCADb patient 1: its vessels modelled by `vesselproximity models`, its first tumour (from its
// mask when models lists tumours, else IRCADb's own mesh) the target, approached from the front
// with a search; track replaying plan.csv finds each class's minimum the plan reported.
TEST_F(Plan, RealDataPatient1TrackAgrees)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  const std::string masks = extracted + "/ircadb/3Dircadb1.1/MASKS_DICOM";
  const std::string tumour = extracted + "/ircadb/3Dircadb1.1/MESHES_VTK/livertumor01.vtk";
  if (extracted.empty() || !fs::exists(masks) || !fs::exists(tumour))
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: the IRCADb masks and meshes are in ../shared/data";
  }
  const std::string models = this->Dir + "/p1";
  const ToolRun built = RunTool(this->Dir, "models " + masks + " -o " + models);
  ASSERT_EQ(built.ExitCode, 0) << built.Err;
  // The tumour from its mask when models lists the tumours, else IRCADb's own mesh of it.
  nlohmann::json doc = nlohmann::json::parse(Slurp(models + "/models.json"));
  const auto& structures = doc.at("structures");
  if (std::none_of(structures.begin(), structures.end(), [](const nlohmann::json& s) { return s.value("id", "") == "tumour_01"; }))
  {
    fs::copy_file(tumour, models + "/tumour_01.vtk");
    doc["structures"].push_back({ { "id", "tumour_01" }, { "class", "tumour" }, { "role", "tumour" }, { "file", "tumour_01.vtk" } });
    std::ofstream(models + "/models.json") << doc.dump(2);
  }
  const std::string out = this->Dir + "/p1plan";
  const ToolRun plan = RunTool(this->Dir,
    "plan --models " + models + " --target tumour_01 --from-direction 0,1,0 --stand-off-mm 40 --search-deg 10 --no-picture -o " + out);
  ASSERT_EQ(plan.ExitCode, 0) << plan.Err;
  const nlohmann::json json = nlohmann::json::parse(Slurp(out + "/plan.json"));
  std::string vessels;
  for (const char* c : { "portal_vein", "hepatic_vein", "hepatic_artery" })
  {
    vessels += (vessels.empty() ? "" : ",") + std::string(c) + "=" + models + "/" + c + ".stl";
  }
  const ToolRun track = RunTool(this->Dir, "track --method exact --vessels " + vessels + " --scalpel " + out +
      "/scalpel/CusaHandpiece.stl --poses " + out + "/plan.csv -o " + this->Dir + "/p1track");
  ASSERT_EQ(track.ExitCode, 0) << track.Err;
  const auto frames = ReadRows(this->Dir + "/p1track/frames.csv");
  EXPECT_EQ(frames.size(), json.at("poses").get<std::size_t>() + 1);
  for (const char* c : { "portal_vein", "hepatic_vein", "hepatic_artery" })
  {
    const nlohmann::json& planned = json.at("classes").at(c);
    ASSERT_FALSE(planned.at("closest_mm").is_null()) << c << " within range";
    EXPECT_NEAR(ColumnMinimum(frames, std::string(c) + "_surface_mm"), planned.at("closest_mm").get<double>(), 0.01) << c;
  }
  EXPECT_GE(json.at("search").at("safest").at("clearance_mm").get<double>(), json.at("clearance_mm").get<double>());
}
} // namespace
