#ifndef vtkVesselProximityParameters_h
#define vtkVesselProximityParameters_h

#include "vpInstrumentMethod.h"
#include "vtkScalpelPenetration.h"
#include "vpTrackingSettings.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

class vtkPolyData;
class vtkScalpelModel;
class vtkVesselDistanceEngine;

/// Everything the module logic computes from, in one object: the part vtkMRMLBreachWarningNode
/// plays for SlicerIGT's BreachWarning, and a Slicer parameter node plays for a scripted module.
/// A front end (a command, a CLI, the viewer) fills it; vtkVesselProximityLogic observes it and
/// rebuilds only what a change invalidates.
///
/// Every setter fires ModifiedEvent only when the value changes. Two clocks say what changed:
/// GetSceneMTime() for what the engines are built from (vessels, scalpel, engine, which engines
/// are wanted), GetSettingsMTime() for what is applied per frame (thresholds, hysteresis, frame
/// budget), which never causes a rebuild.
///
/// Defaults: no vessel, no scalpel, the exact engine, the whole instrument measured, no
/// comparison with the exact engine, and vp::TrackingSettings' thresholds, hysteresis and budget.
class vtkVesselProximityParameters : public vtkObject
{
public:
  static vtkVesselProximityParameters* New();
  vtkTypeMacro(vtkVesselProximityParameters, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds or replaces the surface of a vessel class (LPS mm, closed for inside/outside).
  void SetVessel(const std::string& className, vtkPolyData* surface);
  void RemoveAllVessels();
  int GetNumberOfVessels() const { return static_cast<int>(this->Vessels.size()); }
  const std::string& GetVesselClassName(int i) const { return this->Vessels[i].first; }
  vtkPolyData* GetVesselSurface(int i) const { return this->Vessels[i].second; }

  /// Adds or replaces a tumour to be resected (LPS mm, closed for inside/outside), under its id:
  /// the tip's resection margin is measured against every tumour (vtkTumourMarginDistance).
  void SetTumour(const std::string& id, vtkPolyData* surface);
  void RemoveAllTumours();
  int GetNumberOfTumours() const { return static_cast<int>(this->Tumours.size()); }
  const std::string& GetTumourId(int i) const { return this->Tumours[i].first; }
  vtkPolyData* GetTumourSurface(int i) const { return this->Tumours[i].second; }

  void SetScalpel(vtkScalpelModel* scalpel);
  vtkScalpelModel* GetScalpel() const { return this->Scalpel; }

  /// The engine that answers every frame, with its own settings (not null).
  void SetDistanceEngine(vtkVesselDistanceEngine* engine);
  vtkVesselDistanceEngine* GetDistanceEngine() const { return this->DistanceEngine; }

  /// Whether the whole instrument surface is measured beside the tip, with its penetration.
  void SetComputeSurfaceDistance(bool compute);
  bool GetComputeSurfaceDistance() const { return this->ComputeSurfaceDistance; }
  /// How the whole instrument is measured (default Automatic: the z-buffer's layers when the
  /// engine is the z-buffer with a fixed box, else FCL).
  void SetInstrumentMethod(vp::InstrumentMethod method);
  vp::InstrumentMethod GetInstrumentMethod() const { return this->Instrument; }
  /// How far the whole instrument is searched, in mm (default 0: the engine's range). Not
  /// negative: throws ParameterError("InstrumentRangeMm").
  void SetInstrumentRangeMm(double rangeMm);
  double GetInstrumentRangeMm() const { return this->InstrumentRangeMm; }
  /// Whether the instrument's penetration depth and volume are computed with the surface
  /// distance (default true).
  void SetComputePenetration(bool compute);
  bool GetComputePenetration() const { return this->ComputePenetration; }
  /// The most vessel-wall queries the penetration's walk makes per class and frame (0: no limit;
  /// default vtkScalpelPenetration's): what bounds a breach's frame. Not negative: throws
  /// ParameterError("PenetrationQueryBudget").
  void SetPenetrationQueryBudget(long long queries);
  long long GetPenetrationQueryBudget() const { return this->PenetrationQueryBudget; }

  /// Whether every frame is also answered by the exact engine, for the accuracy check.
  void SetCompareWithExact(bool compare);
  bool GetCompareWithExact() const { return this->CompareWithExact; }

  /// Checked where they are used (vtkScalpelTrackingLogic::ValidateSettings).
  void SetDangerThresholds(const vp::DangerThresholds& thresholds);
  const vp::DangerThresholds& GetDangerThresholds() const { return this->Tracking.Thresholds; }
  /// Not negative: throws ParameterError("HysteresisMm").
  void SetHysteresisMm(double hysteresisMm);
  double GetHysteresisMm() const { return this->Tracking.HysteresisMm; }
  /// Not negative, 0: no budget. Throws ParameterError("FrameBudgetMs").
  void SetFrameBudgetMs(double budgetMs);
  double GetFrameBudgetMs() const { return this->Tracking.FrameBudgetMs; }
  /// The haptic contact force (vp::HapticSettings, off by default). Throws as HapticSettings::Validate.
  void SetHapticSettings(const vp::HapticSettings& haptic);
  const vp::HapticSettings& GetHapticSettings() const { return this->Tracking.Haptic; }
  /// The resection margin and its near band (vp::MarginSettings, 5 and 5 mm). Throws
  /// ParameterError("MarginMm") as MarginSettings::Validate.
  void SetMarginSettings(const vp::MarginSettings& margin);
  const vp::MarginSettings& GetMarginSettings() const { return this->Tracking.Margin; }
  /// The thresholds, the hysteresis, the frame budget, the haptic force and the margin together.
  const vp::TrackingSettings& GetTrackingSettings() const { return this->Tracking; }

  vtkMTimeType GetSceneMTime() const { return this->SceneTime.GetMTime(); }
  vtkMTimeType GetSettingsMTime() const { return this->SettingsTime.GetMTime(); }

protected:
  vtkVesselProximityParameters();
  ~vtkVesselProximityParameters() override;

private:
  vtkVesselProximityParameters(const vtkVesselProximityParameters&) = delete;
  void operator=(const vtkVesselProximityParameters&) = delete;
  void SceneModified();
  void SettingsModified();

  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Vessels;
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Tumours;
  vtkSmartPointer<vtkScalpelModel> Scalpel;
  vtkSmartPointer<vtkVesselDistanceEngine> DistanceEngine;
  bool ComputeSurfaceDistance = true;
  vp::InstrumentMethod Instrument = vp::InstrumentMethod::Automatic;
  double InstrumentRangeMm = 0.0;
  bool ComputePenetration = true;
  long long PenetrationQueryBudget = vtkScalpelPenetration::DefaultQueryBudget;
  bool CompareWithExact = false;
  vp::TrackingSettings Tracking;
  vtkTimeStamp SceneTime;
  vtkTimeStamp SettingsTime;
};

#endif
