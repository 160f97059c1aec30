#include "vtkVesselProximityParameters.h"

#include "vpInputError.h"
#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cmath>
#include <stdexcept>

vtkStandardNewMacro(vtkVesselProximityParameters);

namespace
{
/// Assigns, and says whether the value changed: a setter fires its event only then.
template <typename T>
bool Assign(T& field, const T& value)
{
  if (field == value)
  {
    return false;
  }
  field = value;
  return true;
}

/// Adds name's surface, or replaces it in place (the order kept), and says whether it changed.
bool AssignNamed(std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>>& surfaces, const std::string& name,
  vtkPolyData* surface)
{
  for (auto& named : surfaces)
  {
    if (named.first == name)
    {
      return Assign(named.second, vtkSmartPointer<vtkPolyData>(surface));
    }
  }
  surfaces.emplace_back(name, surface);
  return true;
}

/// A length or a time that may be 0 but not negative (nor NaN, nor infinite).
double NotNegative(double value, const char* parameter, const char* problem)
{
  if (!(value >= 0.0) || !std::isfinite(value))
  {
    throw vp::ParameterError(parameter, problem);
  }
  return value;
}
} // namespace

vtkVesselProximityParameters::vtkVesselProximityParameters()
  : DistanceEngine(vtkSmartPointer<vtkExactVesselDistance>::New())
{
  this->SceneTime.Modified();
  this->SettingsTime.Modified();
}

vtkVesselProximityParameters::~vtkVesselProximityParameters() = default;

void vtkVesselProximityParameters::SceneModified()
{
  this->SceneTime.Modified();
  this->Modified();
}

void vtkVesselProximityParameters::SettingsModified()
{
  this->SettingsTime.Modified();
  this->Modified();
}

void vtkVesselProximityParameters::SetVessel(const std::string& className, vtkPolyData* surface)
{
  if (AssignNamed(this->Vessels, className, surface))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::RemoveAllVessels()
{
  if (!this->Vessels.empty())
  {
    this->Vessels.clear();
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetTumour(const std::string& id, vtkPolyData* surface)
{
  if (AssignNamed(this->Tumours, id, surface))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::RemoveAllTumours()
{
  if (!this->Tumours.empty())
  {
    this->Tumours.clear();
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetMarginSettings(const vp::MarginSettings& margin)
{
  margin.Validate("MarginMm");
  if (this->Tracking.Margin.MarginMm != margin.MarginMm || this->Tracking.Margin.NearBandMm != margin.NearBandMm)
  {
    this->Tracking.Margin = margin;
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetScalpel(vtkScalpelModel* scalpel)
{
  if (Assign(this->Scalpel, vtkSmartPointer<vtkScalpelModel>(scalpel)))
  {
    this->SceneModified(); // the whole-instrument trees are built from its model
  }
}

void vtkVesselProximityParameters::SetDistanceEngine(vtkVesselDistanceEngine* engine)
{
  if (!engine)
  {
    throw std::invalid_argument("vtkVesselProximityParameters: the distance engine cannot be null");
  }
  if (Assign(this->DistanceEngine, vtkSmartPointer<vtkVesselDistanceEngine>(engine)))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetComputeSurfaceDistance(bool compute)
{
  if (Assign(this->ComputeSurfaceDistance, compute))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetInstrumentMethod(vp::InstrumentMethod method)
{
  if (Assign(this->Instrument, method))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetInstrumentRangeMm(double rangeMm)
{
  if (Assign(this->InstrumentRangeMm, NotNegative(rangeMm, "InstrumentRangeMm", "must be a distance in mm, 0 or more (0: the engine's range)")))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetComputePenetration(bool compute)
{
  if (Assign(this->ComputePenetration, compute))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetPenetrationQueryBudget(long long queries)
{
  if (queries < 0)
  {
    throw vp::ParameterError("PenetrationQueryBudget", "must be 0 (no limit) or a positive count, got " + std::to_string(queries));
  }
  if (Assign(this->PenetrationQueryBudget, queries))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetCompareWithExact(bool compare)
{
  if (Assign(this->CompareWithExact, compare))
  {
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetDangerThresholds(const vp::DangerThresholds& t)
{
  const vp::DangerThresholds& d = this->Tracking.Thresholds;
  if (t.CautionMm != d.CautionMm || t.WarningMm != d.WarningMm || t.DangerMm != d.DangerMm)
  {
    this->Tracking.Thresholds = t;
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetHysteresisMm(double hysteresisMm)
{
  if (Assign(this->Tracking.HysteresisMm, NotNegative(hysteresisMm, "HysteresisMm", "must be a distance in mm, 0 or more (0: none)")))
  {
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetFrameBudgetMs(double budgetMs)
{
  if (Assign(this->Tracking.FrameBudgetMs, NotNegative(budgetMs, "FrameBudgetMs", "must be a time in ms, 0 or more (0: no budget)")))
  {
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetHapticSettings(const vp::HapticSettings& haptic)
{
  haptic.Validate();
  const vp::HapticSettings& now = this->Tracking.Haptic;
  if (now.StiffnessNPerMm != haptic.StiffnessNPerMm || now.DampingNsPerMm != haptic.DampingNsPerMm ||
    now.RateTimeConstantS != haptic.RateTimeConstantS || now.MaxRateMmPerS != haptic.MaxRateMmPerS)
  {
    this->Tracking.Haptic = haptic;
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Vessels:";
  for (const auto& vessel : this->Vessels)
  {
    os << " " << vessel.first;
  }
  os << "\n" << indent << "Tumours:";
  for (const auto& tumour : this->Tumours)
  {
    os << " " << tumour.first;
  }
  os << "\n" << indent << "Scalpel: " << (this->Scalpel ? "set" : "(none)") << "\n";
  os << indent << "DistanceEngine: " << this->DistanceEngine->GetMethodName() << "\n";
  os << indent << "ComputeSurfaceDistance: " << this->ComputeSurfaceDistance << "\n";
  os << indent << "InstrumentMethod: " << vp::InstrumentMethodName(this->Instrument) << "\n";
  os << indent << "InstrumentRangeMm: " << this->InstrumentRangeMm << (this->InstrumentRangeMm > 0 ? "" : " (the engine's)") << "\n";
  os << indent << "ComputePenetration: " << this->ComputePenetration << "\n";
  os << indent << "PenetrationQueryBudget: " << this->PenetrationQueryBudget << (this->PenetrationQueryBudget > 0 ? "" : " (no limit)") << "\n";
  os << indent << "CompareWithExact: " << this->CompareWithExact << "\n";
  os << indent << "DangerThresholdsMm: " << this->Tracking.Thresholds.CautionMm << " " << this->Tracking.Thresholds.WarningMm << " "
     << this->Tracking.Thresholds.DangerMm << "\n";
  os << indent << "HysteresisMm: " << this->Tracking.HysteresisMm << "\n";
  os << indent << "HapticStiffnessNPerMm: " << this->Tracking.Haptic.StiffnessNPerMm << "\n";
  os << indent << "HapticDampingNsPerMm: " << this->Tracking.Haptic.DampingNsPerMm << "\n";
  os << indent << "FrameBudgetMs: " << this->Tracking.FrameBudgetMs << "\n";
  os << indent << "MarginMm: " << this->Tracking.Margin.MarginMm << " (near band " << this->Tracking.Margin.NearBandMm << ")\n";
}
