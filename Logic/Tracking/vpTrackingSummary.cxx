#include "vpTrackingSummary.h"

#include <algorithm>

namespace vp
{
namespace
{
void Lower(ClassMinimum& minimum, double distanceMm, double boundMm, bool inside, const double point[3], const TrackedFrame& frame)
{
  const double signedMm = inside ? -distanceMm : distanceMm;
  if (!minimum.Seen || signedMm < (minimum.Inside ? -minimum.DistanceMm : minimum.DistanceMm))
  {
    minimum.Seen = true;
    minimum.Inside = inside;
    minimum.DistanceMm = distanceMm;
    minimum.ErrorBoundMm = boundMm;
    minimum.Frame = frame.Frame;
    minimum.TimeS = frame.TimeS;
    std::copy(point, point + 3, minimum.PointMm);
  }
}
} // namespace

void TrackingSummary::Add(const TrackedFrame& frame)
{
  this->FrameMs.Add(frame.FrameMs);
  this->FramesOverBudget += frame.OverBudget ? 1 : 0;
  if (frame.Haptic)
  {
    this->Haptic = true;
    this->MaxHapticForceN = std::max(this->MaxHapticForceN, frame.Haptic->ForceN);
    this->FramesWithHapticForce += frame.Haptic->ForceN > 0.0 ? 1 : 0;
  }
  const auto& classes = frame.Proximity.Classes;
  if (this->Frames == 0)
  {
    this->FirstTimeS = frame.TimeS;
    for (const auto& c : classes)
    {
      this->ClassNames.push_back(c.ClassName);
    }
    this->TipMinimum.resize(classes.size());
    this->SurfaceMinimum.resize(classes.size());
    this->FramesInsideUncertain.resize(classes.size());
  }
  else
  {
    this->TimeInLevelS[static_cast<int>(this->LastLevel)] += frame.TimeS - this->LastTimeS;
  }
  if (!frame.Penetrations.empty())
  {
    this->PenetrationMaximum.resize(classes.size());
  }
  for (std::size_t c = 0; c < classes.size() && c < this->TipMinimum.size(); ++c)
  {
    this->FramesInsideUncertain[c] += classes[c].InRange && classes[c].InsideUncertain ? 1 : 0;
    if (classes[c].InRange)
    {
      Lower(this->TipMinimum[c], classes[c].DistanceMm, frame.Proximity.ErrorBoundMm, classes[c].Inside.value_or(false),
        classes[c].ClosestPoint, frame);
    }
    if (c < frame.Surface.size() && frame.Surface[c].InRange)
    {
      Lower(this->SurfaceMinimum[c], frame.Surface[c].DistanceMm, frame.Surface[c].ErrorBoundMm, false,
        frame.Surface[c].PointOnVesselMm, frame);
    }
    if (c < frame.Penetrations.size())
    {
      const Penetration& p = frame.Penetrations[c];
      ClassPenetration& most = this->PenetrationMaximum[c];
      most.Known = most.Known && p.Known;
      if (p.Known && p.DepthMm > most.DepthMm)
      {
        most.DepthMm = p.DepthMm;
        most.DepthBoundMm = p.DepthBoundMm;
        most.DepthFrame = frame.Frame;
      }
      if (p.Known && p.VolumeMm3 > most.VolumeMm3)
      {
        most.VolumeMm3 = p.VolumeMm3;
        most.VolumeBoundMm3 = p.VolumeBoundMm3;
        most.VolumeFrame = frame.Frame;
      }
      most.FramesInside += p.Known && p.VolumeMm3 > 0.0 ? 1 : 0;
    }
  }
  ++this->FramesInLevel[static_cast<int>(frame.Level)];
  this->Worst = std::max(this->Worst, frame.Level);
  this->LastLevel = frame.Level;
  this->LastTimeS = frame.TimeS;
  ++this->Frames;
}
} // namespace vp
