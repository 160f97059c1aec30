#ifndef vpApproachPlanFile_h
#define vpApproachPlanFile_h

#include "vpApproachPlan.h"

#include <nlohmann/json.hpp>

#include <string>

namespace vp
{
/// A planned approach's poses as a pose file (plan.csv) that vp::ReadPoseFile reads back as the
/// very poses planned: declarations of its frame and units (LPS, mm, s), a header
/// `time,x,y,z,qw,qx,qy,qz` (x,y,z: the model's origin in the world; the quaternion turns the
/// model into the world), a row per pose, positions and quaternions to 17 significant digits.
std::string FormatApproachPosesCsv(const PlannedApproach& approach);

/// The plan as plan.json says it: {"target", "target_centre", "entry", "direction",
/// "target_surface_point", "end", "margin_mm", "step_mm", "time_step_s", "poses", "range_mm",
/// "classes": {"<class>": {"closest_mm", "step", "time_s", "point", "tool_point",
/// "penetration_depth_mm"}}, "clearance_mm", "clearance_class", "tip_target_signed_mm",
/// "search" (with a search: "deg", "step_deg", "directions", "missed" and "safest", the same
/// keys for the safest approach with its "angle_deg"), "step_ms": {"median", "p95", "max",
/// "count"}}. Points LPS mm; a class never within range has null numbers; the clearance is
/// the engine's range then.
nlohmann::ordered_json ApproachPlanJson(const ApproachPlan& plan);
} // namespace vp

#endif
