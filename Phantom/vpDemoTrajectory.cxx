#include "vpDemoTrajectory.h"
#include "vpVec3.h"

#include "vpAnalyticShapes.h"
#include "vpInputError.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace vp
{
namespace
{
using namespace vec3;

// What the path must do, in mm of analytic signed distance to the nearest vessel surface.
constexpr double BreachDepthMm = 1.0;
constexpr double PassDistanceMm = 3.5;
constexpr double StartDistanceMm = 16.5;   // > 15, with margin
constexpr double WithdrawnDistanceMm = 12.0;
constexpr double EndDistanceMm = 13.0;     // > 12, with margin
/// How far every extremum of the distance keeps from every threshold: a surface built from 1 mm
/// voxels lies about half a voxel from the analytic one.
constexpr double ThresholdMarginMm = 0.75;
/// Medium calibre: 4.6-7.2 mm diameter.
constexpr double TargetMinimumRadiusMm = 2.3;
constexpr double TargetMaximumRadiusMm = 3.6;
constexpr double PassMinimumRadiusMm = 1.8;
constexpr double PassMaximumRadiusMm = 4.0;
constexpr double SampleStepMm = 0.25;

// How the surgeon moves: mean speeds of the legs (a half-cosine profile peaks at pi/2 times the
// mean), and a pause when the breach is noticed.
constexpr double ApproachSpeedMmS = 6.0;
constexpr double WithdrawSpeedMmS = 7.0;
constexpr double TransitSpeedMmS = 8.0;
constexpr double PassSpeedMmS = 6.0;
constexpr double BreachPauseS = 0.6;
constexpr double MinimumDurationS = 16.0;
constexpr double MaximumDurationS = 24.0;

const DangerThresholds Thresholds{};

DangerLevel LevelOf(double signedDistanceMm)
{
  return signedDistanceMm < 0 ? DangerLevel::Breach : ClassifyDistance(signedDistanceMm, Thresholds);
}

/// The analytic vessel trees, by class index.
class Vessels
{
public:
  explicit Vessels(const LiverPhantom& phantom)
  {
    for (const auto& [name, tree] : phantom.Centrelines)
    {
      this->Names.push_back(name);
      this->Trees.push_back(&tree);
    }
  }
  int IndexOf(const std::string& name) const
  {
    const auto found = std::find(this->Names.begin(), this->Names.end(), name);
    return found == this->Names.end() ? -1 : static_cast<int>(found - this->Names.begin());
  }
  const std::string& Name(int index) const { return this->Names[static_cast<std::size_t>(index)]; }
  const std::vector<VesselSegment>& Tree(int index) const { return *this->Trees[static_cast<std::size_t>(index)]; }
  double To(int index, const Vec3& p) const { return TreeSignedDistanceMm(this->Tree(index), p); }
  /// The nearest class and its signed distance.
  std::pair<int, double> Nearest(const Vec3& p) const
  {
    std::pair<int, double> best{ -1, std::numeric_limits<double>::infinity() };
    for (std::size_t c = 0; c < this->Trees.size(); ++c)
    {
      const double d = TreeSignedDistanceMm(*this->Trees[c], p);
      if (d < best.second)
      {
        best = { static_cast<int>(c), d };
      }
    }
    return best;
  }
  /// The nearest distance among the classes other than one.
  double NearestOther(int excluded, const Vec3& p) const
  {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < this->Trees.size(); ++c)
    {
      if (static_cast<int>(c) != excluded)
      {
        best = std::min(best, TreeSignedDistanceMm(*this->Trees[c], p));
      }
    }
    return best;
  }

private:
  std::vector<std::string> Names;
  std::vector<const std::vector<VesselSegment>*> Trees;
};

/// The nearest class and distance at points along a straight leg, both ends included.
struct LegSamples
{
  std::vector<int> Classes;
  std::vector<double> DistancesMm;

  void Append(const LegSamples& other)
  {
    this->Classes.insert(this->Classes.end(), other.Classes.begin(), other.Classes.end());
    this->DistancesMm.insert(this->DistancesMm.end(), other.DistancesMm.begin(), other.DistancesMm.end());
  }
};

LegSamples SampleLeg(const Vessels& vessels, const Vec3& from, const Vec3& to)
{
  const int steps = std::max(1, static_cast<int>(std::ceil(Norm(to - from) / SampleStepMm)));
  LegSamples samples;
  for (int s = 0; s <= steps; ++s)
  {
    const auto [c, d] = vessels.Nearest(from + (static_cast<double>(s) / steps) * (to - from));
    samples.Classes.push_back(c);
    samples.DistancesMm.push_back(d);
  }
  return samples;
}

/// The levels visited, repeats removed.
std::vector<DangerLevel> LevelSequence(const std::vector<double>& distancesMm)
{
  std::vector<DangerLevel> sequence;
  for (double d : distancesMm)
  {
    const DangerLevel level = LevelOf(d);
    if (sequence.empty() || sequence.back() != level)
    {
      sequence.push_back(level);
    }
  }
  return sequence;
}

/// True when the distance never grazes a threshold: every time it comes within the margin of
/// one, it leaves on the other side. Then a surface within the margin of the analytic one gives
/// the same level sequence (no extra flicker in and out of a level). Ending inside a margin band
/// counts as grazing.
bool ClearOfThresholds(const std::vector<double>& distancesMm)
{
  for (double threshold : { 0.0, Thresholds.DangerMm, Thresholds.WarningMm, Thresholds.CautionMm })
  {
    int side = 0, entrySide = 0;
    bool inBand = false;
    for (double d : distancesMm)
    {
      const int now = d > threshold + ThresholdMarginMm ? 1 : (d < threshold - ThresholdMarginMm ? -1 : 0);
      if (now == 0)
      {
        if (!inBand)
        {
          inBand = true;
          entrySide = side;
        }
        continue;
      }
      if (inBand && now == entrySide)
      {
        return false;
      }
      inBand = false;
      side = now;
    }
    if (inBand)
    {
      return false;
    }
  }
  return true;
}

/// Every sample whose distance is within caution is nearest to the given class.
bool OnlyNear(const LegSamples& samples, int cls)
{
  for (std::size_t i = 0; i < samples.DistancesMm.size(); ++i)
  {
    if (samples.DistancesMm[i] <= Thresholds.CautionMm + ThresholdMarginMm && samples.Classes[i] != cls)
    {
      return false;
    }
  }
  return true;
}

/// The first distance along the ray from origin (step 0.5 mm, from minimumMm up to 60 mm) where
/// the nearest vessel is at least wantedMm away; -1 when there is none.
double ReachClearance(const Vessels& vessels, const Vec3& origin, const Vec3& direction, double wantedMm,
  double minimumMm)
{
  for (double l = minimumMm; l <= 60.0; l += 0.5)
  {
    if (vessels.Nearest(origin + l * direction).second >= wantedMm)
    {
      return l;
    }
  }
  return -1;
}

/// The approach: from Start along Direction to Target, 1 mm inside a portal branch.
struct Approach
{
  Vec3 Direction{};
  Vec3 Start{};
  Vec3 Target{};
  Vec3 Withdrawn{};
  LegSamples Samples; ///< Start to Target
  double TargetRadiusMm = 0;
  double Score = 0;
};

/// The instrument comes from anterior (-y) and superior (+z), tip first: elevations of 30-60
/// degrees below the horizontal, turned up to 50 degrees to either side.
std::vector<Vec3> ApproachDirections()
{
  std::vector<Vec3> directions;
  for (double elevationDeg : { 45.0, 30.0, 60.0 })
  {
    for (double azimuthDeg : { 0.0, -25.0, 25.0, -50.0, 50.0 })
    {
      const double e = elevationDeg * Pi / 180, a = azimuthDeg * Pi / 180;
      directions.push_back({ std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), -std::sin(e) });
    }
  }
  return directions;
}

std::vector<Approach> FindApproaches(const Vessels& vessels, int portal)
{
  std::vector<Approach> approaches;
  for (const Vec3& direction : ApproachDirections())
  {
    for (const VesselSegment& s : vessels.Tree(portal))
    {
      const double radius = 0.5 * (s.StartRadiusMm + s.EndRadiusMm);
      const Vec3 along = s.EndMm - s.StartMm;
      if (radius < TargetMinimumRadiusMm || radius > TargetMaximumRadiusMm || Norm(along) < 3.0 ||
        std::abs(Dot(Normalized(along), direction)) > 0.5) // meet the branch at 60 degrees or more
      {
        continue;
      }
      // Back out from the branch's axis along the approach until the tip is 1 mm deep.
      const Vec3 centre = s.StartMm + 0.5 * along;
      auto depth = [&](double l) { return vessels.To(portal, centre - l * direction) + BreachDepthMm; };
      double lo = 0, hi = 0;
      while (depth(hi) < 0 && hi < 20)
      {
        lo = hi;
        hi += 0.1;
      }
      for (int i = 0; i < 60; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        (depth(mid) < 0 ? lo : hi) = mid;
      }
      Approach a;
      a.Direction = direction;
      a.Target = centre - lo * direction;
      a.TargetRadiusMm = radius;
      if (vessels.Nearest(a.Target).first != portal)
      {
        continue;
      }
      const double length = ReachClearance(vessels, a.Target, -1.0 * direction, StartDistanceMm, 18.0);
      if (length < 0)
      {
        continue;
      }
      a.Start = a.Target - length * direction;
      a.Samples = SampleLeg(vessels, a.Start, a.Target);
      const std::vector<DangerLevel> wanted = { DangerLevel::Safe, DangerLevel::Caution, DangerLevel::Warning,
        DangerLevel::Danger, DangerLevel::Breach };
      if (LevelSequence(a.Samples.DistancesMm) != wanted || !ClearOfThresholds(a.Samples.DistancesMm) ||
        !OnlyNear(a.Samples, portal))
      {
        continue;
      }
      const double back = ReachClearance(vessels, a.Target, -1.0 * direction, WithdrawnDistanceMm, 5.0);
      a.Withdrawn = a.Target - back * direction;
      // Prefer approaches that keep the other vessel systems far, then short ones.
      double otherClearance = 15.0;
      for (int s2 = 0; s2 <= 40; ++s2)
      {
        otherClearance =
          std::min(otherClearance, vessels.NearestOther(portal, a.Start + (s2 / 40.0) * (a.Target - a.Start)));
      }
      a.Score = otherClearance - 0.05 * length;
      approaches.push_back(std::move(a));
    }
  }
  std::stable_sort(
    approaches.begin(), approaches.end(), [](const Approach& x, const Approach& y) { return x.Score > y.Score; });
  return approaches;
}

/// The sweep past a hepatic vein: from PassStart through Closest to End.
struct Pass
{
  Vec3 PassStart{};
  Vec3 Closest{};
  Vec3 End{};
  LegSamples Samples; ///< PassStart to End
  double VeinRadiusMm = 0;
};

/// One straight leg of the path, travelled with a half-cosine speed profile (still at both ends),
/// or a pause where From == To.
struct Leg
{
  Vec3 From{};
  Vec3 To{};
  double DurationS = 0;
};

double TotalDuration(const std::vector<Leg>& legs)
{
  double total = 0;
  for (const Leg& l : legs)
  {
    total += l.DurationS;
  }
  return total;
}

std::vector<Leg> PlanLegs(const Approach& a, const Pass& p)
{
  std::vector<Leg> legs = { { a.Start, a.Target, Norm(a.Target - a.Start) / ApproachSpeedMmS },
    { a.Target, a.Target, BreachPauseS }, { a.Target, a.Withdrawn, Norm(a.Withdrawn - a.Target) / WithdrawSpeedMmS },
    { a.Withdrawn, p.PassStart, Norm(p.PassStart - a.Withdrawn) / TransitSpeedMmS },
    { p.PassStart, p.End, Norm(p.End - p.PassStart) / PassSpeedMmS } };
  const double total = TotalDuration(legs);
  if (total < MinimumDurationS)
  {
    // A short path is walked more slowly rather than padded with stillness.
    for (Leg& l : legs)
    {
      l.DurationS *= MinimumDurationS / total;
    }
  }
  return legs;
}

/// The first pass (nearest the withdrawn tip first) that completes the path: the transit stays
/// safe, the sweep gives caution-warning-caution with the hepatic vein alone, and the whole
/// takes at most MaximumDurationS.
bool FindPass(const Vessels& vessels, int hepatic, const Approach& a, Pass& found)
{
  struct Candidate
  {
    Vec3 Closest;
    Vec3 Axis;
    Vec3 Normal;
    double RadiusMm;
    double Key;
  };
  std::vector<Candidate> candidates;
  for (const VesselSegment& s : vessels.Tree(hepatic))
  {
    const double radius = 0.5 * (s.StartRadiusMm + s.EndRadiusMm);
    const Vec3 along = s.EndMm - s.StartMm;
    if (radius < PassMinimumRadiusMm || radius > PassMaximumRadiusMm || Norm(along) < 3.0)
    {
      continue;
    }
    const Vec3 axis = Normalized(along);
    const Vec3 centre = s.StartMm + 0.5 * along;
    const Vec3 facing = PerpendicularTo(axis, a.Withdrawn - centre);
    for (int k = 0; k < 8; ++k)
    {
      const Vec3 normal = Rotate(facing, axis, k * Pi / 4);
      const Vec3 closest = centre + (radius + PassDistanceMm) * normal;
      candidates.push_back({ closest, axis, normal, radius, Norm(closest - a.Withdrawn) });
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
    [](const Candidate& x, const Candidate& y) { return x.Key < y.Key; });

  const std::vector<DangerLevel> wantedPass = { DangerLevel::Safe, DangerLevel::Caution, DangerLevel::Warning,
    DangerLevel::Caution, DangerLevel::Safe };
  const std::vector<DangerLevel> wantedAll = DemoTrajectoryLevelSequence();
  for (const Candidate& c : candidates)
  {
    // The closest point must be what it claims: 3.5 mm from this vein, nothing else as close.
    if (std::abs(vessels.To(hepatic, c.Closest) - PassDistanceMm) > 0.02 ||
      vessels.NearestOther(hepatic, c.Closest) < PassDistanceMm + 3.0)
    {
      continue;
    }
    const Vec3 across = Normalized(Cross(c.Axis, c.Normal));
    for (double tiltDeg : { 0.0, 35.0, -35.0 })
    {
      Vec3 sweep = std::cos(tiltDeg * Pi / 180) * across + std::sin(tiltDeg * Pi / 180) * c.Axis;
      // Sweep away from the withdrawn tip, so the transit meets the pass at its start.
      if (Dot(sweep, c.Closest - a.Withdrawn) < 0)
      {
        sweep = -1.0 * sweep;
      }
      const double before = ReachClearance(vessels, c.Closest, -1.0 * sweep, WithdrawnDistanceMm, 1.0);
      const double after = ReachClearance(vessels, c.Closest, sweep, EndDistanceMm, 1.0);
      if (before < 0 || after < 0)
      {
        continue;
      }
      Pass p;
      p.PassStart = c.Closest - before * sweep;
      p.Closest = c.Closest;
      p.End = c.Closest + after * sweep;
      p.VeinRadiusMm = c.RadiusMm;
      if (TotalDuration(PlanLegs(a, p)) > MaximumDurationS)
      {
        continue;
      }
      p.Samples = SampleLeg(vessels, p.PassStart, p.End);
      double minimum = std::numeric_limits<double>::infinity();
      for (double d : p.Samples.DistancesMm)
      {
        minimum = std::min(minimum, d);
      }
      if (LevelSequence(p.Samples.DistancesMm) != wantedPass || !ClearOfThresholds(p.Samples.DistancesMm) ||
        !OnlyNear(p.Samples, hepatic) || minimum < PassDistanceMm - 0.1)
      {
        continue;
      }
      const LegSamples transit = SampleLeg(vessels, a.Withdrawn, p.PassStart);
      LegSamples all = a.Samples;
      all.Append(SampleLeg(vessels, a.Target, a.Withdrawn));
      all.Append(transit);
      all.Append(p.Samples);
      if (LevelSequence(all.DistancesMm) != wantedAll || !ClearOfThresholds(all.DistancesMm))
      {
        continue;
      }
      found = p;
      return true;
    }
  }
  return false;
}

/// Where the tip is at time t on the legs (half-cosine speed profile on each).
Vec3 TipAt(const std::vector<Leg>& legs, double t)
{
  for (const Leg& l : legs)
  {
    if (t <= l.DurationS)
    {
      const double u = l.DurationS > 0 ? t / l.DurationS : 1.0;
      const double s = 0.5 * (1.0 - std::cos(Pi * u));
      return l.From + s * (l.To - l.From);
    }
    t -= l.DurationS;
  }
  return legs.back().To;
}

DemoKeyPoint KeyPoint(const Vessels& vessels, const std::string& name, double timeS, const Vec3& tip)
{
  const auto [c, d] = vessels.Nearest(tip);
  DemoKeyPoint k;
  k.Name = name;
  k.TimeS = timeS;
  k.TipMm = tip;
  k.ClassName = vessels.Name(c);
  k.DistanceMm = d;
  k.Level = LevelOf(d);
  return k;
}
} // namespace

AnalyticProximity AnalyticProximityAt(
  const LiverPhantom& phantom, const std::array<double, 3>& tipMm, const DangerThresholds& thresholds)
{
  AnalyticProximity result;
  result.NearestMm = std::numeric_limits<double>::infinity();
  for (const auto& [name, tree] : phantom.Centrelines)
  {
    const double d = TreeSignedDistanceMm(tree, tipMm);
    if (d < result.NearestMm)
    {
      result.NearestMm = d;
      result.NearestClass = name;
    }
  }
  result.Level = result.NearestMm < 0 ? DangerLevel::Breach : ClassifyDistance(result.NearestMm, thresholds);
  return result;
}

DemoTrajectory DesignDemoTrajectory(const LiverPhantom& phantom, double rateHz)
{
  if (!(rateHz >= 1.0 && rateHz <= 1000.0))
  {
    throw InputError("demo trajectory", "rate must be 1-1000 Hz (got " + NumberText(rateHz) + ")");
  }
  const Vessels vessels(phantom);
  const int portal = vessels.IndexOf("portal_vein"), hepatic = vessels.IndexOf("hepatic_vein");
  if (portal < 0 || hepatic < 0)
  {
    throw InputError("demo trajectory", "the phantom has no portal or hepatic vein");
  }
  const std::vector<Approach> approaches = FindApproaches(vessels, portal);
  // The best few approaches are enough: each has many passes to choose from.
  const std::size_t tried = std::min<std::size_t>(approaches.size(), 6);
  for (std::size_t i = 0; i < tried; ++i)
  {
    const Approach& a = approaches[i];
    Pass p;
    if (!FindPass(vessels, hepatic, a, p))
    {
      continue;
    }
    const std::vector<Leg> legs = PlanLegs(a, p);
    const double total = TotalDuration(legs);
    DemoTrajectory trajectory;
    trajectory.AxisDirection = a.Direction;
    trajectory.TargetRadiusMm = a.TargetRadiusMm;
    trajectory.PassRadiusMm = p.VeinRadiusMm;
    double rotation[3][3];
    RotationFromZ(a.Direction.data(), rotation);
    const int frames = static_cast<int>(std::ceil(total * rateHz - 1e-9));
    for (int f = 0; f <= frames; ++f)
    {
      TrackedPose pose;
      pose.TimeS = f / rateHz;
      const Vec3 tip = TipAt(legs, pose.TimeS);
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          pose.ModelToWorld[static_cast<std::size_t>(4 * r + c)] = rotation[r][c];
        }
        pose.ModelToWorld[static_cast<std::size_t>(4 * r + 3)] = tip[static_cast<std::size_t>(r)];
      }
      pose.ModelToWorld[15] = 1.0;
      trajectory.Poses.push_back(pose);
    }
    // Times of the key points: ends of legs, and the closest point of the sweep, where the
    // half-cosine profile has covered the fraction s of the leg at u = acos(1 - 2 s) / pi.
    const double breachTime = legs[0].DurationS;
    const double withdrawnTime = breachTime + legs[1].DurationS + legs[2].DurationS;
    const double passStartTime = withdrawnTime + legs[3].DurationS;
    const double fraction = Norm(p.Closest - p.PassStart) / Norm(p.End - p.PassStart);
    const double passTime = passStartTime + legs[4].DurationS * std::acos(1.0 - 2.0 * fraction) / Pi;
    trajectory.KeyPoints = { KeyPoint(vessels, "start", 0.0, a.Start), KeyPoint(vessels, "breach", breachTime, a.Target),
      KeyPoint(vessels, "withdrawn", withdrawnTime, a.Withdrawn),
      KeyPoint(vessels, "hepatic pass", passTime, p.Closest), KeyPoint(vessels, "end", total, p.End) };
    return trajectory;
  }
  throw InputError("demo trajectory", "no path through this phantom meets the design");
}

std::vector<DangerLevel> DemoTrajectoryLevelSequence()
{
  return { DangerLevel::Safe, DangerLevel::Caution, DangerLevel::Warning, DangerLevel::Danger, DangerLevel::Breach,
    DangerLevel::Danger, DangerLevel::Warning, DangerLevel::Caution, DangerLevel::Safe, DangerLevel::Caution,
    DangerLevel::Warning, DangerLevel::Caution, DangerLevel::Safe };
}

std::vector<TrackedPose> MakeDemoTrajectory(const LiverPhantom& phantom, double rateHz)
{
  return DesignDemoTrajectory(phantom, rateHz).Poses;
}
} // namespace vp
