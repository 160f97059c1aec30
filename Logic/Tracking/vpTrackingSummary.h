#ifndef vpTrackingSummary_h
#define vpTrackingSummary_h

#include "vpFrameOutput.h"
#include "vpRunningQuantiles.h"
#include "vtkScalpelTrackingLogic.h"

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// The closest a class came during a run, and when. Inside counts as closer than any distance
/// outside, and a deeper penetration as closer still: the minimum of the signed distance.
struct ClassMinimum
{
  bool Seen = false; ///< false when the class was never in range
  bool Inside = false; ///< then DistanceMm is the penetration depth
  double DistanceMm = 0.0;
  double ErrorBoundMm = 0.0; ///< that answer's bound (0 for the exact engines)
  int Frame = 0;
  double TimeS = 0.0;
  double PointMm[3] = { 0, 0, 0 }; ///< closest vessel point at that frame
};

/// The instrument's largest penetration of one class over a run (each maximum from its own frame).
struct ClassPenetration
{
  bool Known = true;          ///< false when some frame could not decide it (an open surface)
  double DepthMm = 0.0;       ///< deepest
  double DepthBoundMm = 0.0;
  int DepthFrame = -1;        ///< -1: never inside
  double VolumeMm3 = 0.0;     ///< largest volume
  double VolumeBoundMm3 = 0.0;
  int VolumeFrame = -1;
  int FramesInside = 0;       ///< frames with any volume inside
};

/// One tumour over a run: the smallest margin the tip kept (its signed distance, negative inside)
/// and the time at each margin level.
struct TumourMarginSummary
{
  std::string Id;
  double MarginMinMm = 0.0;
  int Frame = 0;
  double TimeS = 0.0;
  double PointMm[3] = { 0, 0, 0 }; ///< closest tumour point at that frame
  /// The instrument's closest approach over the run (0: it touched or crossed the tumour);
  /// false when the instrument was not measured.
  bool SurfaceSeen = false;
  double SurfaceMinMm = 0.0;
  std::array<double, NumberOfMarginLevels> TimeInLevelS{};
  std::array<int, NumberOfMarginLevels> FramesInLevel{};
};

/// What a surgeon or researcher reads after a run: per class the closest approach of the tip
/// (and of the whole surface when computed), the time spent at each danger level, and the
/// level changes. Frames are added in order; nothing grows with their number but the level
/// changes. An output of the frame pipeline (vp::FrameOutput) that keeps all of it.
class TrackingSummary : public FrameOutput
{
public:
  void Add(const TrackedFrame& frame);
  void AddChange(const DangerLevelChange& change) { this->Changes.push_back(change); }
  void AddMarginChange(const MarginLevelChange& change) { this->MarginChanges.push_back(change); }
  void OnFrame(const TrackedFrame& frame) override { this->Add(frame); }
  void OnLevelChange(const DangerLevelChange& change) override { this->AddChange(change); }
  void OnMarginChange(const MarginLevelChange& change) override { this->AddMarginChange(change); }

  int GetNumberOfFrames() const { return this->Frames; }
  double GetDurationS() const { return this->Frames > 0 ? this->LastTimeS - this->FirstTimeS : 0.0; }
  const std::vector<std::string>& GetClassNames() const { return this->ClassNames; }
  const std::vector<ClassMinimum>& GetTipMinimum() const { return this->TipMinimum; }
  const std::vector<ClassMinimum>& GetSurfaceMinimum() const { return this->SurfaceMinimum; }
  /// Per class, the frames whose tip's inside was uncertain (the rays' votes on a defective
  /// surface disagreed; those frames' level is a breach).
  const std::vector<int>& GetFramesInsideUncertain() const { return this->FramesInsideUncertain; }
  /// Per class, the frames at its breach level: the tip or the whole instrument inside it (or
  /// undecidably so).
  const std::vector<int>& GetFramesInBreach() const { return this->FramesInBreach; }
  /// Per class; empty when no frame carried penetrations.
  const std::vector<ClassPenetration>& GetPenetrationMaximum() const { return this->PenetrationMaximum; }
  /// Seconds at each level (index: DangerLevel). A frame's level holds until the next frame's
  /// time, so the last frame adds nothing and the times sum to the duration.
  const std::array<double, NumberOfDangerLevels>& GetTimeInLevelS() const { return this->TimeInLevelS; }
  /// Frames at each level.
  const std::array<int, NumberOfDangerLevels>& GetFramesInLevel() const { return this->FramesInLevel; }
  const std::vector<DangerLevelChange>& GetChanges() const { return this->Changes; }
  /// Per tumour, in the scene's order; empty without tumours. Times as GetTimeInLevelS().
  const std::vector<TumourMarginSummary>& GetTumours() const { return this->Tumours; }
  const std::vector<MarginLevelChange>& GetMarginChanges() const { return this->MarginChanges; }
  MarginLevel GetWorstMarginLevel() const { return this->WorstMargin; }
  DangerLevel GetWorstLevel() const { return this->Worst; }
  /// The worst level of the tip alone, and of the whole instrument alone (Safe when it was never
  /// measured: GetInstrumentMeasured()).
  DangerLevel GetWorstTipLevel() const { return this->WorstTip; }
  DangerLevel GetWorstInstrumentLevel() const { return this->WorstInstrument; }
  bool GetInstrumentMeasured() const { return this->InstrumentMeasured; }
  /// The q-quantile of the frames' computing times (ms; nearest rank, vp::RunningQuantiles: at
  /// most 0.1% above the exact one, the maximum exact), in memory that does not grow with the run.
  double GetFrameMsQuantile(double q) const { return this->FrameMs.Quantile(q); }
  /// Frames the tracking logic marked as over its frame budget.
  int GetFramesOverBudget() const { return this->FramesOverBudget; }
  /// With haptics on: the largest force (N) and the frames with one.
  bool HasHaptic() const { return this->Haptic; }
  double GetMaxHapticForceN() const { return this->MaxHapticForceN; }
  int GetFramesWithHapticForce() const { return this->FramesWithHapticForce; }

private:
  void AddTumours(const TumourMargin& margin, const TrackedFrame& frame);
  int Frames = 0;
  double FirstTimeS = 0.0;
  double LastTimeS = 0.0;
  DangerLevel LastLevel = DangerLevel::Safe;
  DangerLevel Worst = DangerLevel::Safe;
  DangerLevel WorstTip = DangerLevel::Safe;
  DangerLevel WorstInstrument = DangerLevel::Safe;
  bool InstrumentMeasured = false;
  std::vector<std::string> ClassNames;
  std::vector<ClassMinimum> TipMinimum;
  std::vector<ClassMinimum> SurfaceMinimum;
  std::vector<int> FramesInsideUncertain;
  std::vector<int> FramesInBreach;
  std::vector<ClassPenetration> PenetrationMaximum;
  std::array<double, NumberOfDangerLevels> TimeInLevelS{};
  std::array<int, NumberOfDangerLevels> FramesInLevel{};
  std::vector<DangerLevelChange> Changes;
  std::vector<TumourMarginSummary> Tumours;
  std::vector<MarginLevel> LastMarginLevels;
  std::vector<MarginLevelChange> MarginChanges;
  MarginLevel WorstMargin = MarginLevel::Clear;
  RunningQuantiles FrameMs;
  int FramesOverBudget = 0;
  bool Haptic = false;
  double MaxHapticForceN = 0.0;
  int FramesWithHapticForce = 0;
};
} // namespace vp

#endif
