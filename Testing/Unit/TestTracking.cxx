// Tracking: per-frame proximity equals a direct query at the pose's tip, danger levels change
// once per change, the whole-instrument distance equals brute force over every triangle pair,
// and the summary adds up. Synthetic poses with known answers, as SlicerIGT's pivot test does.
#include "vpAnalyticShapes.h"
#include "vpDangerLevels.h"
#include "vpFrameHeadline.h"
#include "vpKeyFrames.h"
#include "vpHapticForce.h"
#include "vpInputError.h"
#include "vpRigidTransform.h"
#include "vpTrackingSummary.h"
#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"

#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cmath>
#include <random>

namespace
{
const double Origin[3] = { 0, 0, 0 };

/// A tool pose whose model +z (the axis) points along world -x, tip (model origin) at tipX on
/// the x axis, shifted by offset.
vp::TrackedPose PoseTowardsMinusX(double timeS, double tipX, const double offset[3] = Origin)
{
  // Columns: model x -> world z, model y -> world y, model z -> world -x (a proper rotation).
  return { timeS, { 0, 0, -1, tipX + offset[0], 0, 1, 0, offset[1], 1, 0, 0, offset[2], 0, 0, 0, 1 } };
}

vtkSmartPointer<vtkPolyData> ToolShaft()
{
  const double z[3] = { 0, 0, 1 };
  const double centre[3] = { 0, 0, -40 };
  return vp::MakeCappedCylinder(centre, z, 1.5, 80.0, 16); // tip face at z = 0
}

struct Recorder
{
  std::vector<vp::DangerLevelChange> Changes;
  static void Callback(vtkObject*, unsigned long, void* client, void* call)
  {
    static_cast<Recorder*>(client)->Changes.push_back(*static_cast<vp::DangerLevelChange*>(call));
  }
};

class Tracking : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Engine->AddVessel("portal_vein", vp::MakeSphere(Origin, 10.0, 90, 180));
    const double far[3] = { 0, 60, 0 };
    this->Engine->AddVessel("hepatic_vein", vp::MakeSphere(far, 5.0, 30, 60));
    this->Engine->Build();
    this->Scalpel->SetModel(ToolShaft());
    this->Logic->SetDistanceEngine(this->Engine);
    this->Logic->SetScalpel(this->Scalpel);
    this->Observer->SetClientData(&this->Events);
    this->Observer->SetCallback(&Recorder::Callback);
    this->Logic->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, this->Observer);
  }
  vtkNew<vtkExactVesselDistance> Engine;
  vtkNew<vtkScalpelModel> Scalpel;
  vtkNew<vtkScalpelTrackingLogic> Logic;
  vtkNew<vtkCallbackCommand> Observer;
  Recorder Events;
};

/// Approach to 0.5 mm from the sphere and back, in 0.25 mm steps.
std::vector<vp::TrackedPose> ApproachAndRetreat(double jitterMm, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, jitterMm);
  std::vector<vp::TrackedPose> poses;
  double t = 0.0;
  auto add = [&](double x) {
    const double offset[3] = { jitterMm > 0 ? noise(random) : 0.0, jitterMm > 0 ? noise(random) : 0.0,
      jitterMm > 0 ? noise(random) : 0.0 };
    poses.push_back(PoseTowardsMinusX(t, x, offset));
    t += 0.05;
  };
  for (double x = 30.0; x > 10.5; x -= 0.25)
  {
    add(x);
  }
  for (double x = 10.5; x <= 30.0; x += 0.25)
  {
    add(x);
  }
  return poses;
}
} // namespace

TEST(DangerLevels, ThresholdsNamesAndTheErrorBound)
{
  const vp::DangerThresholds t; // 10, 5, 2
  vp::ClassProximity p;
  p.InRange = true;
  p.Inside = false;
  const std::pair<double, vp::DangerLevel> cases[] = { { 10.01, vp::DangerLevel::Safe }, { 10.0, vp::DangerLevel::Caution },
    { 5.0, vp::DangerLevel::Warning }, { 2.0, vp::DangerLevel::Danger }, { 0.0, vp::DangerLevel::Danger } };
  for (const auto& c : cases)
  {
    p.DistanceMm = c.first;
    EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), c.second) << c.first;
  }
  // An approximate engine's 5.2 mm may be 4.85: the level says warning, never less.
  p.DistanceMm = 5.2;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), vp::DangerLevel::Caution);
  EXPECT_EQ(vp::ClassifyDanger(p, 0.35, t), vp::DangerLevel::Warning);
  // Within twice its bound of a wall, an approximate engine cannot tell the sides apart: breach.
  // The exact engine (bound 0) on the wall itself is in danger, not inside.
  p.DistanceMm = 0.69;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.347, t), vp::DangerLevel::Breach);
  p.DistanceMm = 0.70;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.347, t), vp::DangerLevel::Danger);
  p.DistanceMm = 0.0;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), vp::DangerLevel::Danger);
  p.Inside = true;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), vp::DangerLevel::Breach);
  p.InRange = false;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), vp::DangerLevel::Breach) << "inside is a breach whatever the range (issue 29)";
  p.Inside = false;
  EXPECT_EQ(vp::ClassifyDanger(p, 0.0, t), vp::DangerLevel::Safe);
  EXPECT_STREQ(vp::DangerLevelName(vp::DangerLevel::Warning), "warning");
  EXPECT_EQ(vp::DangerLevelColour(vp::DangerLevel::Safe)[0], 255);
  EXPECT_THROW((vp::DangerThresholds{ 5, 5, 2 }.Validate("t")), vp::InputError);
  EXPECT_THROW((vp::DangerThresholds{ 10, 5, 0 }.Validate("t")), vp::InputError);
  EXPECT_NO_THROW((vp::DangerThresholds{ 20, 8, 1 }.Validate("t")));
}

TEST_F(Tracking, EachFrameEqualsADirectQueryAtItsTip)
{
  this->Scalpel->SetTipMm(0, 0, 0);
  this->Scalpel->SetAxis(0, 0, 1);
  vtkNew<vtkExactVesselDistance> direct; // a second engine, no previous-frame hints
  direct->AddVessel("portal_vein", vp::MakeSphere(Origin, 10.0, 90, 180));
  const double far[3] = { 0, 60, 0 };
  direct->AddVessel("hepatic_vein", vp::MakeSphere(far, 5.0, 30, 60));
  const auto poses = ApproachAndRetreat(0.3, 11);
  for (const auto& pose : poses)
  {
    const vp::TrackedFrame& f = this->Logic->ProcessPose(pose);
    const double tip[3] = { pose.ModelToWorld[3], pose.ModelToWorld[7], pose.ModelToWorld[11] };
    EXPECT_DOUBLE_EQ(f.TipMm[0], tip[0]);
    EXPECT_DOUBLE_EQ(f.AxisWorld[0], -1.0);
    const double axis[3] = { -1, 0, 0 };
    vp::ProximityResult expected;
    direct->ComputeProximity(tip, axis, expected);
    ASSERT_EQ(f.Proximity.Classes.size(), 2u);
    for (int c = 0; c < 2; ++c)
    {
      const auto& got = f.Proximity.Classes[c];
      const auto& want = expected.Classes[c];
      ASSERT_EQ(got.InRange, want.InRange);
      if (got.InRange)
      {
        EXPECT_NEAR(got.DistanceMm, want.DistanceMm, 1e-12);
        EXPECT_NEAR(got.ClosestPoint[1], want.ClosestPoint[1], 1e-9);
        ASSERT_EQ(got.DirectionalMm.has_value(), want.DirectionalMm.has_value());
        if (got.DirectionalMm)
        {
          EXPECT_NEAR(*got.DirectionalMm, *want.DirectionalMm, 1e-9);
        }
      }
    }
    // The sphere's analytic distance, within the mesh's chord error (90 x 180 facets: < 0.02 mm).
    const double r = std::sqrt(tip[0] * tip[0] + tip[1] * tip[1] + tip[2] * tip[2]);
    EXPECT_NEAR(f.Proximity.Classes[0].DistanceMm, r - 10.0, 0.02);
  }
  EXPECT_EQ(this->Logic->GetNumberOfFrames(), static_cast<int>(poses.size()));
}

TEST_F(Tracking, DangerLevelChangesAreReportedOncePerChange)
{
  this->Logic->SetHysteresisMm(0.0); // each frame's level from its own distance alone
  for (double jitter : { 0.0, 0.3 })
  {
    this->Logic->Reset();
    this->Events.Changes.clear();
    std::vector<vp::DangerLevel> levels;
    std::vector<double> distances;
    for (const auto& pose : ApproachAndRetreat(jitter, 5))
    {
      const vp::TrackedFrame& f = this->Logic->ProcessPose(pose);
      levels.push_back(f.Level);
      distances.push_back(f.Proximity.Classes[0].DistanceMm);
      // The level is the frame's own distance classified, nothing remembered.
      EXPECT_EQ(f.Level, vp::ClassifyDistance(distances.back(), vp::DangerThresholds())) << "frame " << f.Frame;
    }
    std::vector<int> changedAt;
    for (std::size_t i = 0; i < levels.size(); ++i)
    {
      if (levels[i] != (i == 0 ? vp::DangerLevel::Safe : levels[i - 1]))
      {
        changedAt.push_back(static_cast<int>(i));
      }
    }
    ASSERT_EQ(this->Events.Changes.size(), changedAt.size()) << "jitter " << jitter;
    for (std::size_t k = 0; k < changedAt.size(); ++k)
    {
      const vp::DangerLevelChange& e = this->Events.Changes[k];
      EXPECT_EQ(e.Frame, changedAt[k]);
      EXPECT_EQ(e.To, levels[changedAt[k]]);
      EXPECT_EQ(e.From, changedAt[k] == 0 ? vp::DangerLevel::Safe : levels[changedAt[k] - 1]);
      EXPECT_EQ(e.ClassName, e.To == vp::DangerLevel::Safe ? "" : "portal_vein");
    }
    if (jitter == 0.0)
    {
      // Smooth approach to 0.5 mm and back: up through caution, warning, danger and down again.
      ASSERT_EQ(changedAt.size(), 6u);
      const vp::DangerLevel expected[6] = { vp::DangerLevel::Caution, vp::DangerLevel::Warning, vp::DangerLevel::Danger,
        vp::DangerLevel::Warning, vp::DangerLevel::Caution, vp::DangerLevel::Safe };
      for (int k = 0; k < 6; ++k)
      {
        EXPECT_EQ(this->Events.Changes[k].To, expected[k]) << k;
      }
      EXPECT_NEAR(this->Events.Changes[0].DistanceMm, 10.0, 0.25); // first frame within 10 mm
    }
  }
}

// Tracking noise of 0.2 mm at each threshold: with the default 0.3 mm hysteresis the level changes
// once in (at the first frame past the threshold) and once out (only 0.3 mm beyond it); without
// it, at every frame. A step into the vessel is a breach on that very frame, and the breach holds
// until the tip is 0.3 mm outside.
TEST_F(Tracking, HysteresisChangesTheLevelOnceInAndOnceOut)
{
  EXPECT_DOUBLE_EQ(this->Logic->GetHysteresisMm(), 0.3);
  EXPECT_THROW(this->Logic->SetHysteresisMm(-0.1), vp::InputError);
  const vp::DangerThresholds t;
  for (double threshold : { t.CautionMm, t.WarningMm, t.DangerMm })
  {
    for (double hysteresis : { 0.3, 0.0 })
    {
      this->Logic->SetHysteresisMm(hysteresis);
      this->Logic->Reset();
      std::vector<double> distances{ threshold + 1.0 };
      for (int i = 0; i < 20; ++i)
      {
        distances.push_back(threshold + (i % 2 == 0 ? -0.2 : 0.2));
      }
      distances.push_back(threshold + 0.5);
      std::vector<int> changedAt;
      vp::DangerLevel before = vp::DangerLevel::Safe;
      for (std::size_t i = 0; i < distances.size(); ++i)
      {
        const vp::TrackedFrame& f = this->Logic->ProcessPose(PoseTowardsMinusX(0.02 * i, 10.0 + distances[i]));
        if (i > 0 && f.Level != before)
        {
          changedAt.push_back(static_cast<int>(i));
        }
        before = f.Level;
      }
      if (hysteresis > 0.0)
      {
        ASSERT_EQ(changedAt.size(), 2u) << "threshold " << threshold;
        EXPECT_EQ(changedAt[0], 1) << "threshold " << threshold << ": entering must not wait";
        EXPECT_EQ(changedAt[1], 21) << "threshold " << threshold << ": left before 0.3 mm past it";
      }
      else
      {
        EXPECT_EQ(changedAt.size(), 20u) << "threshold " << threshold; // at every frame of the noise
      }
    }
  }

  this->Logic->SetHysteresisMm(0.3);
  this->Logic->Reset();
  const double steps[] = { 3.0, -1.0, 0.2, 0.5 };
  const vp::DangerLevel expected[] = { vp::DangerLevel::Warning, vp::DangerLevel::Breach, vp::DangerLevel::Breach,
    vp::DangerLevel::Danger };
  for (int i = 0; i < 4; ++i)
  {
    const vp::TrackedFrame& f = this->Logic->ProcessPose(PoseTowardsMinusX(0.02 * i, 10.0 + steps[i]));
    EXPECT_EQ(f.Level, expected[i]) << "frame " << i << ", " << steps[i] << " mm from the wall";
  }
}

TEST_F(Tracking, RangeShorterThanTheCautionThresholdIsRefused)
{
  this->Engine->SetRangeMm(8.0);
  EXPECT_THROW(this->Logic->ProcessPose(PoseTowardsMinusX(0.0, 20.0)), vp::InputError);
}

TEST_F(Tracking, SummaryAddsUp)
{
  vp::TrackingSummary summary;
  const auto poses = ApproachAndRetreat(0.0, 1);
  std::array<int, vp::NumberOfDangerLevels> frames{};
  std::array<double, vp::NumberOfDangerLevels> seconds{};
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const vp::TrackedFrame& f = this->Logic->ProcessPose(poses[i]);
    summary.Add(f);
    ++frames[static_cast<int>(f.Level)];
    if (i + 1 < poses.size())
    {
      seconds[static_cast<int>(f.Level)] += poses[i + 1].TimeS - poses[i].TimeS;
    }
  }
  EXPECT_EQ(summary.GetNumberOfFrames(), static_cast<int>(poses.size()));
  EXPECT_NEAR(summary.GetDurationS(), poses.back().TimeS - poses.front().TimeS, 1e-12);
  double total = 0.0;
  for (int l = 0; l < vp::NumberOfDangerLevels; ++l)
  {
    EXPECT_EQ(summary.GetFramesInLevel()[l], frames[l]) << l;
    EXPECT_NEAR(summary.GetTimeInLevelS()[l], seconds[l], 1e-9) << l;
    total += summary.GetTimeInLevelS()[l];
  }
  EXPECT_NEAR(total, summary.GetDurationS(), 1e-9);
  EXPECT_GT(frames[static_cast<int>(vp::DangerLevel::Danger)], 10); // the run spends time in danger
  const vp::ClassMinimum& m = summary.GetTipMinimum()[0];
  ASSERT_TRUE(m.Seen);
  EXPECT_NEAR(m.DistanceMm, 0.5, 0.02);
  EXPECT_NEAR(poses[m.Frame].ModelToWorld[3], 10.5, 1e-9);
  EXPECT_NEAR(m.PointMm[0], 10.0, 0.02);
  EXPECT_EQ(summary.GetWorstLevel(), vp::DangerLevel::Danger);
  // The far sphere (60 mm away, radius 5) never comes within the 50 mm range.
  EXPECT_FALSE(summary.GetTipMinimum()[1].Seen);
}

// A tip that enters a vessel came closer than any tip outside: the summary keeps the deepest
// penetration, not the small distance on the way through the wall.
TEST_F(Tracking, SummaryMinimumIsTheDeepestPenetration)
{
  vp::TrackingSummary summary;
  double t = 0.0;
  for (double x : { 14.0, 12.0, 10.1, 9.0, 8.0, 9.5, 10.05, 13.0 })
  {
    summary.Add(this->Logic->ProcessPose(PoseTowardsMinusX(t, x)));
    t += 0.1;
  }
  const vp::ClassMinimum& m = summary.GetTipMinimum()[0];
  ASSERT_TRUE(m.Seen);
  EXPECT_TRUE(m.Inside);
  EXPECT_NEAR(m.DistanceMm, 2.0, 0.02);
  EXPECT_EQ(m.Frame, 4);
  EXPECT_EQ(summary.GetWorstLevel(), vp::DangerLevel::Breach);
  // Three frames inside, and the one 0.05 mm outside, within the hysteresis: the breach holds.
  EXPECT_EQ(summary.GetFramesInLevel()[static_cast<int>(vp::DangerLevel::Breach)], 4);
}

namespace
{
/// A frame whose tip is depthMm inside a class, its wall towards +y, at time t.
vp::TrackedFrame FrameInside(double t, double depthMm)
{
  vp::TrackedFrame frame;
  frame.TimeS = t;
  frame.AxisWorld[0] = 0, frame.AxisWorld[1] = 0, frame.AxisWorld[2] = -1;
  vp::ClassProximity c;
  c.ClassName = "portal_vein";
  c.InRange = true;
  c.Inside = depthMm > 0.0;
  c.DistanceMm = std::abs(depthMm);
  c.ClosestPoint[1] = depthMm > 0.0 ? depthMm : -depthMm; // the wall, +y of the tip at the origin
  frame.Proximity.Classes.push_back(c);
  return frame;
}
} // namespace

// Kelvin-Voigt against its formula: on a steady push the force is k * depth + c * rate, out of the
// vessel; outside there is none whatever the rate; a depth that jumps gives no spike beyond the
// rate's bound.
// The whole instrument is graded by the tip's thresholds: its distance as reported (an approximate
// one is already the low end of its interval, so its bound is not taken off again), any
// penetration a breach, an undecidable one a breach where the surfaces touch.
TEST(DangerLevels, TheInstrumentIsGradedByItsDistanceAndAnyPenetration)
{
  const vp::DangerThresholds t;
  vp::SurfaceProximity s;
  s.InRange = true;
  s.DistanceMm = 2.9;
  s.ErrorBoundMm = 1.5; // the truth is 2.9 to 4.4 mm: a warning, not a breach
  vp::Penetration none;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &none, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Warning);
  s.DistanceMm = 1.0;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &none, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Danger);
  s.DistanceMm = 0.0;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &none, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Danger) << "touching";
  vp::Penetration in;
  in.DepthMm = 0.3;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &in, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Breach);
  vp::Penetration unknown;
  unknown.Known = false;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &unknown, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Breach)
    << "touching an open surface: inside cannot be ruled out";
  s.DistanceMm = 12.0;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &unknown, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Safe);
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, nullptr, t, vp::DangerLevel::Safe, 0.0), vp::DangerLevel::Safe);
  // Hysteresis on the way out, as for the tip: 10.2 mm after a caution stays a caution.
  s.DistanceMm = 10.2;
  EXPECT_EQ(vp::ClassifyInstrumentWithHysteresis(s, &none, t, vp::DangerLevel::Caution, 0.3), vp::DangerLevel::Caution);
}

// The headline names the most severe of the vessels' level and the margin's, with its cause, in
// words: a violated margin beside a safe tip is what the screen says first.
TEST(FrameHeadline, TheMostSevereOfVesselAndMarginWithItsCause)
{
  vp::TrackedFrame frame;
  frame.Proximity.Classes.resize(2);
  frame.Proximity.Classes[0].ClassName = "portal_vein";
  frame.Proximity.Classes[0].InRange = true;
  frame.Proximity.Classes[0].DistanceMm = 15.5;
  frame.Proximity.Classes[1].ClassName = "hepatic_vein";
  EXPECT_EQ(vp::FrameHeadline(frame), "SAFE");
  frame.Surface.resize(2);
  frame.Penetrations.resize(2);
  frame.Surface[0].InRange = true;
  frame.Penetrations[0].DepthMm = 1.04;
  frame.Penetrations[0].VolumeMm3 = 3.7;
  frame.Level = vp::DangerLevel::Breach;
  frame.LevelClass = 0;
  frame.LevelCause = vp::DangerCause::Instrument;
  EXPECT_EQ(vp::FrameHeadline(frame), "BREACH: instrument 1.0 mm into the portal vein");
  frame.Level = vp::DangerLevel::Caution;
  frame.LevelCause = vp::DangerCause::Tip;
  frame.Proximity.Classes[0].DistanceMm = 8.04;
  EXPECT_EQ(vp::FrameHeadline(frame), "CAUTION: tip 8.0 mm from the portal vein");
  frame.Tumour.emplace();
  frame.Tumour->Tumours.resize(1);
  frame.Tumour->Tumours[0].Id = "03";
  frame.Tumour->Tumours[0].SignedMm = 1.72;
  frame.Tumour->Worst = 0;
  frame.Tumour->Level = vp::MarginLevel::Violated;
  EXPECT_EQ(vp::FrameHeadline(frame), "MARGIN VIOLATED: tumour 03, 1.7 mm") << "violated outranks caution";
  frame.Level = vp::DangerLevel::Danger;
  EXPECT_EQ(vp::FrameHeadline(frame), "DANGER: tip 8.0 mm from the portal vein") << "a tie goes to the vessels";
  frame.Tumour->Tumours[0].SignedMm = -2.1;
  frame.Tumour->Level = vp::MarginLevel::Inside;
  EXPECT_EQ(vp::FrameHeadline(frame), "INSIDE TUMOUR: tumour 03, 2.1 mm in");
  EXPECT_EQ(vp::DescribeDanger(frame), "DANGER: tip 8.0 mm from the portal vein");
}

// Key frames: captions in words; near frames at the same levels are one picture (at the closest
// approach), a level change is never merged into another level's picture; a tumour's closest
// approach, a margin change and the instrument's first contact each get theirs.
TEST(KeyFrames, NearFramesAtOneLevelAreOnePictureCaptionedInWords)
{
  vp::KeyFrameFinder finder;
  auto frame = [](double t, double tipMm, vp::DangerLevel level, double tumourMm, vp::MarginLevel margin, double surfaceMm) {
    vp::TrackedFrame f;
    f.TimeS = t;
    f.Proximity.Classes.resize(1);
    f.Proximity.Classes[0].ClassName = "portal_vein";
    f.Proximity.Classes[0].InRange = true;
    f.Proximity.Classes[0].DistanceMm = tipMm;
    f.Surface.resize(1);
    f.Surface[0].InRange = true;
    f.Surface[0].DistanceMm = surfaceMm;
    f.Level = level;
    f.LevelClass = level == vp::DangerLevel::Safe ? -1 : 0;
    f.LevelCause = level == vp::DangerLevel::Safe ? vp::DangerCause::None : vp::DangerCause::Tip;
    f.Tumour.emplace();
    f.Tumour->Tumours.resize(1);
    f.Tumour->Tumours[0].Id = "03";
    f.Tumour->Tumours[0].SignedMm = tumourMm;
    f.Tumour->Worst = 0;
    f.Tumour->Level = margin;
    return f;
  };
  using D = vp::DangerLevel;
  using M = vp::MarginLevel;
  finder.AddFrame(frame(0.0, 12.0, D::Safe, 20.0, M::Clear, 11.0));
  finder.AddFrame(frame(1.0, 4.0, D::Warning, 9.0, M::Near, 3.0));  // both levels change: two reasons, one pose
  finder.AddFrame(frame(1.2, 1.5, D::Danger, 4.0, M::Violated, 0.5)); // both change again
  finder.AddFrame(frame(1.3, 1.2, D::Danger, 3.0, M::Violated, 0.0)); // the closest of both, the first contact
  finder.AddFrame(frame(3.0, 8.0, D::Caution, 12.0, M::Near, 6.0));
  const std::vector<vp::KeyFrame> keys = finder.GetKeyFrames();
  std::vector<std::string> names;
  for (const vp::KeyFrame& k : keys)
  {
    names.push_back(k.Name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{ "start", "warning_margin_near", "danger_margin_violated_contact_portal_vein_closest_portal_vein_closest_tumour_03",
                     "caution_margin_near_end" }));
  ASSERT_EQ(keys.size(), 4u);
  EXPECT_EQ(keys[2].PoseIndex, 3u) << "0.1 s after the change, at the same levels: one picture, at the closest approach";
  EXPECT_EQ(keys[2].Caption, "DANGER: tip 1.5 mm from the portal vein; MARGIN VIOLATED: tumour 03, 4.0 mm; the instrument's first "
                             "contact with the portal vein; tip closest to the portal vein, 1.2 mm; tip closest to tumour 03, 3.0 mm");
  EXPECT_EQ(keys[1].PoseIndex, 1u) << "a different level 0.2 s later is a picture of its own";
  EXPECT_EQ(keys[0].Caption, "start, SAFE");
}

TEST(HapticForce, KelvinVoigtOnASteadyPushNoneOutsideAndNoSpike)
{
  vp::HapticSettings settings;
  settings.StiffnessNPerMm = 0.5;
  settings.DampingNsPerMm = 0.01;
  vp::HapticForce haptic(settings);
  // 10 mm/s into the vessel at 100 Hz: after 10 time constants the filtered rate is 10 mm/s.
  vp::HapticSample last;
  for (int i = 1; i <= 50; ++i)
  {
    last = haptic.Update(FrameInside(0.01 * i, 0.1 * i));
  }
  EXPECT_NEAR(last.DepthMm, 5.0, 1e-12);
  EXPECT_NEAR(last.RateMmPerS, 10.0, 1e-3);
  EXPECT_NEAR(last.ForceN, 0.5 * 5.0 + 0.01 * 10.0, 1e-5);
  EXPECT_NEAR(last.Direction[1], 1.0, 1e-12) << "towards the wall";
  // Pulled out: outside, no force, though the depth fell fast.
  const vp::HapticSample outside = haptic.Update(FrameInside(0.51, -1.0));
  EXPECT_EQ(outside.ForceN, 0.0);
  EXPECT_EQ(outside.Direction[0] + outside.Direction[1] + outside.Direction[2], 0.0);
  // From outside to 5 mm deep in one 10 ms frame (500 mm/s raw): filtered and bounded.
  haptic.Reset();
  haptic.Update(FrameInside(1.0, -2.0));
  const vp::HapticSample jump = haptic.Update(FrameInside(1.01, 5.0));
  EXPECT_LE(jump.RateMmPerS, settings.MaxRateMmPerS);
  EXPECT_LT(jump.ForceN, 0.5 * 5.0 + 0.01 * 500.0) << "no spike: the raw rate is not used";
  EXPECT_LE(jump.ForceN, 0.5 * 5.0 + 0.01 * settings.MaxRateMmPerS + 1e-12);
  // The instrument deeper than its tip: pushed back along its axis.
  vp::TrackedFrame shaft = FrameInside(2.0, -3.0);
  vp::Penetration p;
  p.DepthMm = 2.0;
  shaft.Penetrations.push_back(p);
  haptic.Reset();
  const vp::HapticSample back = haptic.Update(shaft);
  EXPECT_NEAR(back.ForceN, 1.0, 1e-12);
  EXPECT_NEAR(back.Direction[2], 1.0, 1e-12);
  // A withdrawal faster than the stiffness holds never pulls inwards.
  haptic.Reset();
  haptic.Update(FrameInside(3.0, 4.0));
  EXPECT_GE(haptic.Update(FrameInside(3.01, 0.5)).ForceN, 0.0);
  vp::HapticSettings bad;
  bad.StiffnessNPerMm = -1.0;
  EXPECT_THROW(bad.Validate(), vp::ParameterError);
}
