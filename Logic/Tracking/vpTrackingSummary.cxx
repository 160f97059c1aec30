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
    this->FramesInBreach.resize(classes.size());
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
    this->FramesInBreach[c] += frame.ClassLevel(c) == DangerLevel::Breach ? 1 : 0;
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
  if (frame.Tumour)
  {
    this->AddTumours(*frame.Tumour, frame);
  }
  ++this->FramesInLevel[static_cast<int>(frame.Level)];
  this->Worst = std::max(this->Worst, frame.Level);
  this->WorstTip = std::max(this->WorstTip, frame.TipLevel);
  this->WorstInstrument = std::max(this->WorstInstrument, frame.InstrumentLevel);
  this->InstrumentMeasured = this->InstrumentMeasured || !frame.InstrumentClassLevels.empty();
  this->LastLevel = frame.Level;
  this->LastTimeS = frame.TimeS;
  ++this->Frames;
}

void TrackingSummary::AddTumours(const TumourMargin& margin, const TrackedFrame& frame)
{
  const bool first = this->Tumours.empty();
  if (first)
  {
    this->Tumours.resize(margin.Tumours.size());
    this->LastMarginLevels.assign(margin.Tumours.size(), MarginLevel::Clear);
  }
  for (std::size_t t = 0; t < margin.Tumours.size() && t < this->Tumours.size(); ++t)
  {
    const TumourProximity& p = margin.Tumours[t];
    TumourMarginSummary& s = this->Tumours[t];
    if (first)
    {
      s.Id = p.Id;
    }
    else
    {
      s.TimeInLevelS[static_cast<int>(this->LastMarginLevels[t])] += frame.TimeS - this->LastTimeS;
    }
    if (first || p.SignedMm < s.MarginMinMm)
    {
      s.MarginMinMm = p.SignedMm;
      s.Frame = frame.Frame;
      s.TimeS = frame.TimeS;
      std::copy(p.ClosestPoint, p.ClosestPoint + 3, s.PointMm);
    }
    if (p.SurfaceKnown && (!s.SurfaceSeen || p.SurfaceMm < s.SurfaceMinMm))
    {
      s.SurfaceSeen = true;
      s.SurfaceMinMm = p.SurfaceMm;
    }
    ++s.FramesInLevel[static_cast<int>(p.Level)];
    this->LastMarginLevels[t] = p.Level;
  }
  this->WorstMargin = std::max(this->WorstMargin, margin.Level);
}
} // namespace vp
