#include "vpApproachRecorder.h"

#include <algorithm>

namespace vp
{
namespace
{
/// Closer than the smallest distance so far by less than this, a pose is taken as the same
/// closest approach: the first pose that reaches it is reported, not one that rounding made a
/// fraction of a micrometre closer while the instrument slid along a wall parallel to its path.
constexpr double SameApproachMm = 1e-3;

void Lower(ClassApproach& c, const SurfaceProximity& s, const TrackedFrame& frame)
{
  if (!c.InRange || s.DistanceMm < c.ClosestMm - SameApproachMm)
  {
    c.InRange = true;
    c.Step = frame.Frame;
    c.TimeS = frame.TimeS;
    std::copy(s.PointOnVesselMm, s.PointOnVesselMm + 3, c.PointMm);
    std::copy(s.PointOnToolMm, s.PointOnToolMm + 3, c.PointOnToolMm);
    c.ClosestMm = s.DistanceMm;
  }
  c.ClosestMm = std::min(c.ClosestMm, s.DistanceMm); // the exact smallest, as track's frames have it
}
} // namespace

void ApproachRecorder::OnFrame(const TrackedFrame& frame)
{
  const auto& classes = frame.Proximity.Classes;
  if (this->Classes.empty())
  {
    for (const ClassProximity& c : classes)
    {
      this->Classes.push_back(ClassApproach());
      this->Classes.back().ClassName = c.ClassName;
    }
  }
  for (std::size_t c = 0; c < this->Classes.size(); ++c)
  {
    if (c < frame.Surface.size() && frame.Surface[c].InRange)
    {
      Lower(this->Classes[c], frame.Surface[c], frame);
    }
    if (c < frame.Penetrations.size() && frame.Penetrations[c].Known)
    {
      this->Classes[c].PenetrationDepthMm = std::max(this->Classes[c].PenetrationDepthMm, frame.Penetrations[c].DepthMm);
    }
  }
  this->Levels.push_back(frame.Level);
  this->StepMs.push_back(frame.FrameMs);
  if (frame.Tumour && !frame.Tumour->Tumours.empty())
  {
    this->TipTargetSignedMm = frame.Tumour->Tumours.front().SignedMm;
  }
}

void ApproachRecorder::Fill(PlannedApproach& approach, double rangeMm) const
{
  approach.Classes = this->Classes;
  approach.StepLevels = this->Levels;
  approach.TipTargetSignedMm = this->TipTargetSignedMm;
  approach.ClearanceMm = rangeMm;
  approach.ClearanceClass.clear();
  for (const ClassApproach& c : this->Classes)
  {
    if (c.InRange && c.ClosestMm < approach.ClearanceMm)
    {
      approach.ClearanceMm = c.ClosestMm;
      approach.ClearanceClass = c.ClassName;
    }
  }
}
} // namespace vp
