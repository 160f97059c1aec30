#include "vtkScalpelTrackingLogic.h"

#include "vpInputError.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkObjectFactory.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

vtkStandardNewMacro(vtkScalpelTrackingLogic);

vtkScalpelTrackingLogic::vtkScalpelTrackingLogic() = default;
vtkScalpelTrackingLogic::~vtkScalpelTrackingLogic() = default;

void vtkScalpelTrackingLogic::SetDistanceEngine(vtkVesselDistanceEngine* engine)
{
  if (this->Engine != engine)
  {
    this->Engine = engine;
    this->Reset(); // the previous answer came from another engine
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::SetScalpel(vtkScalpelModel* scalpel)
{
  if (this->Scalpel != scalpel)
  {
    this->Scalpel = scalpel;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::SetSurfaceDistance(vtkScalpelSurfaceDistance* surface)
{
  if (this->SurfaceDistance != surface)
  {
    this->SurfaceDistance = surface;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::SetReferenceEngine(vtkVesselDistanceEngine* reference)
{
  if (this->Reference != reference)
  {
    this->Reference = reference;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::SetPenetration(vtkScalpelPenetration* penetration)
{
  if (this->Penetration != penetration)
  {
    this->Penetration = penetration;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::ReadSettingsFrom(const vp::TrackingSettings* settings)
{
  const vp::TrackingSettings* now = settings ? settings : &this->OwnSettings;
  if (this->Settings != now)
  {
    this->Settings = now;
    this->Modified();
  }
}

vp::TrackingSettings& vtkScalpelTrackingLogic::OwnSettingsToSet()
{
  if (this->Settings != &this->OwnSettings)
  {
    throw std::logic_error("vtkScalpelTrackingLogic: its settings are the parameter set's; set them there");
  }
  return this->OwnSettings;
}

void vtkScalpelTrackingLogic::SetHysteresisMm(double hysteresisMm)
{
  if (!(hysteresisMm >= 0.0) || !std::isfinite(hysteresisMm))
  {
    throw vp::InputError("hysteresis", "expected a distance in mm, 0 or more, got " + vp::NumberText(hysteresisMm));
  }
  if (this->Settings->HysteresisMm != hysteresisMm)
  {
    this->OwnSettingsToSet().HysteresisMm = hysteresisMm;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::ValidateSettings() const
{
  if (!this->Engine)
  {
    throw std::logic_error("vtkScalpelTrackingLogic: set the distance engine first");
  }
  this->Settings->Thresholds.Validate("danger thresholds");
  // An engine with a bound reports a class out of range when its estimate is beyond the range,
  // where the truth may lie the bound nearer: the range must reach the threshold by that much.
  const double boundMm = this->Engine->GetErrorBoundMm();
  if (this->Engine->GetRangeMm() < this->Settings->Thresholds.CautionMm + boundMm)
  {
    throw vp::ParameterError("RangeMm", "the range (" + vp::NumberText(this->Engine->GetRangeMm()) +
        " mm) must reach the caution threshold (" + vp::NumberText(this->Settings->Thresholds.CautionMm) + " mm)" +
        (boundMm > 0.0 ? " plus the engine's error bound (" + vp::NumberText(boundMm) + " mm)" : std::string()) +
        ", or a class beyond it would look safe");
  }
  if (this->Engine->GetErrorBoundMm() >= this->Settings->Thresholds.DangerMm)
  {
    throw vp::InputError("cell size", "the engine's error bound (" + vp::NumberText(this->Engine->GetErrorBoundMm()) +
        " mm) must be below the danger threshold (" + vp::NumberText(this->Settings->Thresholds.DangerMm) +
        " mm), or it cannot tell danger from safety: use smaller cells");
  }
}

void vtkScalpelTrackingLogic::Reset()
{
  this->Last = vp::TrackedFrame();
  this->FramesProcessed = 0;
  this->Haptic.Reset();
}

namespace
{
/// The whole instrument's search about the tumours with a margin and band of 0: a touch.
constexpr double MinimumInstrumentRangeMm = 1.0;
} // namespace

void vtkScalpelTrackingLogic::SetTumourMargin(vtkTumourMarginDistance* margin)
{
  if (this->TumourMargin != margin)
  {
    this->TumourMargin = margin;
    this->Modified();
  }
}

void vtkScalpelTrackingLogic::SetMarginSettings(const vp::MarginSettings& margin)
{
  margin.Validate("MarginMm");
  this->OwnSettingsToSet().Margin = margin;
}

void vtkScalpelTrackingLogic::ClassifyMargins(vp::TumourMargin& margin, bool hasPrevious) const
{
  const vp::TumourMargin* before = hasPrevious && this->Last.Tumour ? &*this->Last.Tumour : nullptr;
  for (std::size_t t = 0; t < margin.Tumours.size(); ++t)
  {
    vp::TumourProximity& p = margin.Tumours[t];
    const vp::MarginLevel previous =
      before && t < before->Tumours.size() ? before->Tumours[t].Level : vp::MarginLevel::Clear;
    p.Level = vp::ClassifyMargin(p.SignedMm, p.InsideUncertain, this->Settings->Margin, previous, this->Settings->HysteresisMm);
    const bool worse = margin.Worst < 0 || p.Level > margin.Level ||
      (p.Level == margin.Level && p.SignedMm < margin.Tumours[margin.Worst].SignedMm);
    if (worse)
    {
      margin.Level = p.Level;
      margin.Worst = static_cast<int>(t);
    }
  }
}

void vtkScalpelTrackingLogic::SetHapticSettings(const vp::HapticSettings& haptic)
{
  haptic.Validate();
  this->OwnSettingsToSet().Haptic = haptic;
}

void vtkScalpelTrackingLogic::Measure(const vp::TrackedPose& pose, bool hasPrevious, vp::TrackedFrame& frame)
{
  const auto start = std::chrono::steady_clock::now();
  auto lap = start;
  auto timePart = [&lap](double& ms) {
    const auto now = std::chrono::steady_clock::now();
    ms = std::chrono::duration<double, std::milli>(now - lap).count();
    lap = now;
  };
  this->Engine->ComputeProximity(frame.TipMm, frame.AxisWorld, frame.Proximity, hasPrevious ? &this->Last.Proximity : nullptr);
  timePart(frame.PartsMs.TipMs);
  if (this->SurfaceDistance)
  {
    this->SurfaceDistance->ComputeSurfaceProximity(
      pose.ModelToWorld, frame.Surface, hasPrevious && !this->Last.Surface.empty() ? &this->Last.Surface : nullptr);
    timePart(frame.PartsMs.SurfaceMs);
    if (this->Penetration)
    {
      this->Penetration->ComputePenetration(pose.ModelToWorld, frame.Surface, frame.Penetrations);
      timePart(frame.PartsMs.PenetrationMs);
    }
  }
  if (this->TumourMargin && this->TumourMargin->GetNumberOfTumours() > 0)
  {
    frame.Tumour.emplace();
    // The instrument is measured where a tumour is more than clear: within the margin and its band.
    const vp::MarginSettings& m = this->Settings->Margin;
    this->TumourMargin->SetInstrumentRangeMm(std::max(m.MarginMm + m.NearBandMm, MinimumInstrumentRangeMm));
    this->TumourMargin->ComputeMargin(
      frame.TipMm, pose.ModelToWorld, *frame.Tumour, hasPrevious && this->Last.Tumour ? &*this->Last.Tumour : nullptr);
    timePart(frame.PartsMs.MarginMs);
  }
  frame.FrameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

namespace
{
/// The worst of levels (the nearer class among equals, by distance): its level and class.
template <typename DistanceOf>
std::pair<vp::DangerLevel, int> WorstOf(const std::vector<vp::DangerLevel>& levels, DistanceOf distanceOf)
{
  std::pair<vp::DangerLevel, int> worst{ vp::DangerLevel::Safe, -1 };
  for (std::size_t c = 0; c < levels.size(); ++c)
  {
    const bool worse = worst.second < 0 || levels[c] > worst.first ||
      (levels[c] == worst.first && distanceOf(c) < distanceOf(static_cast<std::size_t>(worst.second)));
    if (levels[c] != vp::DangerLevel::Safe && worse)
    {
      worst = { levels[c], static_cast<int>(c) };
    }
  }
  return worst;
}
} // namespace

void vtkScalpelTrackingLogic::ClassifyDanger(vp::TrackedFrame& frame, bool hasPrevious) const
{
  const auto& classes = frame.Proximity.Classes;
  const vp::TrackedFrame& last = this->Last;
  frame.ClassLevels.resize(classes.size());
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const vp::DangerLevel before = hasPrevious && c < last.ClassLevels.size() ? last.ClassLevels[c] : vp::DangerLevel::Safe;
    frame.ClassLevels[c] = vp::ClassifyDangerWithHysteresis(
      classes[c], frame.Proximity.ErrorBoundMm, this->Settings->Thresholds, before, this->Settings->HysteresisMm);
  }
  std::tie(frame.TipLevel, frame.TipLevelClass) = WorstOf(frame.ClassLevels, [&](std::size_t c) { return classes[c].DistanceMm; });
  frame.InstrumentClassLevels.resize(frame.Surface.size());
  for (std::size_t c = 0; c < frame.Surface.size(); ++c)
  {
    const vp::DangerLevel before =
      hasPrevious && c < last.InstrumentClassLevels.size() ? last.InstrumentClassLevels[c] : vp::DangerLevel::Safe;
    frame.InstrumentClassLevels[c] = vp::ClassifyInstrumentWithHysteresis(frame.Surface[c],
      c < frame.Penetrations.size() ? &frame.Penetrations[c] : nullptr, this->Settings->Thresholds, before,
      this->Settings->HysteresisMm);
    // The tip is the instrument's: a tip inside is an instrument inside, even one whose walls are
    // all beyond the range (where its surface distance and penetration are not searched).
    if (c < frame.ClassLevels.size() && frame.ClassLevels[c] == vp::DangerLevel::Breach)
    {
      frame.InstrumentClassLevels[c] = vp::DangerLevel::Breach;
    }
  }
  std::tie(frame.InstrumentLevel, frame.InstrumentLevelClass) =
    WorstOf(frame.InstrumentClassLevels, [&](std::size_t c) { return frame.Surface[c].DistanceMm; });
  // The instrument sets the frame's level only where it is worse than the tip: the tip is what the
  // surgeon steers by, and its distance the one a level usually names.
  const bool instrument = frame.InstrumentLevel > frame.TipLevel;
  frame.Level = instrument ? frame.InstrumentLevel : frame.TipLevel;
  frame.LevelClass = instrument ? frame.InstrumentLevelClass : frame.TipLevelClass;
  frame.LevelCause = frame.LevelClass < 0 ? vp::DangerCause::None : instrument ? vp::DangerCause::Instrument : vp::DangerCause::Tip;
}

const vp::TrackedFrame& vtkScalpelTrackingLogic::ProcessPose(const vp::TrackedPose& pose)
{
  if (!this->Engine || !this->Scalpel)
  {
    throw std::logic_error("vtkScalpelTrackingLogic: set the distance engine and the scalpel first");
  }
  if (this->FramesProcessed == 0)
  {
    this->ValidateSettings();
  }
  const bool hasPrevious = this->FramesProcessed > 0;
  const vp::DangerLevel previousLevel = this->Last.Level;
  const vp::MarginLevel previousMargin = this->Last.Tumour ? this->Last.Tumour->Level : vp::MarginLevel::Clear;
  // The previous answer narrows the engine's search; keep it while the new one is computed.
  vp::TrackedFrame frame;
  frame.Frame = this->FramesProcessed;
  frame.TimeS = pose.TimeS;
  frame.SourceClockS = pose.SourceClockS;
  this->Scalpel->SetModelToWorld(pose.ModelToWorld);
  this->Scalpel->GetTipInWorld(frame.TipMm);
  this->Scalpel->GetAxisInWorld(frame.AxisWorld);

  this->Measure(pose, hasPrevious, frame);
  frame.OverBudget = this->Settings->FrameBudgetMs > 0.0 && frame.FrameMs > this->Settings->FrameBudgetMs;
  if (this->Reference && this->Reference != this->Engine)
  {
    frame.Exact.emplace();
    this->Reference->ComputeProximity(frame.TipMm, frame.AxisWorld, *frame.Exact);
  }

  this->ClassifyDanger(frame, hasPrevious);
  if (frame.Tumour)
  {
    this->ClassifyMargins(*frame.Tumour, hasPrevious);
  }
  if (this->Settings->Haptic.Enabled())
  {
    if (!(this->Haptic.GetSettings() == this->Settings->Haptic))
    {
      this->Haptic = vp::HapticForce(this->Settings->Haptic); // a new contact model: no rate carried over
    }
    frame.Haptic = this->Haptic.Update(frame);
  }
  else
  {
    this->Haptic.Reset(); // switched on again later: no rate carried over the gap
  }
  this->Last = std::move(frame);
  ++this->FramesProcessed;

  // The first frame reports its level only when it is not safe: a tracking session starts safe.
  if (this->Last.Level != previousLevel)
  {
    vp::DangerLevelChange change;
    change.Frame = this->Last.Frame;
    change.TimeS = this->Last.TimeS;
    change.From = previousLevel;
    change.To = this->Last.Level;
    change.Cause = this->Last.LevelCause;
    if (this->Last.LevelClass >= 0)
    {
      const auto c = static_cast<std::size_t>(this->Last.LevelClass);
      change.ClassName = this->Last.Proximity.Classes[c].ClassName;
      change.DistanceMm = change.Cause == vp::DangerCause::Instrument ? this->Last.Surface[c].DistanceMm
                                                                       : this->Last.Proximity.Classes[c].DistanceMm;
    }
    this->InvokeEvent(DangerLevelChangedEvent, &change);
  }
  if (this->Last.Tumour && this->Last.Tumour->Level != previousMargin)
  {
    const vp::TumourMargin& m = *this->Last.Tumour;
    vp::MarginLevelChange change;
    change.Frame = this->Last.Frame;
    change.TimeS = this->Last.TimeS;
    change.From = previousMargin;
    change.To = m.Level;
    change.TumourId = m.Tumours[m.Worst].Id;
    change.SignedMm = m.Tumours[m.Worst].SignedMm;
    this->InvokeEvent(MarginLevelChangedEvent, &change);
  }
  this->InvokeEvent(FrameProcessedEvent, &this->Last);
  return this->Last;
}

void vtkScalpelTrackingLogic::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DistanceEngine: " << (this->Engine ? this->Engine->GetMethodName() : "(none)") << "\n";
  os << indent << "Scalpel: " << (this->Scalpel ? "set" : "(none)") << "\n";
  os << indent << "SurfaceDistance: " << (this->SurfaceDistance ? this->SurfaceDistance->GetMethodName() : "off") << "\n";
  os << indent << "Penetration: " << (this->Penetration ? "on" : "off") << "\n";
  os << indent << "Tumours: " << (this->TumourMargin ? this->TumourMargin->GetNumberOfTumours() : 0) << "\n";
  os << indent << "MarginMm: " << this->Settings->Margin.MarginMm << " (near band " << this->Settings->Margin.NearBandMm
     << ")\n";
  os << indent << "DangerThresholds (caution, warning, danger): " << this->Settings->Thresholds.CautionMm << ", "
     << this->Settings->Thresholds.WarningMm << ", " << this->Settings->Thresholds.DangerMm << " mm\n";
  os << indent << "HysteresisMm: " << this->Settings->HysteresisMm << "\n";
  os << indent << "HapticStiffnessNPerMm: " << this->Settings->Haptic.StiffnessNPerMm << "\n";
  os << indent << "HapticDampingNsPerMm: " << this->Settings->Haptic.DampingNsPerMm << "\n";
  os << indent << "FrameBudgetMs: " << this->Settings->FrameBudgetMs << (this->Settings->FrameBudgetMs > 0 ? "" : " (off)") << "\n";
  os << indent << "FramesProcessed: " << this->FramesProcessed << "\n";
}
