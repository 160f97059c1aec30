#include "vpTipDistanceQuery.h"

#include "vpInputError.h"
#include "vpPatientSpace.h"
#include "vpQuantile.h"
#include "vpSurfaceReport.h"
#include "vpClock.h"
#include "vtkExactVesselDistance.h"

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

Json PointJson(const double p[3], bool ras)
{
  const std::array<double, 3> q = ConvertSpace({ p[0], p[1], p[2] }, ras);
  return Json::array({ q[0], q[1], q[2] });
}

Json ClassJson(const ClassProximity& c, const ClassProximity* exact, bool within, bool ras)
{
  Json entry;
  entry["distance_mm"] = c.InRange ? Json(c.DistanceMm) : Json(nullptr);
  entry["point"] = c.InRange ? PointJson(c.ClosestPoint, ras) : Json(nullptr);
  entry["inside"] = c.Inside ? Json(*c.Inside) : Json(nullptr);
  if (c.InsideUncertain)
  {
    entry["inside_uncertain"] = true; // the votes on a defective surface disagreed
  }
  entry["in_range"] = c.InRange;
  entry["directional_mm"] = c.DirectionalMm ? Json(*c.DirectionalMm) : Json(nullptr);
  if (exact)
  {
    entry["exact_mm"] = exact->InRange ? Json(exact->DistanceMm) : Json(nullptr);
    entry["difference_mm"] = exact->InRange && c.InRange ? Json(c.DistanceMm - exact->DistanceMm) : Json(nullptr);
    entry["within_bound"] = within;
  }
  return entry;
}
} // namespace

double TipDistanceAnswer::QueryMs() const
{
  return this->BatchMs / static_cast<double>(std::max<std::size_t>(1, this->Results.size()));
}

TipDistanceAnswer ComputeTipDistances(const TipDistanceRequest& request)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  std::vector<std::array<double, 3>> axes;
  if (request.Axis)
  {
    std::array<double, 3> axis = *request.Axis;
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 0))
    {
      throw ParameterError("Axis", "must not be the zero vector");
    }
    for (double& c : axis)
    {
      c /= n;
    }
    axes.assign(request.TipsMm.size(), axis);
  }
  vtkSmartPointer<vtkExactVesselDistance> reference;
  if (request.CompareWithExact)
  {
    reference = vtkSmartPointer<vtkExactVesselDistance>::New();
    reference->SetRangeMm(engine->GetRangeMm());
  }
  for (const NamedMesh& m : request.Vessels)
  {
    engine->AddVessel(m.ClassName, m.Mesh);
    if (reference)
    {
      reference->AddVessel(m.ClassName, m.Mesh);
    }
  }
  engine->Build();
  if (reference)
  {
    reference->Build();
  }

  TipDistanceAnswer answer;
  const double start = NowMs();
  engine->ComputeProximityBatch(request.TipsMm, request.Axis ? &axes : nullptr, answer.Results);
  answer.BatchMs = NowMs() - start;
  if (reference)
  {
    reference->ComputeProximityBatch(request.TipsMm, request.Axis ? &axes : nullptr, answer.Exact);
    answer.WithinBound.resize(answer.Exact.size());
    for (std::size_t i = 0; i < answer.Exact.size(); ++i)
    {
      answer.Comparison.Add(answer.Results[i], answer.Exact[i], engine->GetRangeMm(), engine->GetErrorBoundMm(),
        &answer.WithinBound[i]);
    }
  }
  return answer;
}

Json TipDistanceReportJson(const TipDistanceRequest& request, const TipDistanceAnswer& answer, bool ras, double loadMs)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  const bool compared = !answer.Exact.empty();
  Json out;
  out["method"] = engine->GetMethodName();
  out["device"] = engine->GetDeviceDescription();
  out["space"] = ras ? "RAS" : "LPS";
  out["range_mm"] = engine->GetRangeMm();
  out["error_bound_mm"] = engine->GetErrorBoundMm();
  out["surfaces"] = SurfacesJson(engine, request.Vessels);
  Json list = Json::array();
  for (std::size_t i = 0; i < answer.Results.size(); ++i)
  {
    const ProximityResult& r = answer.Results[i];
    Json item;
    item["tip"] = PointJson(r.Tip, ras);
    item["error_bound_mm"] = r.ErrorBoundMm;
    const int nearest = r.NearestIndex();
    item["nearest"] = nullptr;
    if (nearest >= 0)
    {
      const ClassProximity& n = r.Classes[nearest];
      item["nearest"] = { { "class", n.ClassName }, { "distance_mm", n.DistanceMm }, { "point", PointJson(n.ClosestPoint, ras) } };
    }
    Json classes = Json::object();
    for (std::size_t k = 0; k < r.Classes.size(); ++k)
    {
      classes[r.Classes[k].ClassName] = ClassJson(r.Classes[k], compared ? &answer.Exact[i].Classes[k] : nullptr,
        compared && answer.WithinBound[i][k] != 0, ras);
    }
    item["classes"] = classes;
    list.push_back(item);
  }
  out["results"] = list;
  if (compared)
  {
    out["comparison"] = { { "reference", "exact" }, { "max_abs_difference_mm", answer.Comparison.MaxAbsDifferenceMm },
      { "outside_bound", answer.Comparison.OutsideBound } };
  }
  const std::vector<double> queryMs(answer.Results.size(), answer.QueryMs());
  out["timing_ms"] = { { "load", loadMs }, { "build", engine->GetBuildTimeMs() }, { "query_median", Quantile(queryMs, 0.5) },
    { "query_p95", Quantile(queryMs, 0.95) }, { "batch", answer.BatchMs },
    { "tips_per_second", 1000.0 * static_cast<double>(answer.Results.size()) / std::max(1e-9, answer.BatchMs) } };
  return out;
}
} // namespace vp
