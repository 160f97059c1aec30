#include "vpTrackingOptions.h"

#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"

namespace vp
{
DangerThresholds ParseDangerThresholds(const Arguments& args)
{
  DangerThresholds thresholds;
  if (args.Has("--danger-mm"))
  {
    const auto d = ParsePoint(args.Get("--danger-mm"), "--danger-mm");
    thresholds = { d[0], d[1], d[2] };
  }
  thresholds.Validate("--danger-mm");
  return thresholds;
}

ScalpelTipDefinition ParseTipDefinition(const Arguments& args)
{
  ScalpelTipDefinition tip;
  tip.Source = "--tip";
  if (args.Has("--tip"))
  {
    tip.TipMm = ParsePoint(args.Get("--tip"), "--tip");
  }
  if (args.Has("--axis"))
  {
    tip.Axis = ParsePoint(args.Get("--axis"), "--axis");
  }
  return tip;
}

double ParseFrameBudgetMs(const Arguments& args)
{
  const double budgetMs = args.GetNumber("--frame-budget-ms", 16.7);
  if (budgetMs < 0.0) // GetNumber refuses what is not a finite number
  {
    throw InputError("--frame-budget-ms", "expected a time in ms, 0 or more (0: no budget), got '" + args.Get("--frame-budget-ms") + "'");
  }
  return budgetMs;
}

double ParseHysteresisMm(const Arguments& args)
{
  const double hysteresisMm = args.GetNumber("--hysteresis-mm", 0.3);
  if (hysteresisMm < 0.0)
  {
    throw InputError("--hysteresis-mm", "expected a distance in mm, 0 or more (0: none), got '" + args.Get("--hysteresis-mm") + "'");
  }
  return hysteresisMm;
}
vtkSmartPointer<vtkVesselProximityLogic> ConfigureTrackingLogic(const Arguments& args, const std::string& method)
{
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  vtkVesselProximityParameters* parameters = logic->GetParameters();
  parameters->SetDangerThresholds(ParseDangerThresholds(args));
  parameters->SetFrameBudgetMs(ParseFrameBudgetMs(args));
  parameters->SetHysteresisMm(ParseHysteresisMm(args));
  parameters->SetComputeSurfaceDistance(!args.Has("--no-surface"));
  parameters->SetCompareWithExact(method == "both");
  parameters->SetDistanceEngine(MakeDistanceEngine(method, args));
  return logic;
}
} // namespace vp
