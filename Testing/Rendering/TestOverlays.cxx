// The overlays as an output of the logic's frames, and their pictures: the module's widget representation on
// the built-in phantom (torus portal vein, cylinder artery, sphere hepatic vein) with the
// built-in CUSA handpiece, at poses whose answers are known analytically.
#include "vpBuiltInPhantom.h"
#include "vpDangerBands.h"
#include "vpDangerLevels.h"
#include "vpDefaultScalpel.h"
#include "vpImageComparison.h"
#include "vpKeyFrames.h"
#include "vpPlotValues.h"
#include "vpScalpelLoader.h"
#include "vpTestSupport.h"
#include "vpVirtualDisplay.h"
#include "vtkClosestPointLineRepresentation.h"
#include "vtkDistancePlotRepresentation.h"
#include "vtkProximityReadoutRepresentation.h"
#include "vtkScalpelDangerRepresentation.h"
#include "vtkScalpelModel.h"
#include "vtkVesselModelsRepresentation.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityOverlays.h"
#include "vtkVesselProximityParameters.h"
#include "vpAnalyticShapes.h"
#include "vtkVesselProximityView.h"
#include "vpClearViewCamera.h"
#include "vpTipOcclusion.h"
#include "vpTrackingSession.h"
#include "vtkZBufferVesselDistance.h"
#include "vpVulkanContext.h"
#include "vpVesselLabelTable.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkPolyDataMapper.h>
#include <vtkLineSource.h>
#include <vtkActor2D.h>
#include <vtkTextActor.h>
#include <vtkCoordinate.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <gtest/gtest.h>

#include <map>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace
{
/// The scalpel pointing down (model +z turned onto world -z) with its tip at (0, -30, z), above
/// the front of the torus's tube (ring 30, tube 6): the distance to the portal vein is |z| - 6,
/// inside below z = 6. The artery (along x at y = 0, z = 25) and the hepatic vein (at 45, 30,
/// -10) stay more than 27 mm away.
std::array<double, 16> TipDownAt(double z)
{
  return { 1, 0, 0, 0, 0, -1, 0, -30, 0, 0, -1, z, 0, 0, 0, 1 };
}

vtkSmartPointer<vtkVesselProximityLogic> MakePhantomLogic(const std::string& tmp)
{
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  for (const auto& vessel : vp::MakeBuiltInVessels())
  {
    logic->AddVessel(vessel.first, vessel.second);
  }
  logic->SetScalpel(vp::LoadScalpel(vp::WriteDefaultScalpel(tmp), {}));
  logic->SetComputeSurfaceDistance(false);
  // The pictures must not depend on the machine's speed: no frame-budget line in them.
  logic->GetParameters()->SetFrameBudgetMs(0.0);
  return logic;
}

vp::TrackedPose Pose(double timeS, const std::array<double, 16>& m)
{
  vp::TrackedPose pose;
  pose.TimeS = timeS;
  pose.ModelToWorld = m;
  return pose;
}

int ClassIndex(vtkVesselProximityLogic* logic, const std::string& name)
{
  for (int i = 0; i < logic->GetNumberOfVessels(); ++i)
  {
    if (logic->GetVesselClassName(i) == name)
    {
      return i;
    }
  }
  return -1;
}
} // namespace

TEST(Overlays, FollowTheLogicAndRecolourOnlyOnLevelChanges)
{
  const std::string tmp = vp::test::MakeTempDir("overlays");
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkVesselProximityOverlays> overlays;
  overlays->SetRenderer(renderer);
  overlays->SetLogic(logic);
  vp::TrackingSession session(logic); // the overlays are an output of its frames
  session.AddOutput(overlays);

  // Vessel actors in the label table's colours, the same as the plot's lines (one colour per class).
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  for (const char* c : { "portal_vein", "hepatic_artery", "hepatic_vein" })
  {
    vtkActor* actor = overlays->GetVessels()->GetActor(c);
    ASSERT_NE(actor, nullptr) << c;
    const double* rgb = actor->GetProperty()->GetColor();
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(rgb[k], vp::ClassDisplayColour(c, 0)[k] / 255.0, 1e-12) << c;
      EXPECT_NEAR(rgb[k], table.Color(c)[k], 0.5 / 255.0) << c;
    }
  }

  // Straight down onto the torus tube, from 21 mm above its centre line to 1 mm above it.
  const int portal = ClassIndex(logic, "portal_vein");
  int changes = 0;
  vp::DangerLevel previous = vp::DangerLevel::Safe;
  const int colourChangesBefore = overlays->GetScalpel()->GetNumberOfColourChanges();
  for (int i = 0; i <= 40; ++i)
  {
    const double z = 21.0 - 0.5 * i; // 21 mm down to 1 mm: inside the tube below z = 6
    const vp::TrackedFrame& f = session.Process(Pose(0.02 * i, TipDownAt(z)));
    changes += f.Level != previous ? 1 : 0;
    previous = f.Level;
    // The scalpel wears the colour of the frame's level.
    const auto expected = vp::DangerLevelColour(f.Level);
    const double* rgb = overlays->GetScalpel()->GetActor()->GetProperty()->GetColor();
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(rgb[k], expected[k] / 255.0, 1e-12) << "frame " << i;
    }
    // Its pose is the actor's user matrix; the surface is untouched.
    const double* tipPoint = f.TipMm;
    EXPECT_NEAR(tipPoint[2], z, 1e-9);
    // The line runs from the tip to the portal vein's closest point, labelled with the distance.
    const vp::ClassProximity& p = f.Proximity.Classes[portal];
    ASSERT_TRUE(p.InRange);
    EXPECT_NEAR(p.DistanceMm, std::abs(z - 6.0), 0.05) << "frame " << i;
    ASSERT_TRUE(overlays->GetClosestPointLine()->IsShown());
    char label[64];
    std::snprintf(label, sizeof(label), z < 6.0 ? "portal vein %.1f mm inside" : "portal vein %.1f mm", p.DistanceMm);
    EXPECT_EQ(overlays->GetClosestPointLine()->GetLabelText(), label);
    // The readout's portal line carries the same number.
    char number[32];
    std::snprintf(number, sizeof(number), "%.1f mm", p.DistanceMm);
    EXPECT_NE(overlays->GetReadout()->GetLineText(portal + 1).find(number), std::string::npos)
      << overlays->GetReadout()->GetLineText(portal + 1);
  }
  // Safe (21 -> 15 mm away), caution, warning, danger, breach: four changes, four recolours.
  EXPECT_EQ(changes, 4);
  EXPECT_EQ(previous, vp::DangerLevel::Breach);
  EXPECT_EQ(overlays->GetScalpel()->GetNumberOfColourChanges() - colourChangesBefore, 4);
  EXPECT_EQ(overlays->GetReadout()->GetLineText(0), "BREACH: tip 5.0 mm inside the portal vein | exact engine") << "the level, its cause and the engine";
  EXPECT_EQ(overlays->GetPlot()->GetNumberOfSamples(), 41);
  // 41 poses, one build: nothing is rebuilt because the scalpel moved.
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1);
  std::filesystem::remove_all(tmp);
}

TEST(Overlays, ConfigurableColoursAndThresholds)
{
  const std::string tmp = vp::test::MakeTempDir("overlays_config");
  auto logic = MakePhantomLogic(tmp);
  logic->SetDangerThresholds({ 20.0, 12.0, 8.0 });
  vtkNew<vtkVesselProximityOverlays> overlays;
  overlays->SetLogic(logic);
  vp::TrackingSession session(logic); // the overlays are an output of its frames
  session.AddOutput(overlays);
  overlays->GetScalpel()->SetLevelColour(vp::DangerLevel::Warning, { 255, 200, 0 });
  // 10 mm from the tube: a warning with these thresholds (caution with the defaults), drawn in
  // the colour set for it.
  const vp::TrackedFrame& f = session.Process(Pose(0.0, TipDownAt(16.0)));
  EXPECT_EQ(f.Level, vp::DangerLevel::Warning);
  const double* rgb = overlays->GetScalpel()->GetActor()->GetProperty()->GetColor();
  EXPECT_NEAR(rgb[0], 1.0, 1e-12);
  EXPECT_NEAR(rgb[1], 200 / 255.0, 1e-12);
  EXPECT_NEAR(rgb[2], 0.0, 1e-12);
  std::filesystem::remove_all(tmp);
}

// The readout's last line speaks only of a frame over its budget: a budget no frame can meet puts
// it there, the next frame within a generous budget clears it.
TEST(Overlays, AFrameOverItsBudgetIsShownAndCleared)
{
  const std::string tmp = vp::test::MakeTempDir("overlays_budget");
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkVesselProximityOverlays> overlays;
  overlays->SetLogic(logic);
  vp::TrackingSession session(logic); // the overlays are an output of its frames
  session.AddOutput(overlays);
  vtkProximityReadoutRepresentation* readout = overlays->GetReadout();
  const int last = readout->GetNumberOfLines() - 1;
  session.Process(Pose(0.0, TipDownAt(16.0)));
  EXPECT_EQ(readout->GetLineText(last), "") << "budget off: nothing to say";
  logic->GetParameters()->SetFrameBudgetMs(1e-9);
  const vp::TrackedFrame& late = session.Process(Pose(0.02, TipDownAt(15.5)));
  ASSERT_TRUE(late.OverBudget);
  EXPECT_NE(readout->GetLineText(last).find("over the 0.0 ms budget"), std::string::npos) << readout->GetLineText(last);
  EXPECT_EQ(readout->GetLineText(last).find("frame "), 0u) << readout->GetLineText(last);
  logic->GetParameters()->SetFrameBudgetMs(60000.0);
  EXPECT_FALSE(session.Process(Pose(0.04, TipDownAt(15.0))).OverBudget);
  EXPECT_EQ(readout->GetLineText(last), "");
  std::filesystem::remove_all(tmp);
}

// The plot is drawn when a render shows it, not for every frame: frames without a render draw
// nothing, the next render draws once with every frame in it, and a render with no new frame
// (the camera moved) draws nothing.
TEST(Overlays, ThePlotIsDrawnOnlyWhenARenderShowsIt)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  const std::string tmp = vp::test::MakeTempDir("overlays_plot");
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(400, 300);
  view->SetLogic(logic);
  vtkDistancePlotRepresentation* plot = view->GetOverlays()->GetPlot();
  view->Render();
  const int before = plot->GetNumberOfRedraws();
  for (int i = 0; i < 30; ++i)
  {
    view->SetScalpelPose(TipDownAt(20.0 - 0.5 * i));
  }
  EXPECT_EQ(plot->GetNumberOfSamples(), 30);
  EXPECT_EQ(plot->GetNumberOfRedraws(), before) << "no render, no drawing";
  view->Render();
  EXPECT_EQ(plot->GetNumberOfRedraws(), before + 1);
  view->GetRenderer()->GetActiveCamera()->Azimuth(10);
  view->Render();
  EXPECT_EQ(plot->GetNumberOfRedraws(), before + 1) << "only the camera moved";
  view->SetScalpelPose(TipDownAt(5.0));
  ASSERT_NE(plot->GetImage(), nullptr); // asking for the picture draws it
  EXPECT_EQ(plot->GetNumberOfRedraws(), before + 2);
  std::filesystem::remove_all(tmp);
}

// A module hands the view its widget representation (issue 15): the view draws with those overlays,
// hands them the logic it already shows, and the ones it had leave the renderer.
TEST(Overlays, AViewTakesTheModulesOverlays)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  const std::string tmp = vp::test::MakeTempDir("overlays_given");
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(400, 300);
  view->SetLogic(logic);
  view->Render();
  const int propsWithOne = view->GetRenderer()->GetViewProps()->GetNumberOfItems();
  vtkSmartPointer<vtkVesselProximityOverlays> first = view->GetOverlays();
  vtkNew<vtkVesselProximityOverlays> given;
  view->SetOverlays(given);
  EXPECT_EQ(view->GetOverlays(), given.GetPointer());
  EXPECT_EQ(given->GetLogic(), logic.GetPointer()) << "the logic already shown is handed on";
  EXPECT_EQ(first->GetRenderer(), nullptr) << "the overlays it had leave the renderer";
  view->SetScalpelPose(TipDownAt(5.0));
  view->Render();
  EXPECT_EQ(view->GetRenderer()->GetViewProps()->GetNumberOfItems(), propsWithOne) << "one set of overlays drawn";
  EXPECT_EQ(given->GetPlot()->GetNumberOfSamples(), 1) << "the given overlays follow the logic";
  std::filesystem::remove_all(tmp);
}

// With the whole instrument measured, each class line says where the instrument is: its distance,
// or inside, its depth and volume.
namespace
{
/// The readout's tests' frame: the portal vein at portalMm, the hepatic vein at hepaticMm (NaN:
/// out of range).
vp::ProximityResult PortalAndHepaticVein(double portalMm, double hepaticMm)
{
  vp::ProximityResult proximity;
  proximity.Classes.resize(2);
  proximity.Classes[0].ClassName = "portal_vein";
  proximity.Classes[0].InRange = true;
  proximity.Classes[0].DistanceMm = portalMm;
  proximity.Classes[1].ClassName = "hepatic_vein";
  proximity.Classes[1].InRange = !std::isnan(hepaticMm);
  proximity.Classes[1].DistanceMm = std::isnan(hepaticMm) ? 0.0 : hepaticMm;
  return proximity;
}

/// A readout of those two classes, in colours of their own.
vtkSmartPointer<vtkProximityReadoutRepresentation> PortalAndHepaticVeinReadout()
{
  auto readout = vtkSmartPointer<vtkProximityReadoutRepresentation>::New();
  readout->SetClasses({ "portal_vein", "hepatic_vein" }, { { 0, 0.6, 0.8 }, { 0.4, 0.2, 0.7 } });
  return readout;
}
} // namespace

TEST(Overlays, ATumourIsShownInItsColourAndItsMarginRead)
{
  const std::string tmp = vp::test::MakeTempDir("overlays_tumour");
  auto logic = MakePhantomLogic(tmp);
  // A sphere of radius 5 mm centred 40 mm above the torus tube's top: the tip at (0, -30, z) is
  // 35 - z from it (the facets within 0.06 mm).
  const double centre[3] = { 0, -30, 40 };
  logic->GetParameters()->SetTumour("lesion", vp::MakeSphere(centre, 5.0, 24, 48));
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkVesselProximityOverlays> overlays;
  overlays->SetRenderer(renderer);
  overlays->SetLogic(logic);
  vp::TrackingSession session(logic); // the overlays are an output of its frames
  session.AddOutput(overlays);
  vtkActor* tumour = overlays->GetVessels()->GetTumourActor("lesion");
  ASSERT_NE(tumour, nullptr);
  EXPECT_TRUE(renderer->GetActors()->IsItemPresent(tumour));
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(tumour->GetProperty()->GetColor()[k], vp::TumourDisplayColour[k] / 255.0, 1e-12);
  }
  EXPECT_EQ(tumour->GetProperty()->GetOpacity(), 0.5);
  vtkProximityReadoutRepresentation* readout = overlays->GetReadout();
  const int margin = readout->GetNumberOfLines() - 2;
  EXPECT_EQ(readout->GetLineText(margin), "") << "no pose yet";
  session.Process(Pose(0.0, TipDownAt(21.0)));
  EXPECT_NE(readout->GetLineText(margin).find("tumour lesion"), std::string::npos) << readout->GetLineText(margin);
  EXPECT_NE(readout->GetLineText(margin).find("14.0 mm  CLEAR  (margin 5 mm)"), std::string::npos) << readout->GetLineText(margin);
  session.Process(Pose(0.1, TipDownAt(32.0)));
  EXPECT_NE(readout->GetLineText(margin).find("3.0 mm  VIOLATED"), std::string::npos) << readout->GetLineText(margin);
  session.Process(Pose(0.2, TipDownAt(37.0)));
  EXPECT_NE(readout->GetLineText(margin).find("2.0 mm inside  INSIDE"), std::string::npos) << readout->GetLineText(margin);
  overlays->ShowTrackingLost(250.0);
  EXPECT_EQ(readout->GetLineText(margin), "tumour                -") << "no distance read as current";
}

/// A frame of these answers and tip levels (and the instrument's, when measured).
vp::TrackedFrame FrameOf(const vp::ProximityResult& proximity, const std::vector<vp::DangerLevel>& tipLevels,
  const std::vector<vp::SurfaceProximity>& surface = {}, const std::vector<vp::Penetration>& penetrations = {},
  const std::vector<vp::DangerLevel>& instrumentLevels = {})
{
  vp::TrackedFrame frame;
  frame.Proximity = proximity;
  frame.ClassLevels = tipLevels;
  frame.Surface = surface;
  frame.Penetrations = penetrations;
  frame.InstrumentClassLevels = instrumentLevels;
  return frame;
}

TEST(Overlays, ReadoutShowsTheInstrumentBesideTheTip)
{
  const auto readout = PortalAndHepaticVeinReadout();
  vp::ProximityResult proximity = PortalAndHepaticVein(0.6, 3.3);
  proximity.Classes[0].Inside = true;
  std::vector<vp::SurfaceProximity> surface(2);
  surface[0].InRange = true;
  surface[1].InRange = true;
  surface[1].DistanceMm = 2.58;
  std::vector<vp::Penetration> penetrations(2);
  penetrations[0].DepthMm = 1.02;
  penetrations[0].VolumeMm3 = 3.71;
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Breach, vp::DangerLevel::Warning }, surface, penetrations,
                       { vp::DangerLevel::Breach, vp::DangerLevel::Warning }),
    "BREACH");
  EXPECT_NE(readout->GetLineText(1).find("tool 1.0 mm in, 3.7 mm^3  breach"), std::string::npos) << readout->GetLineText(1);
  EXPECT_NE(readout->GetLineText(2).find("tool 2.6 mm  warning"), std::string::npos) << readout->GetLineText(2);
  // Without the whole instrument: the tip alone, as before.
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Breach, vp::DangerLevel::Warning }), "BREACH");
  EXPECT_EQ(readout->GetLineText(1).find("tool"), std::string::npos) << readout->GetLineText(1);
}

// The screen says whose numbers they are: the engine, and for the z-buffer its bound, each class's
// distance as the interval the truth lies in (its "0.0 mm danger" was a tip 0.032 mm outside).
TEST(Overlays, TheReadoutNamesItsEngineAndShowsABoundAsAnInterval)
{
  const auto readout = PortalAndHepaticVeinReadout();
  vp::ProximityResult proximity = PortalAndHepaticVein(0.2, 3.3);
  proximity.ErrorBoundMm = 0.347;
  readout->SetEngine("zbuffer");
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Danger, vp::DangerLevel::Warning }), "DANGER");
  EXPECT_EQ(readout->GetLineText(0), "DANGER   | z-buffer engine, within 0.35 mm");
  EXPECT_NE(readout->GetLineText(1).find("0.0-0.5 mm"), std::string::npos) << readout->GetLineText(1);
  EXPECT_NE(readout->GetLineText(2).find("3.0-3.6 mm"), std::string::npos) << readout->GetLineText(2);
  // With the exact engine's answer computed beside it (--method both), that too.
  vp::ProximityResult exact = proximity;
  exact.ErrorBoundMm = 0.0;
  exact.Classes[0].DistanceMm = 0.032;
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Danger, vp::DangerLevel::Warning }), "DANGER", &exact);
  EXPECT_EQ(readout->GetLineText(0), "DANGER   | z-buffer engine sets the level, within 0.35 mm");
  EXPECT_NE(readout->GetLineText(1).find("0.0-0.5 mm  danger  (exact 0.0)"), std::string::npos) << readout->GetLineText(1);
  EXPECT_NE(readout->GetLineText(2).find("(exact 3.3)"), std::string::npos) << readout->GetLineText(2);
  proximity.ErrorBoundMm = 0.0;
  readout->SetEngine("exact");
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Danger, vp::DangerLevel::Warning }), "DANGER");
  EXPECT_EQ(readout->GetLineText(0), "DANGER   | exact engine");
  EXPECT_NE(readout->GetLineText(1).find(" 0.2 mm"), std::string::npos) << readout->GetLineText(1);
}

// A live stream that stopped: the readout says so and shows no distance as current, until the
// next frame gives them back.
TEST(Overlays, TrackingLostShowsNoDistanceAsCurrent)
{
  const auto readout = PortalAndHepaticVeinReadout();
  const vp::ProximityResult proximity = PortalAndHepaticVein(4.2, NAN);
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Warning, vp::DangerLevel::Safe }), "WARNING");
  EXPECT_NE(readout->GetLineText(1).find("4.2 mm"), std::string::npos);
  readout->ShowTrackingLost(250.0);
  EXPECT_EQ(readout->GetLineText(0), "TRACKING LOST (no pose for 250 ms)");
  for (int line = 1; line <= 2; ++line)
  {
    EXPECT_EQ(readout->GetLineText(line).find("mm"), std::string::npos) << readout->GetLineText(line);
    EXPECT_EQ(readout->GetLineText(line).back(), '-') << readout->GetLineText(line);
  }
  readout->ShowFrame(FrameOf(proximity, { vp::DangerLevel::Warning, vp::DangerLevel::Safe }), "WARNING");
  EXPECT_EQ(readout->GetLineText(0), "WARNING");
  EXPECT_NE(readout->GetLineText(1).find("4.2 mm"), std::string::npos);
}

// The live plot writes the instrument's largest penetration volume in its window at the line's
// deepest point: two plots of the same lines, one with a volume and one without, differ there.
TEST(Overlays, ThePlotWritesTheInstrumentsPenetrationVolumeAtItsDeepest)
{
  vtkNew<vtkDistancePlotRepresentation> plot;
  auto image = [&](double volumeMm3) {
    plot->SetClasses({ "portal_vein" });
    for (int i = 0; i < 20; ++i)
    {
      vp::TrackedFrame f;
      f.TimeS = 0.1 * i;
      f.Proximity.Classes.resize(1);
      f.Proximity.Classes[0].InRange = true;
      f.Proximity.Classes[0].DistanceMm = 3.0;
      f.Surface.resize(1);
      f.Surface[0].InRange = true;
      f.Penetrations.resize(1);
      f.Penetrations[0].DepthMm = i >= 10 ? 1.0 : 0.0;
      f.Penetrations[0].VolumeMm3 = i >= 10 ? volumeMm3 : 0.0;
      plot->AddFrame(f);
    }
    vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
    copy->DeepCopy(plot->GetImage());
    return copy;
  };
  vtkSmartPointer<vtkImageData> with = image(3.7), without = image(0.0);
  int dims[3];
  with->GetDimensions(dims);
  int differing = 0, lowest = dims[1], highest = -1, left = dims[0], right = -1;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const auto* a = static_cast<unsigned char*>(with->GetScalarPointer(x, y, 0));
      const auto* b = static_cast<unsigned char*>(without->GetScalarPointer(x, y, 0));
      if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2])
      {
        ++differing;
        lowest = std::min(lowest, y);
        highest = std::max(highest, y);
        left = std::min(left, x);
        right = std::max(right, x);
      }
    }
  }
  EXPECT_EQ(vp::InstrumentVolumeNote(3.7), "up to 3.7 mm^3 in");
  EXPECT_EQ(vp::InstrumentVolumeNote(0.0), "");
  EXPECT_GT(differing, 50) << "the volume is not written";
  // Only a line of text differs, in the lower half (below the zero line, where the instrument's
  // 1 mm penetration is drawn) and in the plot's left two thirds, not the legend.
  EXPECT_LT(highest - lowest, 20);
  EXPECT_LT(highest, dims[1] / 2);
  EXPECT_LT(right, dims[0] * 2 / 3);
  EXPECT_GT(left, 0);
}

TEST(Overlays, ZBufferLayersAreNotRebuiltWhenTheScalpelMoves)
{
  try
  {
    vp::VulkanContext probe;
  }
  catch (const vp::DeviceError& e)
  {
    GTEST_SKIP() << "no Vulkan device: " << e.what();
  }
  const std::string tmp = vp::test::MakeTempDir("overlays_zbuffer");
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkZBufferVesselDistance> zbuffer;
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::FixedAroundVessels);
  logic->SetDistanceEngine(zbuffer);
  vtkNew<vtkVesselProximityOverlays> overlays;
  overlays->SetLogic(logic);
  vp::TrackingSession session(logic); // the overlays are an output of its frames
  session.AddOutput(overlays);
  session.Process(Pose(0.0, TipDownAt(20.0)));
  const int renders = zbuffer->GetNumberOfRenders();
  for (int i = 1; i <= 20; ++i)
  {
    session.Process(Pose(0.02 * i, TipDownAt(20.0 - 0.5 * i)));
  }
  EXPECT_EQ(zbuffer->GetNumberOfRenders(), renders);
  EXPECT_EQ(logic->GetNumberOfBuilds(), 1);
  EXPECT_EQ(overlays->GetPlot()->GetNumberOfSamples(), 21);
  std::filesystem::remove_all(tmp);
}

// ---- image regression ------------------------------------------------------------------------

namespace
{
struct Shot
{
  const char* Name;
  double Z; // tip height (see TipDownAt)
};

// Names the parameter in test listings (ctest shows it) instead of its bytes.
void PrintTo(const Shot& shot, std::ostream* os)
{
  *os << shot.Name;
}

/// Renders the overlays at a fixed pose, after the same approach, in a fixed small window.
std::string RenderShot(const std::string& tmp, const Shot& shot)
{
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(960, 600);
  view->SetLogic(logic);
  // From anterior and 40 degrees above: the torus shows as a ring, the scalpel comes down on it.
  view->GetRenderer()->GetActiveCamera()->Elevation(40);
  view->GetRenderer()->GetActiveCamera()->OrthogonalizeViewUp();
  view->GetRenderer()->ResetCameraClippingRange();
  // The approach from 20 mm above, 0.5 mm per frame, so the plot has a history.
  std::vector<vp::TrackedPose> poses;
  for (int i = 0; 20.0 - 0.5 * i >= shot.Z - 1e-9; ++i)
  {
    poses.push_back(Pose(0.02 * i, TipDownAt(20.0 - 0.5 * i)));
  }
  view->SetPoses(poses);
  for (int i = 0; i < view->GetNumberOfPoses(); ++i)
  {
    view->ShowPose(i);
  }
  const std::string file = tmp + "/" + shot.Name + ".png";
  view->SaveScreenshot(file);
  return file;
}

std::string BaselineDir()
{
  return std::string(VP_SOURCE_DIR) + "/Testing/Data/Baseline";
}
} // namespace

/// An image test: a display to render on (skipped, saying why, without one), and the picture
/// compared with its baseline (or, with VP_UPDATE_BASELINES, written as the baseline).
template <typename Param>
class ImageTest : public ::testing::TestWithParam<Param>
{
protected:
  void SetUp() override
  {
    if (!this->Display.Ensure())
    {
      GTEST_SKIP() << "no display for rendering: " << this->Display.GetProblem();
    }
  }
  /// Tolerance: antialiased edges and text may move by a pixel between GL drivers; a changed
  /// colour, a missing actor or a moved overlay changes far more than 0.5% of the pixels. The
  /// temporary folder goes when the picture matches.
  void ExpectBaseline(const std::string& actual, const std::string& baselineName, const std::string& tmp)
  {
    const std::string baseline = BaselineDir() + "/" + baselineName;
    if (std::getenv("VP_UPDATE_BASELINES"))
    {
      std::filesystem::copy_file(actual, baseline, std::filesystem::copy_options::overwrite_existing);
      GTEST_SKIP() << "baseline written: " << baseline;
    }
    const vp::ImageDifference d = vp::CompareImages(actual, baseline, actual.substr(0, actual.size() - 4) + "_difference.png");
    EXPECT_TRUE(d.SameSize) << actual << " vs " << baseline;
    EXPECT_LT(d.FractionDifferent, 0.005) << "actual " << actual << ", difference image beside it";
    EXPECT_LT(d.MeanAbsDifference, 1.0) << actual;
    if (!this->HasFailure())
    {
      std::filesystem::remove_all(tmp);
    }
  }
  vp::VirtualDisplay Display;
};

class OverlayImages : public ImageTest<Shot>
{
};

TEST_P(OverlayImages, MatchTheBaseline)
{
  const Shot shot = GetParam();
  const std::string tmp = vp::test::MakeTempDir(std::string("image_") + shot.Name);
  this->ExpectBaseline(RenderShot(tmp, shot), std::string("overlays_") + shot.Name + ".png", tmp);
}

INSTANTIATE_TEST_SUITE_P(Poses, OverlayImages,
  ::testing::Values(Shot{ "safe", 17.0 }, Shot{ "warning", 10.0 }, Shot{ "danger", 7.5 }, Shot{ "breach", 5.0 }),
  [](const ::testing::TestParamInfo<Shot>& info) { return std::string(info.param.Name); });

class KeyFrameImages : public ImageTest<const char*>
{
};

// The tip rising towards a tumour 40 mm above the torus (radius 5, margin 5 mm): the key frame at
// the margin's change to violated is found in the run, captioned in words, and its picture (the
// headline naming the margin, the tumour in its colour) matches its baseline.
TEST_P(KeyFrameImages, TheMarginsChangeIsAKeyFrameAndMatchesTheBaseline)
{
  const std::string name = GetParam();
  const std::string tmp = vp::test::MakeTempDir("keyframe_" + name);
  auto logic = MakePhantomLogic(tmp);
  const double centre[3] = { 0, -30, 40 };
  logic->GetParameters()->SetTumour("lesion", vp::MakeSphere(centre, 5.0, 24, 48));
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(960, 600);
  view->SetLogic(logic);
  view->SetCameraPreset(vtkVesselProximityView::CameraPreset::Lateral);
  std::vector<vp::TrackedPose> poses;
  for (int i = 0; 21.0 + 0.5 * i <= 33.0 + 1e-9; ++i)
  {
    poses.push_back(Pose(0.2 * i, TipDownAt(21.0 + 0.5 * i)));
  }
  view->SetPoses(poses);
  vp::KeyFrameFinder finder;
  for (int i = 0; i < view->GetNumberOfPoses(); ++i)
  {
    view->ShowPose(i);
    finder.AddFrame(logic->GetLastFrame());
  }
  const std::vector<vp::KeyFrame> keys = finder.GetKeyFrames();
  const auto key = std::find_if(keys.begin(), keys.end(), [&](const vp::KeyFrame& k) { return k.Name.find(name) != std::string::npos; });
  ASSERT_NE(key, keys.end()) << "no key frame named " << name;
  // The margin (5 mm) is crossed between tip heights 29.5 (5.5 mm) and 30.5 (4.5 mm).
  EXPECT_EQ(key->PoseIndex, 19u) << key->Caption;
  EXPECT_NE(key->Caption.find("tumour lesion"), std::string::npos) << key->Caption;
  view->ShowPose(static_cast<int>(key->PoseIndex));
  const std::string file = tmp + "/keyframe_" + name + ".png";
  view->SaveScreenshot(file);
  this->ExpectBaseline(file, "keyframe_" + name + ".png", tmp);
}

INSTANTIATE_TEST_SUITE_P(Margin, KeyFrameImages, ::testing::Values("margin_violated"),
  [](const ::testing::TestParamInfo<const char*>&) { return std::string("margin_violated"); });

TEST(OverlayImagesComparison, TellsDifferentLevelsApart)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  // The tolerance above must not let one level's picture pass for another's: the safe scene
  // against the breach baseline differs in the scalpel's colour, the line and the readouts.
  const std::string tmp = vp::test::MakeTempDir("image_mismatch");
  const std::string actual = RenderShot(tmp, Shot{ "safe", 17.0 });
  const vp::ImageDifference d = vp::CompareImages(actual, BaselineDir() + "/overlays_breach.png", "");
  ASSERT_TRUE(d.SameSize) << "the breach baseline is missing or of another size";
  EXPECT_GT(d.FractionDifferent, 0.01);
  std::filesystem::remove_all(tmp);
}

// The closest-point line says which vessel it points at, and a z-buffer distance as its interval.
TEST(Overlays, TheClosestPointLineNamesItsVesselAndShowsABoundAsAnInterval)
{
  vtkNew<vtkClosestPointLineRepresentation> line;
  const double tip[3] = { 0, 0, 0 }, point[3] = { 0, 0, 1.5 };
  line->SetLine(tip, point, 1.5, false, "hepatic_artery", 0.347);
  EXPECT_EQ(line->GetLabelText(), "hepatic artery 1.2-1.8 mm");
  line->SetLine(tip, point, 1.0, true, "portal_vein");
  EXPECT_EQ(line->GetLabelText(), "portal vein 1.0 mm inside");
  EXPECT_TRUE(line->IsShown());
  line->Hide();
  EXPECT_FALSE(line->IsShown());
}

// The inset plot keeps its legend whole at any window size the view gives it (at 1000 x 700 the
// instrument's entries and the bands were cut off).
TEST(Overlays, TheInsetPlotsLegendIsWholeAtAnyWindowSize)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  const std::string tmp = vp::test::MakeTempDir("plot_legend");
  auto logic = MakePhantomLogic(tmp);
  for (const auto& size : { std::array<int, 2>{ 1000, 700 }, std::array<int, 2>{ 640, 400 }, std::array<int, 2>{ 1920, 1080 } })
  {
    vtkNew<vtkVesselProximityView> view;
    view->SetOffScreen(true);
    view->SetSizePx(size[0], size[1]);
    view->SetLogic(logic);
    for (int i = 0; i <= 30; ++i)
    {
      view->SetScalpelPose(TipDownAt(20.0 - 0.5 * i)); // into the tube: every band, both lines
    }
    vtkDistancePlotRepresentation* plot = view->GetOverlays()->GetPlot();
    EXPECT_TRUE(plot->GetFrame().LegendWhole) << size[0] << " x " << size[1];
    int dims[3];
    plot->GetImage()->GetDimensions(dims);
    EXPECT_LE(dims[0], size[0] * 13 / 20) << "the inset leaves the scene most of the window";
    view->Render();
    const int* corner = plot->GetActor()->GetPositionCoordinate()->GetComputedDisplayValue(view->GetRenderer());
    EXPECT_GE(corner[0], 0) << size[0] << " x " << size[1];
    EXPECT_LE(corner[0] + dims[0], size[0]) << "the inset's right edge within the window at " << size[0] << " x " << size[1];
  }
  std::filesystem::remove_all(tmp);
}

// The readout's lines fit the window: at 640 x 480 the breach's headline (56 characters) would run
// 100 pixels past the edge at 22 points, so the lines are drawn smaller; at 1920 x 1080 as set.
TEST(Overlays, TheReadoutFitsTheWindowAtAnySize)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  const std::string tmp = vp::test::MakeTempDir("readout_fit");
  auto logic = MakePhantomLogic(tmp);
  for (const auto& size : { std::array<int, 2>{ 640, 480 }, std::array<int, 2>{ 1920, 1080 } })
  {
    vtkNew<vtkVesselProximityView> view;
    view->SetOffScreen(true);
    view->SetSizePx(size[0], size[1]);
    view->SetLogic(logic);
    view->SetScalpelPose(TipDownAt(5.0)); // inside the tube: the long headline
    view->Render();
    vtkProximityReadoutRepresentation* readout = view->GetOverlays()->GetReadout();
    EXPECT_NE(readout->GetLineText(0).find("BREACH: tip"), std::string::npos) << readout->GetLineText(0);
    for (int i = 0; i < readout->GetNumberOfLines(); ++i)
    {
      // The box is the text's own (its backing's padding included), placed at the line's position.
      double box[4];
      readout->GetLineActor(i)->GetBoundingBox(view->GetRenderer(), box);
      const int* at = readout->GetLineActor(i)->GetPositionCoordinate()->GetComputedDisplayValue(view->GetRenderer());
      EXPECT_GE(at[0] + box[0], 0) << "line " << i << " left of the window";
      EXPECT_LE(at[0] + box[1], size[0]) << "line " << i << " at " << size[0] << " x " << size[1] << ": " << readout->GetLineText(i);
      EXPECT_GE(at[1] + box[2], 0) << "line " << i << " below the window";
      EXPECT_LE(at[1] + box[3], size[1]) << "line " << i << " above the window";
    }
    EXPECT_EQ(readout->GetFittedFontSize() < 18, size[0] == 640) << size[0];
  }
  std::filesystem::remove_all(tmp);
}

// ---- camera presets ---------------------------------------------------------------------------

namespace
{
/// The phantom at the warning pose, through a view with the preset, 960 x 600: the camera's
/// direction of projection and focal point, and the picture.
std::string RenderPreset(
  const std::string& tmp, vtkVesselProximityView::CameraPreset preset, double direction[3], double focal[3], double tip[3])
{
  auto logic = MakePhantomLogic(tmp);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(960, 600);
  view->SetLogic(logic);
  view->SetCameraPreset(preset);
  std::vector<vp::TrackedPose> poses;
  for (int i = 0; 20.0 - 0.5 * i >= 10.0 - 1e-9; ++i)
  {
    poses.push_back(Pose(0.02 * i, TipDownAt(20.0 - 0.5 * i)));
  }
  view->SetPoses(poses);
  for (int i = 0; i < view->GetNumberOfPoses(); ++i)
  {
    view->ShowPose(i);
  }
  const std::string file = tmp + "/view_" + vtkVesselProximityView::CameraPresetName(preset) + ".png";
  view->SaveScreenshot(file);
  view->GetRenderer()->GetActiveCamera()->GetDirectionOfProjection(direction);
  view->GetRenderer()->GetActiveCamera()->GetFocalPoint(focal);
  std::copy(logic->GetLastFrame().TipMm, logic->GetLastFrame().TipMm + 3, tip);
  // The presets that move with the tool keep its tip in sight; the fixed ones look from where they
  // say (superior looks down this scalpel's shaft).
  const bool moving = preset == vtkVesselProximityView::CameraPreset::Tool || preset == vtkVesselProximityView::CameraPreset::Follow ||
    preset == vtkVesselProximityView::CameraPreset::Clear;
  EXPECT_TRUE(!moving || vp::PointInPlainSight(view->GetRenderer(), tip)) << vtkVesselProximityView::CameraPresetName(preset);
  // A fixed one never leaves a vessel hiding the tip: it shows the vessels see-through then.
  vp::TipOcclusion occlusion;
  const bool vesselHides = occlusion.Hides(view->GetRenderer(), view->GetOverlays()->GetVessels()->GetVesselActors(), tip);
  EXPECT_EQ(view->GetOverlays()->GetVessels()->GetSeeThrough(), !moving && vesselHides)
    << vtkVesselProximityView::CameraPresetName(preset);
  return file;
}
} // namespace

// Names the preset in test listings (ctest shows it) instead of its bytes; found by ADL beside
// the enumeration's class.
void PrintTo(const vtkVesselProximityView::CameraPreset& preset, std::ostream* os)
{
  *os << vtkVesselProximityView::CameraPresetName(preset);
}

class CameraPresetImages : public ImageTest<vtkVesselProximityView::CameraPreset>
{
};

// Each preset looks from where it says (the world is LPS; the scalpel points down, -z), and its
// picture, with the orientation marker naming the direction seen, matches
// its baseline.
TEST_P(CameraPresetImages, LookFromWhereTheySayAndMatchTheBaseline)
{
  using Preset = vtkVesselProximityView::CameraPreset;
  const Preset preset = GetParam();
  const std::string name = vtkVesselProximityView::CameraPresetName(preset);
  const std::string tmp = vp::test::MakeTempDir("camera_" + name);
  double direction[3], focal[3], tip[3];
  const std::string actual = RenderPreset(tmp, preset, direction, focal, tip);
  const std::map<Preset, std::array<double, 3>> looking = { { Preset::Anterior, { 0, 1, 0 } }, { Preset::Lateral, { 1, 0, 0 } },
    { Preset::Superior, { 0, 0, -1 } }, { Preset::Tool, { 0, 1, 0 } }, { Preset::Follow, { 0, 1, 0 } } };
  for (int k = 0; k < 3 && looking.count(preset); ++k) // clear: wherever the tip is in plain sight
  {
    EXPECT_NEAR(direction[k], looking.at(preset)[k], 1e-9) << name << " axis " << k;
  }
  if (preset == Preset::Tool || preset == Preset::Follow)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(focal[k], tip[k], 1e-6) << name << ": the tip in the middle";
    }
  }
  this->ExpectBaseline(actual, "view_" + name + ".png", tmp);
}

// The tip behind the hepatic vein as seen from the front: the anterior preset keeps its direction
// and shows the vessels see-through while one hides the tip, the clear preset turns until the tip
// and its closest vessel point are both in plain sight, and keeps the shaft up the screen.
TEST(CameraPresets, TheClearViewShowsATipThatAVesselHides)
{
  vp::VirtualDisplay display;
  if (!display.Ensure())
  {
    GTEST_SKIP() << "no display for rendering: " << display.GetProblem();
  }
  const std::string tmp = vp::test::MakeTempDir("camera_clear");
  auto logic = MakePhantomLogic(tmp);
  // Pointing down, its tip at (45, 45, -10): 15 mm behind the centre of the ball (radius 10 at
  // 45, 30, -10), 5 mm from its wall.
  const std::array<double, 16> behind = { 1, 0, 0, 45, 0, -1, 0, 45, 0, 0, -1, -10, 0, 0, 0, 1 };
  for (const auto preset : { vtkVesselProximityView::CameraPreset::Anterior, vtkVesselProximityView::CameraPreset::Clear })
  {
    vtkNew<vtkVesselProximityView> view;
    view->SetOffScreen(true);
    view->SetSizePx(960, 600);
    view->SetLogic(logic);
    view->SetCameraPreset(preset);
    view->SetScalpelPose(behind);
    view->Render();
    const vp::TrackedFrame& frame = logic->GetLastFrame();
    const int nearest = frame.Proximity.NearestIndex();
    ASSERT_GE(nearest, 0);
    EXPECT_EQ(frame.Proximity.Classes[static_cast<std::size_t>(nearest)].ClassName, "hepatic_vein");
    const bool clear = preset == vtkVesselProximityView::CameraPreset::Clear;
    // The anterior view keeps its direction and sees the vessels through (translucent surfaces
    // still fill the depth buffer, so the picture's depth says hidden); the clear one turns.
    EXPECT_EQ(view->GetOverlays()->GetVessels()->GetSeeThrough(), !clear);
    EXPECT_EQ(vp::PointInPlainSight(view->GetRenderer(), frame.TipMm), clear) << vtkVesselProximityView::CameraPresetName(preset);
    if (!clear)
    {
      for (vtkActor* vessel : view->GetOverlays()->GetVessels()->GetVesselActors())
      {
        EXPECT_LT(vessel->GetProperty()->GetOpacity(), 0.5);
      }
      // Moved out in front of the ball (tip at y = 10, the ball from y = 20): opaque again.
      std::array<double, 16> inFront = behind;
      inFront[7] = 10.0;
      view->SetScalpelPose(inFront);
      view->Render();
      EXPECT_FALSE(view->GetOverlays()->GetVessels()->GetSeeThrough());
      EXPECT_TRUE(vp::PointInPlainSight(view->GetRenderer(), logic->GetLastFrame().TipMm));
    }
    if (clear)
    {
      EXPECT_TRUE(vp::PointInPlainSight(view->GetRenderer(), frame.Proximity.Classes[static_cast<std::size_t>(nearest)].ClosestPoint));
      double up[3];
      view->GetRenderer()->GetActiveCamera()->GetViewUp(up);
      EXPECT_GT(up[2], 0.5) << "the shaft (pointing down) up the screen";
    }
  }
  std::filesystem::remove_all(tmp);
}

// The line of sight against an analytic ball (radius 10 at the origin), the camera 100 mm in front
// of it on -y: a point behind the ball is hidden, one in front or beside it is not, one just inside
// its near wall (within the tolerance) is not; the ball's locator is built once for all of them.
TEST(TipOcclusion, ABallHidesWhatIsBehindItAndItsLocatorIsBuiltOnce)
{
  const double centre[3] = { 0, 0, 0 };
  vtkNew<vtkActor> ball;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(vp::MakeSphere(centre, 10.0, 48, 96));
  ball->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->GetActiveCamera()->SetPosition(0, -100, 0);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  vp::TipOcclusion occlusion;
  const std::vector<vtkActor*> actors = { ball };
  const double behind[3] = { 0, 20, 0 }, inFront[3] = { 0, -20, 0 }, beside[3] = { 15, 20, 0 }, justInside[3] = { 0, -8, 0 },
               deepInside[3] = { 0, 0, 0 };
  EXPECT_TRUE(occlusion.Hides(renderer, actors, behind));
  EXPECT_FALSE(occlusion.Hides(renderer, actors, inFront));
  EXPECT_FALSE(occlusion.Hides(renderer, actors, beside));
  EXPECT_FALSE(occlusion.Hides(renderer, actors, justInside)) << "2 mm inside the wall, within 3 mm";
  EXPECT_TRUE(occlusion.Hides(renderer, actors, deepInside)) << "10 mm behind the wall";
  EXPECT_EQ(occlusion.GetNumberOfLocators(), 1u);
  // Moved by its actor's matrix: the ball now at x = 50, the point behind the origin in plain sight.
  ball->SetPosition(50, 0, 0);
  EXPECT_FALSE(occlusion.Hides(renderer, actors, behind));
  EXPECT_EQ(occlusion.GetNumberOfLocators(), 1u);
}

INSTANTIATE_TEST_SUITE_P(Presets, CameraPresetImages,
  ::testing::Values(vtkVesselProximityView::CameraPreset::Anterior, vtkVesselProximityView::CameraPreset::Lateral,
    vtkVesselProximityView::CameraPreset::Superior, vtkVesselProximityView::CameraPreset::Tool,
    vtkVesselProximityView::CameraPreset::Follow, vtkVesselProximityView::CameraPreset::Clear),
  [](const ::testing::TestParamInfo<vtkVesselProximityView::CameraPreset>& info) {
    return std::string(vtkVesselProximityView::CameraPresetName(info.param));
  });
