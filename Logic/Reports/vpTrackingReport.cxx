#include "vpTrackingReport.h"

#include "vpDangerLevels.h"
#include "vpSurfaceReport.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselDistanceEngine.h"

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

Json MinimumJson(const ClassMinimum& m)
{
  if (!m.Seen)
  {
    return nullptr;
  }
  return { { "distance_mm", m.DistanceMm }, { "error_bound_mm", m.ErrorBoundMm }, { "inside", m.Inside }, { "frame", m.Frame },
    { "time", m.TimeS }, { "point", { m.PointMm[0], m.PointMm[1], m.PointMm[2] } } };
}

Json TumourJson(const TrackingSummary& s, const MarginSettings& settings)
{
  Json tumours = Json::array();
  for (const TumourMarginSummary& t : s.GetTumours())
  {
    Json levels = Json::object();
    for (int l = 0; l < NumberOfMarginLevels; ++l)
    {
      levels[MarginLevelName(static_cast<MarginLevel>(l))] = { { "time_s", t.TimeInLevelS[l] }, { "frames", t.FramesInLevel[l] } };
    }
    tumours.push_back({ { "id", t.Id }, { "margin_min_mm", t.MarginMinMm }, { "frame", t.Frame }, { "time", t.TimeS },
      { "point", { t.PointMm[0], t.PointMm[1], t.PointMm[2] } },
      { "surface_min_mm", t.SurfaceSeen ? Json(t.SurfaceMinMm) : Json(nullptr) }, { "time_in_level", levels } });
  }
  Json changes = Json::array();
  for (const MarginLevelChange& c : s.GetMarginChanges())
  {
    changes.push_back({ { "frame", c.Frame }, { "time", c.TimeS }, { "from", MarginLevelName(c.From) },
      { "to", MarginLevelName(c.To) }, { "tumour", c.TumourId }, { "tumour_mm", c.SignedMm } });
  }
  return { { "margin_mm", settings.MarginMm }, { "near_band_mm", settings.NearBandMm },
    { "worst_level", MarginLevelName(s.GetWorstMarginLevel()) }, { "tumours", tumours }, { "level_changes", changes } };
}
} // namespace

Json TrackingSummaryJson(const TrackingSummary& s, vtkScalpelTrackingLogic* logic, bool surface, const std::vector<NamedMesh>& meshes,
  const std::string& posesFile, const ExactComparison* comparison)
{
  vtkVesselDistanceEngine* engine = logic->GetDistanceEngine();
  Json out;
  out["poses"] = posesFile;
  out["frames"] = s.GetNumberOfFrames();
  out["duration_s"] = s.GetDurationS();
  out["method"] = engine->GetMethodName();
  out["device"] = engine->GetDeviceDescription();
  out["range_mm"] = engine->GetRangeMm();
  out["error_bound_mm"] = engine->GetErrorBoundMm();
  out["surfaces"] = SurfacesJson(engine, meshes);
  vtkScalpelModel* scalpel = logic->GetScalpel();
  out["scalpel"] = { { "tip_mm", { scalpel->GetTipMm()[0], scalpel->GetTipMm()[1], scalpel->GetTipMm()[2] } },
    { "axis", { scalpel->GetAxis()[0], scalpel->GetAxis()[1], scalpel->GetAxis()[2] } },
    { "tip_source", scalpel->GetTipSource() } };
  const DangerThresholds& t = logic->GetDangerThresholds();
  out["danger_thresholds_mm"] = { { "caution", t.CautionMm }, { "warning", t.WarningMm }, { "danger", t.DangerMm } };
  out["hysteresis_mm"] = logic->GetHysteresisMm();
  Json classes = Json::object();
  for (std::size_t c = 0; c < s.GetClassNames().size(); ++c)
  {
    Json entry;
    entry["tip_minimum"] = MinimumJson(s.GetTipMinimum()[c]);
    entry["frames_inside_uncertain"] = s.GetFramesInsideUncertain()[c];
    entry["frames_in_breach"] = s.GetFramesInBreach()[c];
    if (surface)
    {
      entry["surface_minimum"] = MinimumJson(s.GetSurfaceMinimum()[c]);
      if (c < s.GetPenetrationMaximum().size())
      {
        const ClassPenetration& p = s.GetPenetrationMaximum()[c];
        entry["penetration_maximum"] = !p.Known ? Json(nullptr)
                                                : Json{ { "depth_mm", p.DepthMm }, { "depth_bound_mm", p.DepthBoundMm },
                                                    { "depth_frame", p.DepthFrame }, { "volume_mm3", p.VolumeMm3 },
                                                    { "volume_bound_mm3", p.VolumeBoundMm3 }, { "volume_frame", p.VolumeFrame },
                                                    { "frames_inside", p.FramesInside } };
      }
    }
    classes[s.GetClassNames()[c]] = entry;
  }
  out["classes"] = classes;
  Json levels = Json::object();
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    levels[DangerLevelName(static_cast<DangerLevel>(l))] = { { "time_s", s.GetTimeInLevelS()[l] },
      { "frames", s.GetFramesInLevel()[l] } };
  }
  out["time_in_level"] = levels;
  out["worst_level"] = DangerLevelName(s.GetWorstLevel());
  out["worst_tip_level"] = DangerLevelName(s.GetWorstTipLevel());
  out["worst_instrument_level"] = s.GetInstrumentMeasured() ? Json(DangerLevelName(s.GetWorstInstrumentLevel())) : Json(nullptr);
  if (s.HasHaptic())
  {
    const HapticSettings& h = logic->GetHapticSettings();
    out["haptic"] = { { "stiffness_n_per_mm", h.StiffnessNPerMm }, { "damping_ns_per_mm", h.DampingNsPerMm },
      { "max_force_n", s.GetMaxHapticForceN() }, { "frames_with_force", s.GetFramesWithHapticForce() } };
  }
  if (!s.GetTumours().empty())
  {
    out["tumour"] = TumourJson(s, logic->GetMarginSettings());
  }
  Json events = Json::array();
  for (const DangerLevelChange& e : s.GetChanges())
  {
    events.push_back({ { "frame", e.Frame }, { "time", e.TimeS }, { "from", DangerLevelName(e.From) },
      { "to", DangerLevelName(e.To) }, { "class", e.ClassName.empty() ? Json(nullptr) : Json(e.ClassName) },
      { "cause", e.ClassName.empty() ? Json(nullptr) : Json(DangerCauseName(e.Cause)) },
      { "distance_mm", e.ClassName.empty() ? Json(nullptr) : Json(e.DistanceMm) } });
  }
  out["level_changes"] = events;
  out["frame_ms"] = { { "median", s.GetFrameMsQuantile(0.5) }, { "p95", s.GetFrameMsQuantile(0.95) },
    { "max", s.GetFrameMsQuantile(1.0) }, { "budget", logic->GetFrameBudgetMs() } };
  out["frames_over_budget"] = s.GetFramesOverBudget();
  out["timing_ms"] = { { "frame_median", s.GetFrameMsQuantile(0.5) }, { "frame_p95", s.GetFrameMsQuantile(0.95) },
    { "frame_max", s.GetFrameMsQuantile(1.0) } };
  if (comparison)
  {
    out["comparison"] = { { "reference", "exact" }, { "max_abs_difference_mm", comparison->MaxAbsDifferenceMm },
      { "outside_bound", comparison->OutsideBound } };
  }
  return out;
}

Json PoseReadingJson(const SettledReading& reading)
{
  Json out;
  out["space"] = PoseSpaceName(reading.Space);
  out["units"] = reading.MillimetresPerUnit == 1000.0 ? "m" : "mm";
  out["time_units"] = reading.SecondsPerUnit == 0.001 ? "ms" : "s";
  out["registration"] = reading.Registration
    ? Json{ { "file", reading.Registration->FileName }, { "kind", reading.Registration->Kind } }
    : Json(nullptr);
  if (reading.QuaternionOrderAssumed)
  {
    out["columns"] = "time,x,y,z,qw,qx,qy,qz (no header: assumed)";
  }
  return out;
}
} // namespace vp
