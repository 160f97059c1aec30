#include "vpApproachPlanFile.h"

#include "vpInputError.h"
#include "vpQuantile.h"

#include <cmath>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

Json Point(const double* p)
{
  return Json::array({ p[0], p[1], p[2] });
}

Json Point(const std::array<double, 3>& p)
{
  return Point(p.data());
}

Json OrNull(bool known, double value)
{
  return known ? Json(value) : Json(nullptr);
}

Json ClassesJson(const PlannedApproach& approach)
{
  Json classes = Json::object();
  for (const ClassApproach& c : approach.Classes)
  {
    classes[c.ClassName] = { { "closest_mm", OrNull(c.InRange, c.ClosestMm) },
      { "step", c.InRange ? Json(c.Step) : Json(nullptr) }, { "time_s", OrNull(c.InRange, c.TimeS) },
      { "point", c.InRange ? Point(c.PointMm) : Json(nullptr) },
      { "tool_point", c.InRange ? Point(c.PointOnToolMm) : Json(nullptr) },
      { "penetration_depth_mm", c.PenetrationDepthMm } };
  }
  return classes;
}

/// The keys an approach has, the asked one's and the safest's alike.
void AddApproach(Json& out, const PlannedApproach& approach)
{
  out["entry"] = Point(approach.EntryMm);
  out["direction"] = Point(approach.Direction);
  out["target_surface_point"] = Point(approach.SurfacePointMm);
  out["end"] = Point(approach.EndMm);
  out["poses"] = approach.Poses.size();
  out["classes"] = ClassesJson(approach);
  out["clearance_mm"] = approach.ClearanceMm;
  out["clearance_class"] = approach.ClearanceClass.empty() ? Json(nullptr) : Json(approach.ClearanceClass);
  out["tip_target_signed_mm"] = approach.TipTargetSignedMm ? Json(*approach.TipTargetSignedMm) : Json(nullptr);
}

Json SearchJson(const ApproachPlan& plan)
{
  Json search = { { "deg", plan.SearchDeg }, { "step_deg", plan.SearchStepDeg }, { "directions", plan.DirectionsSearched },
    { "missed", plan.DirectionsMissing } };
  Json safest = { { "angle_deg", plan.Safest->AngleFromAskedDeg } };
  AddApproach(safest, *plan.Safest);
  search["safest"] = safest;
  search["safer_by_mm"] = plan.Safest->ClearanceMm - plan.Asked.ClearanceMm;
  return search;
}
} // namespace

std::string FormatApproachPosesCsv(const PlannedApproach& approach)
{
  std::string csv = "# pose-space: LPS\n# pose-units: mm\n# time-units: s\ntime,x,y,z,qw,qx,qy,qz\n";
  for (const std::array<double, 8>& row : approach.PoseValues)
  {
    csv += FixedText(row[0], "%.10g");
    for (int k = 1; k < 8; ++k)
    {
      csv += "," + FixedText(row[k], "%.17g");
    }
    csv += "\n";
  }
  return csv;
}

nlohmann::ordered_json ApproachPlanJson(const ApproachPlan& plan)
{
  Json out = { { "target", plan.TargetName }, { "target_centre", Point(plan.TargetCentreMm) } };
  AddApproach(out, plan.Asked);
  out["margin_mm"] = plan.MarginMm;
  out["step_mm"] = plan.StepMm;
  out["time_step_s"] = plan.TimeStepS;
  out["range_mm"] = plan.RangeMm;
  if (plan.Safest)
  {
    out["search"] = SearchJson(plan);
  }
  out["step_ms"] = { { "median", Quantile(plan.StepMs, 0.5) }, { "p95", Quantile(plan.StepMs, 0.95) },
    { "max", Quantile(plan.StepMs, 1.0) }, { "count", plan.StepMs.size() } };
  return out;
}
} // namespace vp
