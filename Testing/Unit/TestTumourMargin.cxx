// The resection margin: the tip's signed distance to each tumour and the whole instrument's, the
// margin's levels with their hysteresis, against a box whose distances are known exactly, and
// against the brute force on IRCADb patient 1's seven tumours.
#include "vpAnalyticShapes.h"
#include "vpInputError.h"
#include "vpLiveResults.h"
#include "vpMarginLevels.h"
#include "vpSceneRequest.h"
#include "vpTestSupport.h"
#include "vpTrackingSession.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkTumourMarginDistance.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityParameters.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <vtkCallbackCommand.h>
#include <vtkCleanPolyData.h>
#include <vtkCubeSource.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
using vp::MarginLevel;

/// A closed box, x in [30, 50], y and z in [-10, 10]: distances to it are known in closed form.
vtkSmartPointer<vtkPolyData> BoxTumour()
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(30, 50, -10, 10, -10, 10);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean; // the faces share their corners: a closed surface
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->Update();
  return clean->GetOutput();
}

/// Signed distance from p to the box (negative inside).
double BoxSignedMm(const double p[3])
{
  const double lo[3] = { 30, -10, -10 }, hi[3] = { 50, 10, 10 };
  double outside2 = 0.0, inside = 1e300;
  for (int a = 0; a < 3; ++a)
  {
    const double d = std::max(lo[a] - p[a], p[a] - hi[a]);
    outside2 += d > 0.0 ? d * d : 0.0;
    inside = std::min(inside, -d);
  }
  return outside2 > 0.0 ? std::sqrt(outside2) : -inside;
}

/// The instrument: a capped cylinder of radius 1 mm standing on its tip (the model's origin), up +z.
vtkSmartPointer<vtkPolyData> Instrument()
{
  const double up[3] = { 0, 0, 1 }, centre[3] = { 0, 0, 20 };
  return vp::MakeCappedCylinder(centre, up, 1.0, 40.0, 64);
}

std::array<double, 16> TranslatedTo(const double p[3])
{
  return { 1, 0, 0, p[0], 0, 1, 0, p[1], 0, 0, 1, p[2], 0, 0, 0, 1 };
}
} // namespace

TEST(MarginLevels, EnteredAtOnceLeftPastTheHysteresis)
{
  const vp::MarginSettings s{ 5.0, 5.0 };
  EXPECT_EQ(vp::ClassifyMargin(12.0, false, s, MarginLevel::Clear, 0.0), MarginLevel::Clear);
  EXPECT_EQ(vp::ClassifyMargin(10.0, false, s, MarginLevel::Clear, 0.0), MarginLevel::Clear);
  EXPECT_EQ(vp::ClassifyMargin(9.99, false, s, MarginLevel::Clear, 0.0), MarginLevel::Near);
  EXPECT_EQ(vp::ClassifyMargin(5.0, false, s, MarginLevel::Clear, 0.0), MarginLevel::Near);
  EXPECT_EQ(vp::ClassifyMargin(4.99, false, s, MarginLevel::Clear, 0.0), MarginLevel::Violated);
  EXPECT_EQ(vp::ClassifyMargin(0.0, false, s, MarginLevel::Clear, 0.0), MarginLevel::Violated) << "on the surface";
  EXPECT_EQ(vp::ClassifyMargin(-0.01, false, s, MarginLevel::Clear, 0.0), MarginLevel::Inside);
  EXPECT_EQ(vp::ClassifyMargin(8.0, true, s, MarginLevel::Clear, 0.0), MarginLevel::Inside) << "uncertain: inside";
  EXPECT_EQ(vp::ClassifyMargin(std::nan(""), false, s, MarginLevel::Clear, 0.0), MarginLevel::Inside);
  // Leaving needs the edge plus the hysteresis; entering is immediate whatever the level before.
  EXPECT_EQ(vp::ClassifyMargin(5.2, false, s, MarginLevel::Violated, 0.3), MarginLevel::Violated);
  EXPECT_EQ(vp::ClassifyMargin(5.3, false, s, MarginLevel::Violated, 0.3), MarginLevel::Near);
  EXPECT_EQ(vp::ClassifyMargin(0.2, false, s, MarginLevel::Inside, 0.3), MarginLevel::Inside);
  EXPECT_EQ(vp::ClassifyMargin(0.31, false, s, MarginLevel::Inside, 0.3), MarginLevel::Violated);
  EXPECT_EQ(vp::ClassifyMargin(10.1, false, s, MarginLevel::Inside, 0.3), MarginLevel::Near) << "one step at a time past each edge";
  EXPECT_EQ(vp::ClassifyMargin(20.0, false, s, MarginLevel::Inside, 0.3), MarginLevel::Clear);
  EXPECT_EQ(vp::ClassifyMargin(-1.0, false, s, MarginLevel::Near, 0.3), MarginLevel::Inside);
  // A margin of 0: only inside and clear or near.
  const vp::MarginSettings none{ 0.0, 0.0 };
  EXPECT_EQ(vp::ClassifyMargin(0.0, false, none, MarginLevel::Clear, 0.0), MarginLevel::Clear);
  EXPECT_THROW(vp::MarginSettings({ -1.0, 5.0 }).Validate("MarginMm"), vp::ParameterError);
  EXPECT_THROW(vp::MarginSettings({ 5.0, std::nan("") }).Validate("MarginMm"), vp::ParameterError);
  EXPECT_STREQ(vp::MarginLevelName(MarginLevel::Violated), "violated");
}

TEST(TumourMargin, TheTipAndTheInstrumentAgainstABoxAreExact)
{
  vtkNew<vtkTumourMarginDistance> margin;
  margin->AddTumour("box", BoxTumour());
  margin->SetToolSurface(Instrument());
  margin->SetInstrumentRangeMm(50.0);
  EXPECT_THROW(margin->AddTumour("box", BoxTumour()), vp::ParameterError);
  EXPECT_THROW(margin->SetInstrumentRangeMm(0.0), vp::ParameterError);
  const double tips[][3] = { { 10, 0, 0 }, { 20, 15, 15 }, { 29.5, 3, -2 }, { 35, 0, 0 }, { 40, 0, 0 }, { 45, 8, 1 },
    { 60, -20, 30 }, { -900, 0, 0 }, { 30, 0, 0 } };
  vp::TumourMargin out, previous;
  for (const auto& tip : tips)
  {
    margin->ComputeMargin(tip, TranslatedTo(tip), out, out.Tumours.empty() ? nullptr : &previous);
    ASSERT_EQ(out.Tumours.size(), 1u);
    const vp::TumourProximity& t = out.Tumours[0];
    EXPECT_EQ(t.Id, "box");
    EXPECT_NEAR(t.SignedMm, BoxSignedMm(tip), 1e-9) << tip[0] << "," << tip[1] << "," << tip[2];
    EXPECT_FALSE(t.InsideUncertain);
    EXPECT_NEAR(std::sqrt(std::pow(t.ClosestPoint[0] - tip[0], 2) + std::pow(t.ClosestPoint[1] - tip[1], 2) +
                  std::pow(t.ClosestPoint[2] - tip[2], 2)),
      std::abs(t.SignedMm), 1e-9);
    if (tip[0] < -100.0)
    {
      EXPECT_FALSE(t.SurfaceKnown) << "beyond the instrument's range (50 mm): no instrument distance";
      previous = out;
      continue;
    }
    ASSERT_TRUE(t.SurfaceKnown);
    // The cylinder stands on the tip: never farther than the tip, and 0 where it crosses the box.
    EXPECT_LE(t.SurfaceMm, std::max(0.0, t.SignedMm) + 1e-9);
    EXPECT_GE(t.SurfaceMm, 0.0);
    previous = out;
  }
  // Beside the box, the cylinder's side (radius 1, 64 facets) is 1 mm nearer than its axis.
  const double beside[3] = { 10, 0, 0 };
  margin->ComputeMargin(beside, TranslatedTo(beside), out);
  EXPECT_NEAR(out.Tumours[0].SurfaceMm, 19.0, 1.0 - std::cos(M_PI / 64) + 1e-9);
  // Above the box, straight up: the cylinder goes away from it, its tip is the nearest point.
  const double above[3] = { 40, 0, 12 };
  margin->ComputeMargin(above, TranslatedTo(above), out);
  EXPECT_NEAR(out.Tumours[0].SignedMm, 2.0, 1e-9);
  EXPECT_NEAR(out.Tumours[0].SurfaceMm, 2.0, 1e-9);
  // Within 10 mm only: the instrument 19 mm away has no distance, the tip keeps its own.
  margin->SetInstrumentRangeMm(10.0);
  margin->ComputeMargin(beside, TranslatedTo(beside), out);
  EXPECT_FALSE(out.Tumours[0].SurfaceKnown);
  EXPECT_NEAR(out.Tumours[0].SignedMm, 20.0, 1e-9);
  // Without a tool surface, the tip alone.
  vtkNew<vtkTumourMarginDistance> tipOnly;
  tipOnly->AddTumour("box", BoxTumour());
  tipOnly->ComputeMargin(above, TranslatedTo(above), out);
  EXPECT_FALSE(out.Tumours[0].SurfaceKnown);
  EXPECT_NEAR(out.Tumours[0].SignedMm, 2.0, 1e-9);
}

TEST(TumourMargin, TheLogicGivesEachFrameItsLevelAndTellsOnlyOfChanges)
{
  const std::string dir = vp::test::MakeTempDir("tumour_margin");
  const double origin[3] = { 0, 0, 0 };
  vp::SceneRequest request;
  request.Vessels = { { "portal_vein", "in memory", vp::MakeSphere(origin, 10.0, 40, 80), std::nullopt } };
  request.Tumours = { { "box", "in memory", BoxTumour(), std::nullopt } };
  request.Scalpel = vtkSmartPointer<vtkScalpelModel>::New();
  request.Scalpel->SetModel(Instrument());
  request.Scalpel->SetTipMm(origin);
  request.Scalpel->SetAxis(0, 0, -1);
  request.Tracking.Margin = { 4.0, 3.0 };
  request.Tracking.HysteresisMm = 0.3;
  vtkNew<vtkVesselProximityLogic> logic;
  const vp::OpenedScene scene = logic->OpenScene(request);
  ASSERT_EQ(scene.Tumours.size(), 1u);
  EXPECT_EQ(logic->GetParameters()->GetNumberOfTumours(), 1);
  EXPECT_EQ(logic->GetParameters()->GetMarginSettings().MarginMm, 4.0);

  std::vector<vp::MarginLevelChange> changes;
  vtkNew<vtkCallbackCommand> onChange;
  onChange->SetClientData(&changes);
  onChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<vp::MarginLevelChange>*>(client)->push_back(*static_cast<vp::MarginLevelChange*>(call));
  });
  logic->GetTrackingLogic()->AddObserver(vtkScalpelTrackingLogic::MarginLevelChangedEvent, onChange);

  // The tip along x at y = z = 0: the box's face at x = 30, so the tip's margin is 30 - x. In from
  // 20 (10 mm: clear), jittering 0.1 mm about the margin's edge (x = 26), into the box and out.
  const std::vector<double> xs = { 20, 23.5, 25.9, 26.1, 25.9, 26.1, 27, 31, 29.8, 29.65, 25.8, 25.5, 22.8, 20 };
  const std::vector<MarginLevel> expected = { MarginLevel::Clear, MarginLevel::Near, MarginLevel::Near,
    MarginLevel::Violated, MarginLevel::Violated, MarginLevel::Violated, MarginLevel::Violated, MarginLevel::Inside,
    MarginLevel::Inside, MarginLevel::Violated, MarginLevel::Violated, MarginLevel::Near, MarginLevel::Near,
    MarginLevel::Clear }; // margin 4, near band 3, hysteresis 0.3: 25.8 (4.2 mm) holds violated, 22.8 (7.2) near
  vp::TrackingSession session(logic);
  for (std::size_t i = 0; i < xs.size(); ++i)
  {
    const double tip[3] = { xs[i], 0, 0 };
    const vp::TrackedFrame& f = session.Process({ 0.1 * i, TranslatedTo(tip) });
    ASSERT_TRUE(f.Tumour) << "with tumours, every frame measures them";
    EXPECT_NEAR(f.Tumour->Tumours[0].SignedMm, 30.0 - xs[i], 1e-9);
    EXPECT_EQ(f.Tumour->Level, expected[i]) << "frame " << i << " at x " << xs[i];
  }
  // Clear -> near -> violated -> inside -> violated -> near -> clear: six changes, none for the jitter.
  ASSERT_EQ(changes.size(), 6u);
  EXPECT_EQ(changes[5].Frame, 13);
  EXPECT_EQ(changes[0].From, MarginLevel::Clear);
  EXPECT_EQ(changes[0].To, MarginLevel::Near);
  EXPECT_EQ(changes[0].Frame, 1);
  EXPECT_EQ(changes[2].To, MarginLevel::Inside);
  EXPECT_EQ(changes[2].TumourId, "box");
  EXPECT_NEAR(changes[2].SignedMm, -1.0, 1e-9);
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1) << "the scalpel moved: nothing rebuilt";

  // A new margin is a setting, not a scene change; a tumour file that is not there is refused by name.
  logic->GetParameters()->SetMarginSettings({ 1.0, 0.0 });
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1);
  const double tip[3] = { 27.5, 0, 0 };
  EXPECT_EQ(session.Process({ 2.0, TranslatedTo(tip) }).Tumour->Level, MarginLevel::Clear);
  request.Tumours = { { "box", dir + "/none.stl", nullptr, std::nullopt } };
  try
  {
    logic->OpenScene(request);
    ADD_FAILURE() << "a missing tumour file was read";
  }
  catch (const vp::InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind(dir + "/none.stl: ", 0), 0u) << e.what();
  }
  request.Tumours = { { "1st", "in memory", BoxTumour(), std::nullopt } };
  EXPECT_THROW(logic->OpenScene(request), vp::ParameterError);
}

TEST(TumourMargin, EqualsTheBruteForceOnIrcadbPatient1sTumours)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: tumour margins on IRCADb not tested";
  }
  const std::string dir = extracted + "/ircadb/3Dircadb1.1/MESHES_VTK/";
  vtkNew<vtkTumourMarginDistance> margin;
  auto brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  brute->SetRangeMm(1e6);
  double bounds[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (int t = 1; t <= 7; ++t)
  {
    const std::string id = "livertumor0" + std::to_string(t);
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(dir + id + ".vtk");
    reader->Read();
    margin->AddTumour(id, reader->GetOutput());
    brute->AddVessel(id, reader->GetOutput());
    const double* b = reader->GetOutput()->GetBounds();
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], b[2 * a] - 20);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], b[2 * a + 1] + 20);
    }
  }
  brute->Build();
  std::mt19937 random(2026);
  int inside = 0;
  vp::TumourMargin out;
  for (int i = 0; i < 400; ++i)
  {
    double tip[3];
    for (int a = 0; a < 3; ++a)
    {
      tip[a] = std::uniform_real_distribution<double>(bounds[2 * a], bounds[2 * a + 1])(random);
    }
    margin->ComputeMargin(tip, TranslatedTo(tip), out);
    vp::ProximityResult b;
    brute->ComputeProximity(tip, nullptr, b);
    ASSERT_EQ(out.Tumours.size(), b.Classes.size());
    for (std::size_t t = 0; t < b.Classes.size(); ++t)
    {
      const vp::ClassProximity& c = b.Classes[t];
      ASSERT_TRUE(c.InRange);
      const bool in = c.Inside.value_or(false);
      EXPECT_NEAR(out.Tumours[t].SignedMm, in ? -c.DistanceMm : c.DistanceMm, 1e-6) << "tip " << i << " " << c.ClassName;
      EXPECT_EQ(out.Tumours[t].InsideUncertain, c.InsideUncertain) << "tip " << i << " " << c.ClassName;
      inside += in ? 1 : 0;
    }
  }
  EXPECT_GT(inside, 0) << "some tips fell inside a tumour";
}

TEST(TumourMargin, ALivePeerReadsTheMarginInRas)
{
  vp::TrackedFrame frame;
  frame.Tumour.emplace();
  frame.Tumour->Tumours.resize(2);
  frame.Tumour->Tumours[0] = { "a", 12.0, { 1, 2, 3 }, false, true, 11.0, MarginLevel::Clear };
  frame.Tumour->Tumours[1] = { "b", -1.5, { 4, 5, 6 }, false, false, 0.0, MarginLevel::Inside };
  frame.Tumour->Worst = 1;
  frame.Tumour->Level = MarginLevel::Inside;
  const nlohmann::json j = nlohmann::json::parse(vp::LiveFrameJson(frame));
  const nlohmann::json& t = j.at("tumour");
  EXPECT_EQ(t.at("level"), "inside");
  EXPECT_EQ(t.at("id"), "b");
  EXPECT_EQ(t.at("tumour_mm").get<double>(), -1.5);
  EXPECT_EQ(t.at("tumours").at("a").at("point"), nlohmann::json::array({ -1.0, -2.0, 3.0 })) << "RAS, as a Slicer peer shows";
  EXPECT_EQ(t.at("tumours").at("a").at("surface_mm").get<double>(), 11.0);
  EXPECT_TRUE(t.at("tumours").at("b").at("surface_mm").is_null());
  EXPECT_EQ(t.at("tumours").at("a").at("level"), "clear");
  frame.Tumour.reset();
  EXPECT_FALSE(nlohmann::json::parse(vp::LiveFrameJson(frame)).contains("tumour")) << "no tumour, no key";
}
