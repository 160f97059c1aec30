// The shape every front end shares: one scene request opened by the logic, one tracking session
// for every loop. Against analytic shapes: a sphere of radius 10 mm at the origin, a capped
// cylinder for a scalpel whose tip is its lower end.
#include "vpAnalyticShapes.h"
#include "vpDistanceEngineFactory.h"
#include "vpInputError.h"
#include "vpSceneRequest.h"
#include "vpTestSupport.h"
#include "vpTrackingSession.h"
#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselMeshWriter.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityParameters.h"

#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
const double Origin[3] = { 0, 0, 0 };

std::string WriteStl(const std::string& dir, const std::string& name, vtkPolyData* mesh)
{
  const std::string path = dir + "/" + name;
  vtkNew<vtkVesselMeshWriter> writer;
  writer->SetFileName(path);
  writer->SetInputData(mesh);
  writer->Write();
  return path;
}

/// The scalpel pointing down -z with its tip (the model's origin) at x on the x axis.
vp::TrackedPose TipAt(double timeS, double x)
{
  return { timeS, { 1, 0, 0, x, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 } };
}

/// The sphere (radius 10 mm at the origin) as the one vessel class, the tip alone measured.
vp::SceneRequest SphereTipOnly()
{
  vp::SceneRequest request;
  request.Vessels = { { "portal_vein", "in memory", vp::MakeSphere(Origin, 10.0, 30, 60), std::nullopt } };
  request.ComputeSurfaceDistance = false;
  return request;
}

/// 40 poses in from 30 mm to 6.6 mm from the sphere's centre: every level on the way.
std::vector<vp::TrackedPose> InFromOutside()
{
  std::vector<vp::TrackedPose> poses;
  for (int i = 0; i < 40; ++i)
  {
    poses.push_back(TipAt(0.02 * i, 30.0 - 0.6 * i));
  }
  return poses;
}

class SceneRequest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("scene_request");
    this->VesselFile = WriteStl(this->Dir, "sphere.stl", vp::MakeSphere(Origin, 10.0, 40, 80));
    const double up[3] = { 0, 0, 1 }, centre[3] = { 0, 0, 20 }; // the lower cap at the tip
    this->ScalpelFile = WriteStl(this->Dir, "cylinder.stl", vp::MakeCappedCylinder(centre, up, 1.0, 40.0, 16));
    this->Request.Vessels = { { "portal_vein", this->VesselFile, nullptr, std::nullopt } };
    this->Request.ScalpelFile = this->ScalpelFile;
    this->Request.Tip.TipMm = std::array<double, 3>{ 0, 0, 0 };
    this->Request.Tip.Axis = std::array<double, 3>{ 0, 0, -1 };
  }
  std::string Dir, VesselFile, ScalpelFile;
  vp::SceneRequest Request;
};

TEST_F(SceneRequest, OpensTheFilesAndTheLogicAnswersAsTheShapesSay)
{
  this->Request.LiverFile = this->VesselFile; // any surface will do: it is shown, not measured
  vtkNew<vtkVesselProximityLogic> logic;
  const vp::OpenedScene scene = logic->OpenScene(this->Request);
  ASSERT_EQ(scene.Vessels.size(), 1u);
  EXPECT_EQ(scene.Vessels[0].FileName, this->VesselFile);
  EXPECT_FALSE(scene.Vessels[0].Repair);
  ASSERT_TRUE(scene.Liver);
  EXPECT_GT(scene.Liver->GetNumberOfPolys(), 1000);
  EXPECT_TRUE(scene.EngineNote.empty());
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1);
  EXPECT_EQ(logic->GetParameters()->GetFrameBudgetMs(), vp::TrackingSettings().FrameBudgetMs);
  EXPECT_NE(logic->GetScalpel()->GetTipSource().find("TipMm"), std::string::npos) << logic->GetScalpel()->GetTipSource();

  vp::TrackingSession session(logic);
  for (const double x : { 30.0, 15.0, 11.0, 5.0 })
  {
    const vp::TrackedFrame& f = session.Process(TipAt(x / 100.0, x));
    const vp::ClassProximity& c = f.Proximity.Classes.at(0);
    ASSERT_TRUE(c.InRange) << x;
    EXPECT_NEAR(c.DistanceMm, std::abs(x - 10.0), 0.05) << x; // the facets lie within 0.05 mm of the sphere
    EXPECT_EQ(c.Inside.value_or(false), x < 10.0) << x;
    ASSERT_EQ(f.Surface.size(), 1u) << "the whole instrument is measured by default";
    EXPECT_LE(f.Surface[0].DistanceMm, c.DistanceMm + 1e-9);
  }
  EXPECT_EQ(logic->GetLastFrame().Level, vp::DangerLevel::Breach);
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1) << "the scalpel moved: nothing rebuilt";
}

TEST_F(SceneRequest, RepairsAndTakesSurfacesFromMemory)
{
  this->Request.Vessels = { { "portal_vein", "in memory", vp::MakeSphere(Origin, 10.0, 40, 80), std::nullopt },
    { "hepatic_vein", this->VesselFile, nullptr, std::nullopt } };
  this->Request.RepairVessels = true;
  this->Request.Scalpel = vtkSmartPointer<vtkScalpelModel>::New(); // a model already made wins over the file
  this->Request.ComputeSurfaceDistance = false;
  vtkNew<vtkVesselProximityLogic> logic;
  const vp::OpenedScene scene = logic->OpenScene(this->Request);
  ASSERT_EQ(scene.Vessels.size(), 2u);
  EXPECT_TRUE(scene.Vessels[0].Repair && scene.Vessels[1].Repair);
  EXPECT_EQ(logic->GetScalpel(), this->Request.Scalpel.Get());
  EXPECT_EQ(logic->GetVesselClassName(1), "hepatic_vein");
  const vp::TrackedFrame& f = vp::TrackingSession(logic).Process(TipAt(0.0, 20.0));
  EXPECT_TRUE(f.Surface.empty());
  EXPECT_NEAR(f.Proximity.Classes.at(1).DistanceMm, 10.0, 0.05);
}

TEST_F(SceneRequest, RefusesEachProblemInItsOwnMessage)
{
  vtkNew<vtkVesselProximityLogic> logic;
  auto refusal = [&](const std::function<void(vp::SceneRequest&)>& change) -> std::string {
    vp::SceneRequest request = this->Request;
    change(request);
    try
    {
      logic->OpenScene(request);
    }
    catch (const vp::ParameterError& e)
    {
      return "parameter " + e.GetParameter() + ": " + e.GetProblem();
    }
    catch (const std::exception& e)
    {
      return e.what();
    }
    return "opened";
  };
  EXPECT_EQ(refusal([&](vp::SceneRequest& r) { r.Vessels[0].FileName = this->Dir + "/none.stl"; }).rfind(this->Dir + "/none.stl: ", 0), 0u);
  EXPECT_EQ(refusal([&](vp::SceneRequest& r) { r.Vessels.push_back(r.Vessels[0]); }),
    "parameter Vessels: class 'portal_vein' is given twice");
  EXPECT_EQ(refusal([&](vp::SceneRequest& r) { r.ScalpelFile = this->Dir + "/none.stl"; }).rfind(this->Dir + "/none.stl: ", 0), 0u);
  EXPECT_EQ(refusal([](vp::SceneRequest& r) { r.Engine.RangeMm = -1.0; }).rfind("parameter RangeMm: ", 0), 0u);
  EXPECT_EQ(refusal([](vp::SceneRequest& r) { r.InstrumentRangeMm = -1.0; }).rfind("parameter InstrumentRangeMm: ", 0), 0u);
  // The settings against the engine: a range short of the caution threshold hides a near class.
  const std::string shortRange = refusal([](vp::SceneRequest& r) { r.Engine.RangeMm = 5.0; });
  EXPECT_NE(shortRange.find("caution threshold"), std::string::npos) << shortRange;
  EXPECT_EQ(refusal([](vp::SceneRequest&) {}), "opened");
}

TEST_F(SceneRequest, NamesTheDeviceSettingAsTheFrontEndCallsIt)
{
  this->Request.Engine.Method = "zbuffer";
  this->Request.Engine.DeviceSelector = "no-such-gpu";
  vtkNew<vtkVesselProximityLogic> logic;
  try
  {
    logic->OpenScene(this->Request);
    ADD_FAILURE() << "a device that matches nothing was opened";
  }
  catch (const vp::DeviceError& e)
  {
    if (e.GetSetting().empty())
    {
      GTEST_SKIP() << "no Vulkan device on this machine: " << e.what();
    }
    EXPECT_EQ(e.GetSetting(), "DeviceSelector");
    EXPECT_EQ(std::string(e.what()).rfind("no Vulkan device matches DeviceSelector 'no-such-gpu' (available: 0: ", 0), 0u) << e.what();
    EXPECT_EQ(e.Describe("--device").rfind("no Vulkan device matches --device 'no-such-gpu' (available: 0: ", 0), 0u);
  }
}

TEST_F(SceneRequest, TheInstrumentMethodsAgreeAndTheRangeAndPenetrationAreHonoured)
{
  const std::vector<vp::TrackedPose> poses = { TipAt(0.0, 25.0), TipAt(0.1, 16.0), TipAt(0.2, 12.5), TipAt(0.3, 9.0) };
  auto surfaces = [&](vp::InstrumentMethod method, double rangeMm, bool penetration) {
    this->Request.Instrument = method;
    this->Request.InstrumentRangeMm = rangeMm;
    this->Request.ComputePenetration = penetration;
    vtkNew<vtkVesselProximityLogic> logic;
    logic->OpenScene(this->Request);
    vp::TrackingSession session(logic);
    vp::PoseListSource source(poses, "the test's poses");
    std::vector<vp::TrackedFrame> frames;
    EXPECT_TRUE(session.Run(source, [&](const vp::TrackedFrame& f) { frames.push_back(f); }));
    return frames;
  };
  const auto fcl = surfaces(vp::InstrumentMethod::Automatic, 0.0, true);
  const auto spheres = surfaces(vp::InstrumentMethod::BoundingSpheres, 0.0, false);
  const auto near = surfaces(vp::InstrumentMethod::Fcl, 4.0, false);
  ASSERT_EQ(fcl.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const double x = poses[i].ModelToWorld[3];
    ASSERT_EQ(fcl[i].Surface.size(), 1u);
    // The cylinder (radius 1) stands on the tip: its nearest point to the sphere is within 1 mm of the tip's.
    EXPECT_NEAR(fcl[i].Surface[0].DistanceMm, spheres[i].Surface[0].DistanceMm, 1e-6) << x;
    EXPECT_LE(fcl[i].Surface[0].DistanceMm, std::abs(x - 10.0) + 0.05) << x;
    EXPECT_EQ(fcl[i].Penetrations.size(), 1u);
    EXPECT_TRUE(spheres[i].Penetrations.empty());
    EXPECT_EQ(near[i].Surface[0].InRange, fcl[i].Surface[0].InRange && fcl[i].Surface[0].DistanceMm <= 4.0) << x;
  }
  EXPECT_GT(fcl.back().Penetrations[0].DepthMm, 0.5) << "the tip is 1 mm inside";
}

TEST(TrackingSession, ASourceAndSinglePosesGiveTheSameFramesAndARestartBeginsAtFrameZero)
{
  vtkNew<vtkVesselProximityLogic> logic;
  logic->OpenScene(SphereTipOnly());
  std::vector<vp::TrackedPose> poses = InFromOutside();
  vp::TrackingSession session(logic);
  vp::PoseListSource source(poses, "the test's poses");
  std::vector<vp::TrackedFrame> run;
  ASSERT_TRUE(session.Run(source, [&](const vp::TrackedFrame& f) { run.push_back(f); }));
  EXPECT_EQ(session.GetNumberOfFrames(), poses.size());
  session.Restart();
  EXPECT_EQ(session.GetNumberOfFrames(), 0u);
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const vp::TrackedFrame& f = session.Process(poses[i]);
    EXPECT_EQ(f.Frame, static_cast<int>(i));
    EXPECT_EQ(f.Level, run[i].Level) << i;
    EXPECT_EQ(f.Proximity.Classes[0].DistanceMm, run[i].Proximity.Classes[0].DistanceMm) << i;
  }
  EXPECT_EQ(run.front().Level, vp::DangerLevel::Safe);
  EXPECT_EQ(run.back().Level, vp::DangerLevel::Breach);
}
/// An output that writes down what it hears, in order, as "name:event:frame".
class Log : public vp::FrameOutput
{
public:
  Log(std::string name, std::vector<std::string>& lines)
    : Name(std::move(name))
    , Lines(lines)
  {
  }
  void OnLevelChange(const vp::DangerLevelChange& c) override
  {
    this->Lines.push_back(this->Name + ":change:" + std::to_string(c.Frame) + ":" + vp::DangerLevelName(c.To));
  }
  void OnFrame(const vp::TrackedFrame& f) override { this->Lines.push_back(this->Name + ":frame:" + std::to_string(f.Frame)); }
  void OnLost(const vp::TrackedPose&) override { this->Lines.push_back(this->Name + ":lost"); }
  void OnEnd() override { this->Lines.push_back(this->Name + ":end"); }

private:
  std::string Name;
  std::vector<std::string>& Lines;
};

// The frame pipeline: every output hears, in the order added, each change of level before the
// frame that made it (once, as the logic's own observers do), each lost pose and the end once.
TEST(TrackingSession, OutputsHearEachChangeBeforeItsFrameEachLossAndTheEnd)
{
  vtkNew<vtkVesselProximityLogic> logic;
  logic->OpenScene(SphereTipOnly());
  std::vector<vp::TrackedPose> poses = InFromOutside();
  vp::TrackedPose lost;
  lost.Lost = true;
  poses.insert(poses.begin() + 20, lost);
  std::vector<vp::DangerLevelChange> observed; // what the logic's own observers hear
  vtkNew<vtkCallbackCommand> onChange;
  onChange->SetClientData(&observed);
  onChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<vp::DangerLevelChange>*>(client)->push_back(*static_cast<vp::DangerLevelChange*>(call));
  });
  logic->GetTrackingLogic()->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, onChange);
  std::vector<std::string> lines;
  Log first("a", lines), second("b", lines);
  vp::TrackingSession session(logic);
  session.AddOutput(&first);
  session.AddOutput(&second);
  vp::PoseListSource source(poses, "the test's poses");
  ASSERT_TRUE(session.Run(source));
  ASSERT_GE(observed.size(), 3u) << "safe to breach passes the levels between";
  std::vector<std::string> expected;
  std::size_t change = 0;
  for (int f = 0; f < 40; ++f)
  {
    if (f == 20)
    {
      expected.insert(expected.end(), { "a:lost", "b:lost" });
    }
    std::vector<std::string> changes;
    for (; change < observed.size() && observed[change].Frame == f; ++change)
    {
      changes.push_back(std::to_string(f) + ":" + vp::DangerLevelName(observed[change].To));
    }
    for (const char* name : { "a", "b" })
    {
      for (const std::string& c : changes)
      {
        expected.push_back(std::string(name) + ":change:" + c);
      }
      expected.push_back(std::string(name) + ":frame:" + std::to_string(f));
    }
  }
  expected.insert(expected.end(), { "a:end", "b:end" });
  EXPECT_EQ(change, observed.size());
  EXPECT_EQ(lines, expected);
  EXPECT_EQ(session.GetNumberOfLostPoses(), 1u);
}
// The engine registry is the one list of methods: each makes the engine it names (both and auto
// the z-buffer, or exact without a device), the front ends' lists are its subsets, and a name it
// lacks is refused with the list.
TEST(EngineRegistry, EachMethodMakesItsEngineAndTheFrontEndsOfferItsSubsets)
{
  std::vector<std::string> all;
  for (const vp::EngineMethod& m : vp::EngineMethods())
  {
    all.emplace_back(m.Name);
    vp::DistanceEngineSettings settings;
    settings.Method = m.Name;
    std::string note;
    vtkSmartPointer<vtkVesselDistanceEngine> engine;
    try
    {
      engine = vp::MakeDistanceEngine(settings, &note);
    }
    catch (const vp::DeviceError&)
    {
      EXPECT_TRUE(settings.Method == "zbuffer" || settings.Method == "both") << "only the z-buffer needs a device";
      continue;
    }
    ASSERT_TRUE(engine) << m.Name;
    const std::string made = engine->GetMethodName();
    if (settings.Method == "both" || settings.Method == "auto")
    {
      EXPECT_TRUE(made == "zbuffer" || (settings.Method == "auto" && made == "exact" && !note.empty())) << m.Name << " made " << made;
    }
    else
    {
      EXPECT_EQ(made, settings.Method);
    }
    EXPECT_EQ(engine->IsExact(), made == "exact" || made == "brute") << made;
    EXPECT_NE(std::string(m.Help).find(std::string(m.Name) + ": "), std::string::npos) << "the help names its method";
  }
  EXPECT_EQ(all, (std::vector<std::string>{ "exact", "zbuffer", "both", "brute", "auto" }));
  EXPECT_EQ(vp::EngineMethodNames(vp::OfferedForTips), all);
  EXPECT_EQ(vp::EngineMethodNames(vp::OfferedForTracking), (std::vector<std::string>{ "exact", "zbuffer", "both" }));
  EXPECT_EQ(vp::EngineMethodNames(vp::OfferedInView), (std::vector<std::string>{ "exact", "zbuffer" }));
  EXPECT_EQ(vp::EngineMethodNames(vp::OfferedToSlicerTips), (std::vector<std::string>{ "exact", "zbuffer", "both", "auto" }));
  EXPECT_EQ(vp::EngineMethodHelp({ "exact", "brute" }, "; "), "exact: Embree BVH, exact; brute: the paper's CPU algorithm");
  vp::DistanceEngineSettings unknown;
  unknown.Method = "fast";
  try
  {
    vp::MakeDistanceEngine(unknown);
    ADD_FAILURE() << "an unknown method was taken";
  }
  catch (const vp::ParameterError& e)
  {
    EXPECT_NE(std::string(e.what()).find("unknown method 'fast' (exact, zbuffer, both, brute, auto)"), std::string::npos) << e.what();
  }
}
// The exact answer beside an approximate engine's is the frame's own (TrackedFrame::Exact), from
// the one pose applied once: equal to the exact engine's for that tip; absent without the check.
TEST(TrackingSession, TheExactAnswerBesideTheZBufferIsInTheFrame)
{
  for (const bool compare : { true, false })
  {
    vp::SceneRequest request = SphereTipOnly();
    request.Engine.Method = "zbuffer";
    request.CompareWithExact = compare;
    vtkNew<vtkVesselProximityLogic> logic;
    try
    {
      logic->OpenScene(request);
    }
    catch (const vp::DeviceError& e)
    {
      GTEST_SKIP() << "no Vulkan device for the z-buffer: " << e.what();
    }
    vp::TrackingSession session(logic);
    const vp::TrackedFrame& frame = session.Process(TipAt(0.0, 14.5));
    ASSERT_EQ(frame.Exact.has_value(), compare);
    if (compare)
    {
      vtkNew<vtkExactVesselDistance> exact;
      exact->AddVessel("portal_vein", vp::MakeSphere(Origin, 10.0, 30, 60));
      vp::ProximityResult expected;
      exact->ComputeProximity(frame.TipMm, frame.AxisWorld, expected);
      EXPECT_EQ(frame.Exact->Classes[0].DistanceMm, expected.Classes[0].DistanceMm);
      EXPECT_NEAR(frame.Exact->Classes[0].DistanceMm, 4.5, 0.1) << "the tip 14.5 mm from the centre of a 10 mm sphere";
      EXPECT_LE(std::abs(frame.Proximity.Classes[0].DistanceMm - frame.Exact->Classes[0].DistanceMm), frame.Proximity.ErrorBoundMm);
    }
  }
}
// The tracking settings are held once, in the parameter set: the tracking logic reads them
// there (a change is seen by the next frame, no copy to go stale), and refuses its own setters.
TEST(TrackingSession, TheTrackingLogicReadsTheParameterSetsSettings)
{
  vtkNew<vtkVesselProximityLogic> logic;
  logic->OpenScene(SphereTipOnly());
  vtkScalpelTrackingLogic* tracking = logic->GetTrackingLogic();
  EXPECT_EQ(&tracking->GetDangerThresholds(), &logic->GetParameters()->GetTrackingSettings().Thresholds);
  logic->GetParameters()->SetHysteresisMm(1.25);
  EXPECT_EQ(tracking->GetHysteresisMm(), 1.25);
  EXPECT_THROW(tracking->SetHysteresisMm(0.5), std::logic_error);
  vp::HapticSettings haptic;
  haptic.StiffnessNPerMm = 0.2;
  logic->GetParameters()->SetHapticSettings(haptic);
  vp::TrackingSession session(logic);
  const vp::TrackedFrame& inside = session.Process(TipAt(0.0, 7.0)); // 3 mm inside the sphere
  ASSERT_TRUE(inside.Haptic.has_value());
  EXPECT_NEAR(inside.Haptic->ForceN, 0.2 * inside.Haptic->DepthMm, 1e-9);
  EXPECT_GT(inside.Haptic->DepthMm, 2.5);
}
} // namespace
