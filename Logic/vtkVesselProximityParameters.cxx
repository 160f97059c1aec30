#include "vtkVesselProximityParameters.h"

#include "vpInputError.h"
#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cmath>
#include <stdexcept>

vtkStandardNewMacro(vtkVesselProximityParameters);

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
  for (auto& vessel : this->Vessels)
  {
    if (vessel.first == className)
    {
      if (vessel.second != surface)
      {
        vessel.second = surface;
        this->SceneModified();
      }
      return;
    }
  }
  this->Vessels.emplace_back(className, surface);
  this->SceneModified();
}

void vtkVesselProximityParameters::RemoveAllVessels()
{
  if (!this->Vessels.empty())
  {
    this->Vessels.clear();
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetScalpel(vtkScalpelModel* scalpel)
{
  if (scalpel != this->Scalpel)
  {
    this->Scalpel = scalpel;
    this->SceneModified(); // the whole-instrument trees are built from its model
  }
}

void vtkVesselProximityParameters::SetDistanceEngine(vtkVesselDistanceEngine* engine)
{
  if (!engine)
  {
    throw std::invalid_argument("vtkVesselProximityParameters: the distance engine cannot be null");
  }
  if (engine != this->DistanceEngine)
  {
    this->DistanceEngine = engine;
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetComputeSurfaceDistance(bool compute)
{
  if (compute != this->ComputeSurfaceDistance)
  {
    this->ComputeSurfaceDistance = compute;
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetCompareWithExact(bool compare)
{
  if (compare != this->CompareWithExact)
  {
    this->CompareWithExact = compare;
    this->SceneModified();
  }
}

void vtkVesselProximityParameters::SetDangerThresholds(const vp::DangerThresholds& t)
{
  const vp::DangerThresholds& d = this->DangerThresholds;
  if (t.CautionMm != d.CautionMm || t.WarningMm != d.WarningMm || t.DangerMm != d.DangerMm)
  {
    this->DangerThresholds = t;
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetHysteresisMm(double hysteresisMm)
{
  if (!(hysteresisMm >= 0.0) || !std::isfinite(hysteresisMm))
  {
    throw vp::ParameterError("HysteresisMm", "must be a distance in mm, 0 or more (0: none)");
  }
  if (hysteresisMm != this->HysteresisMm)
  {
    this->HysteresisMm = hysteresisMm;
    this->SettingsModified();
  }
}

void vtkVesselProximityParameters::SetFrameBudgetMs(double budgetMs)
{
  if (!(budgetMs >= 0.0) || !std::isfinite(budgetMs))
  {
    throw vp::ParameterError("FrameBudgetMs", "must be a time in ms, 0 or more (0: no budget)");
  }
  if (budgetMs != this->FrameBudgetMs)
  {
    this->FrameBudgetMs = budgetMs;
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
  os << "\n" << indent << "Scalpel: " << (this->Scalpel ? "set" : "(none)") << "\n";
  os << indent << "DistanceEngine: " << this->DistanceEngine->GetMethodName() << "\n";
  os << indent << "ComputeSurfaceDistance: " << this->ComputeSurfaceDistance << "\n";
  os << indent << "CompareWithExact: " << this->CompareWithExact << "\n";
  os << indent << "DangerThresholdsMm: " << this->DangerThresholds.CautionMm << " " << this->DangerThresholds.WarningMm << " "
     << this->DangerThresholds.DangerMm << "\n";
  os << indent << "HysteresisMm: " << this->HysteresisMm << "\n";
  os << indent << "FrameBudgetMs: " << this->FrameBudgetMs << "\n";
}
