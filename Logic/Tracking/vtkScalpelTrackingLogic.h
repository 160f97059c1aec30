#ifndef vtkScalpelTrackingLogic_h
#define vtkScalpelTrackingLogic_h

#include "vpDangerLevels.h"
#include "vpHapticForce.h"
#include "vpTrackedFrame.h"
#include "vpTrackingSettings.h"
#include "vpPoseFile.h"
#include "vpProximityResult.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelPenetration.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkTumourMarginDistance.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkCommand.h>
#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <vector>


/// Turns tracked poses of a scalpel into per-frame proximity records and danger-level events.
///
/// For each pose: the scalpel's tip and axis go to world coordinates, the distance engine answers
/// for every vessel class (passing the previous frame's answer, so a moving tip costs little),
/// each class gets a danger level and the frame the worst of them. With a surface-distance
/// calculator set, the closest approach of the whole instrument surface (and with a penetration
/// calculator, how far it is inside) is computed as well and graded by the same thresholds, so
/// the frame's level is the worse of the tip's and the instrument's: a shaft inside a vessel is a
/// breach whatever the tip's distance. DangerLevelChangedEvent is invoked with a
/// vp::DangerLevelChange as call data only when that level differs from the previous frame's,
/// never on every frame.
///
/// The logic owns no UI: a widget observes the event and reads GetLastFrame().
class vtkScalpelTrackingLogic : public vtkObject
{
public:
  static vtkScalpelTrackingLogic* New();
  vtkTypeMacro(vtkScalpelTrackingLogic, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum
  {
    DangerLevelChangedEvent = vtkCommand::UserEvent + 1201,
    /// Invoked after every processed pose with the vp::TrackedFrame as call data: overlays move
    /// on it, and recolour only on DangerLevelChangedEvent.
    FrameProcessedEvent = vtkCommand::UserEvent + 1202,
    /// Invoked with a vp::MarginLevelChange as call data when the resection margin's level (the
    /// worst over the tumours) differs from the previous frame's; never on every frame.
    MarginLevelChangedEvent = vtkCommand::UserEvent + 1203
  };

  void SetDistanceEngine(vtkVesselDistanceEngine* engine);
  vtkVesselDistanceEngine* GetDistanceEngine() const { return this->Engine; }
  void SetScalpel(vtkScalpelModel* scalpel);
  vtkScalpelModel* GetScalpel() const { return this->Scalpel; }
  /// Optional: whole-surface distance (costs more than the tip; null switches it off, the default).
  void SetSurfaceDistance(vtkScalpelSurfaceDistance* surface);
  vtkScalpelSurfaceDistance* GetSurfaceDistance() const { return this->SurfaceDistance; }
  /// Optional, with the surface distance: the instrument's penetration volume and depth per class
  /// (null switches it off, the default).
  void SetPenetration(vtkScalpelPenetration* penetration);
  vtkScalpelPenetration* GetPenetration() const { return this->Penetration; }

  /// Optional: an exact engine every frame's tip is also answered by, into TrackedFrame::Exact,
  /// outside the frame's time (null, the default: none): the check of an approximate engine.
  void SetReferenceEngine(vtkVesselDistanceEngine* reference);
  vtkVesselDistanceEngine* GetReferenceEngine() const { return this->Reference; }

  /// Optional: the tip and the whole instrument against the tumours to be resected, each frame's
  /// TrackedFrame::Tumour (null, the default: no tumour). Its time counts in the frame's.
  void SetTumourMargin(vtkTumourMarginDistance* margin);
  vtkTumourMarginDistance* GetTumourMargin() const { return this->TumourMargin; }
  /// Where the settings below are read, each frame: the module's parameter set
  /// (vtkVesselProximityParameters::GetTrackingSettings, outliving this), which alone holds
  /// them and checks them as they are set; the setters below then refuse (std::logic_error).
  /// Null (the default): this logic's own, set by the setters, for use on its own.
  void ReadSettingsFrom(const vp::TrackingSettings* settings);

  /// The resection margin and its near band (vp::MarginSettings: 5 and 5 mm); the levels take the
  /// hysteresis of the danger levels. Throws as MarginSettings::Validate.
  void SetMarginSettings(const vp::MarginSettings& margin);
  const vp::MarginSettings& GetMarginSettings() const { return this->Settings->Margin; }

  /// The time a frame may take, in ms (default vp::TrackingSettings: 16.7, one refresh at 60 Hz; the paper's 40 ms is
  /// where a navigator's animation freezes). A frame that takes longer is marked OverBudget; 0
  /// switches the check off.
  void SetFrameBudgetMs(double budgetMs) { this->OwnSettingsToSet().FrameBudgetMs = budgetMs; }
  double GetFrameBudgetMs() const { return this->Settings->FrameBudgetMs; }

  /// Hysteresis on the way out of a level, in mm (default 0.3): entering a more dangerous level is
  /// immediate, leaving one needs the distance to exceed its threshold by this much (see
  /// vp::ClassifyDangerWithHysteresis); 0 switches it off. Tracking noise of a tenth of a
  /// millimetre at a threshold would otherwise flicker the level.
  void SetHysteresisMm(double hysteresisMm);
  double GetHysteresisMm() const { return this->Settings->HysteresisMm; }

  /// The contact force for a haptic device (vp::HapticSettings; off by default): each frame's
  /// TrackedFrame::Haptic when on. Validated with the other settings.
  void SetHapticSettings(const vp::HapticSettings& haptic);
  const vp::HapticSettings& GetHapticSettings() const { return this->Settings->Haptic; }

  /// Danger thresholds (defaults 10, 5, 2 mm). Validated when the first pose is processed.
  void SetDangerThresholds(const vp::DangerThresholds& thresholds) { this->OwnSettingsToSet().Thresholds = thresholds; }
  const vp::DangerThresholds& GetDangerThresholds() const { return this->Settings->Thresholds; }

  /// Throws vp::InputError when the engine's range is shorter than the caution threshold plus
  /// its error bound (a far class would look safe when it is not), or its error bound is not
  /// below the danger threshold (it could not tell danger from safety). ProcessPose checks this at its first frame; a front
  /// end calls it to refuse the settings before it says anything.
  void ValidateSettings() const;
  /// Places the scalpel at pose, computes the frame, fires the event on a change of level, and
  /// returns the frame (valid until the next call). Throws as ValidateSettings() at the first.
  const vp::TrackedFrame& ProcessPose(const vp::TrackedPose& pose);
  const vp::TrackedFrame& GetLastFrame() const { return this->Last; }
  int GetNumberOfFrames() const { return this->FramesProcessed; }
  /// Forgets the previous frame: the next pose is frame 0 and starts from the safe level.
  void Reset();

protected:
  vtkScalpelTrackingLogic();
  ~vtkScalpelTrackingLogic() override;

  vtkSmartPointer<vtkVesselDistanceEngine> Engine;
  vtkSmartPointer<vtkScalpelModel> Scalpel;
  vtkSmartPointer<vtkScalpelSurfaceDistance> SurfaceDistance;
  vtkSmartPointer<vtkScalpelPenetration> Penetration;
  vtkSmartPointer<vtkVesselDistanceEngine> Reference;
  vtkSmartPointer<vtkTumourMarginDistance> TumourMargin;
  vp::TrackingSettings OwnSettings;
  const vp::TrackingSettings* Settings = &OwnSettings;
  /// The settings the setters change: this logic's own (throws when they are read elsewhere).
  vp::TrackingSettings& OwnSettingsToSet();
  vp::TrackedFrame Last;
  int FramesProcessed = 0;
  vp::HapticForce Haptic;

private:
  /// Each tumour's level from the frame's distances and the previous frame's levels, the worst.
  /// The tip's level per class, the whole instrument's, and the frame's: the worse of the two.
  void ClassifyDanger(vp::TrackedFrame& frame, bool hasPrevious) const;
  void ClassifyMargins(vp::TumourMargin& margin, bool hasPrevious) const;
  /// The frame's measurements at the pose (the tip, the whole instrument and its penetration, the
  /// tumours' margins), each part timed, and FrameMs; the previous frame narrows the searches.
  void Measure(const vp::TrackedPose& pose, bool hasPrevious, vp::TrackedFrame& frame);
  vtkScalpelTrackingLogic(const vtkScalpelTrackingLogic&) = delete;
  void operator=(const vtkScalpelTrackingLogic&) = delete;
};

#endif
