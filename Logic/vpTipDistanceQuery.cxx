#include "vpTipDistanceQuery.h"

#include "vpSceneRequest.h"
#include "vpInputError.h"
#include "vpPatientSpace.h"
#include "vpQuantile.h"
#include "vpSurfaceReport.h"
#include "vpClock.h"
#include "vtkExactVesselDistance.h"
#include "vtkTumourMarginDistance.h"
#include "vpClassName.h"

#include <algorithm>
#include <cmath>
#include <optional>

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
/// The tumours' exact distance, built once for every chunk; null without tumours.
vtkSmartPointer<vtkTumourMarginDistance> TumourDistanceOf(const std::vector<NamedMesh>& tumours)
{
  if (tumours.empty())
  {
    return nullptr;
  }
  auto distance = vtkSmartPointer<vtkTumourMarginDistance>::New();
  for (const NamedMesh& t : tumours)
  {
    distance->AddTumour(t.ClassName, t.Mesh);
  }
  distance->Build();
  return distance;
}

/// Each tip (the patient's) against every tumour: the tip alone, no instrument.
void MeasureTumours(vtkTumourMarginDistance* tumours, const std::vector<std::array<double, 3>>& tips, std::vector<TumourMargin>& out)
{
  static const std::array<double, 16> identity = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  out.resize(tips.size());
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    tumours->ComputeMargin(tips[i].data(), identity, out[i], i > 0 ? &out[i - 1] : nullptr);
  }
}
} // namespace

double TipDistanceAnswer::QueryMs() const
{
  return this->BatchMs / static_cast<double>(std::max<std::size_t>(1, this->Results.size()));
}

double TipDistanceTotals::QueryMs() const
{
  return this->BatchMs / static_cast<double>(std::max<std::size_t>(1, this->Tips));
}

TipDistanceTotals ComputeTipDistancesInChunks(const TipDistanceRequest& request, std::size_t chunkTips,
  const std::function<void(const TipDistanceAnswer& chunk, std::size_t firstTip)>& visit)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  CheckVesselClassNames(request.Vessels);
  std::optional<std::array<double, 3>> axis = request.Axis;
  if (axis)
  {
    const double n = std::sqrt((*axis)[0] * (*axis)[0] + (*axis)[1] * (*axis)[1] + (*axis)[2] * (*axis)[2]);
    if (!(n > 0))
    {
      throw ParameterError("Axis", "must not be the zero vector");
    }
    for (double& c : *axis)
    {
      c /= n;
    }
    if (request.Registration)
    {
      *axis = TransformDirection(request.Registration->TrackerToPatient, *axis);
    }
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
  vtkSmartPointer<vtkTumourMarginDistance> tumours = TumourDistanceOf(request.Tumours);

  TipDistanceTotals totals;
  totals.Compared = static_cast<bool>(reference);
  chunkTips = std::max<std::size_t>(1, chunkTips);
  for (std::size_t first = 0; first < request.TipsMm.size(); first += chunkTips)
  {
    const std::size_t n = std::min(chunkTips, request.TipsMm.size() - first);
    std::vector<std::array<double, 3>> tips(request.TipsMm.begin() + static_cast<std::ptrdiff_t>(first),
      request.TipsMm.begin() + static_cast<std::ptrdiff_t>(first + n));
    if (request.Registration)
    {
      for (auto& tip : tips)
      {
        tip = TransformPoint(request.Registration->TrackerToPatient, tip);
      }
    }
    const std::vector<std::array<double, 3>> axes(axis ? n : 0, axis ? *axis : std::array<double, 3>{});
    TipDistanceAnswer answer;
    const double start = NowMs();
    engine->ComputeProximityBatch(tips, axis ? &axes : nullptr, answer.Results);
    answer.BatchMs = NowMs() - start;
    if (reference)
    {
      reference->ComputeProximityBatch(tips, axis ? &axes : nullptr, answer.Exact);
      answer.WithinBound.resize(answer.Exact.size());
      for (std::size_t i = 0; i < answer.Exact.size(); ++i)
      {
        totals.Comparison.Add(answer.Results[i], answer.Exact[i], engine->GetRangeMm(), engine->GetErrorBoundMm(),
          &answer.WithinBound[i]);
      }
    }
    if (tumours)
    {
      MeasureTumours(tumours, tips, answer.Tumours);
    }
    totals.BatchMs += answer.BatchMs;
    totals.Tips += n;
    visit(answer, first);
  }
  return totals;
}

TipDistanceAnswer ComputeTipDistances(const TipDistanceRequest& request)
{
  TipDistanceAnswer whole;
  const TipDistanceTotals totals = ComputeTipDistancesInChunks(request, request.TipsMm.size(),
    [&](const TipDistanceAnswer& chunk, std::size_t) { whole = chunk; });
  whole.Comparison = totals.Comparison;
  return whole;
}

Json TipDistanceHeaderJson(const TipDistanceRequest& request, bool ras)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  Json out;
  out["method"] = engine->GetMethodName();
  out["device"] = engine->GetDeviceDescription();
  out["space"] = ras ? "RAS" : "LPS";
  out["range_mm"] = engine->GetRangeMm();
  out["error_bound_mm"] = engine->GetErrorBoundMm();
  out["surfaces"] = SurfacesJson(engine, request.Vessels);
  if (!request.Tumours.empty())
  {
    Json tumours = Json::array();
    for (const NamedMesh& t : request.Tumours)
    {
      tumours.push_back({ { "id", t.ClassName }, { "name", t.DisplayName.empty() ? TumourSpoken(t.ClassName) : t.DisplayName },
        { "file", t.FileName } });
    }
    out["tumours"] = tumours;
  }
  out["registration"] = request.Registration
    ? Json{ { "file", request.Registration->FileName }, { "kind", request.Registration->Kind } }
    : Json(nullptr);
  return out;
}

Json TipResultJson(const TipDistanceAnswer& answer, std::size_t i, bool ras)
{
  const bool compared = !answer.Exact.empty();
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
  if (!answer.Tumours.empty())
  {
    item["tumours"] = TipTumoursJson(answer, i, ras);
  }
  return item;
}

Json TipTumoursJson(const TipDistanceAnswer& answer, std::size_t i, bool ras)
{
  if (answer.Tumours.empty())
  {
    return nullptr;
  }
  Json tumours = Json::object();
  for (const TumourProximity& t : answer.Tumours[i].Tumours)
  {
    tumours[t.Id] = { { "signed_mm", t.SignedMm }, { "inside", t.SignedMm < 0.0 || t.InsideUncertain },
      { "point", PointJson(t.ClosestPoint, ras) } };
    if (t.InsideUncertain)
    {
      tumours[t.Id]["inside_uncertain"] = true;
    }
  }
  return tumours;
}

Json TipDistanceTrailerJson(const TipDistanceRequest& request, const TipDistanceTotals& totals, double loadMs)
{
  Json out = Json::object();
  if (totals.Compared)
  {
    out["comparison"] = { { "reference", "exact" }, { "max_abs_difference_mm", totals.Comparison.MaxAbsDifferenceMm },
      { "outside_bound", totals.Comparison.OutsideBound } };
  }
  // Each tip's share of its batch: the batches' time per tip, the same for every tip.
  out["timing_ms"] = { { "load", loadMs }, { "build", request.Engine->GetBuildTimeMs() }, { "query_median", totals.QueryMs() },
    { "query_p95", totals.QueryMs() }, { "batch", totals.BatchMs },
    { "tips_per_second", 1000.0 * static_cast<double>(totals.Tips) / std::max(1e-9, totals.BatchMs) } };
  return out;
}

std::pair<std::string, std::string> TipDistanceReportAround(const Json& header, const Json& trailer, bool anyResults)
{
  // As the whole document's dump(2): the header's members, "results" with each item at four
  // spaces, then the trailer's members.
  std::string before = header.dump(2);
  before.erase(before.size() - 2); // "\n}"
  before += anyResults ? ",\n  \"results\": [\n" : ",\n  \"results\": []";
  std::string after = anyResults ? "\n  ]" : "";
  for (auto it = trailer.begin(); it != trailer.end(); ++it)
  {
    std::string member = Json{ { it.key(), it.value() } }.dump(2);
    member = member.substr(2, member.size() - 4); // without the braces and their line breaks
    after += ",\n" + member;
  }
  return { before, after + "\n}" };
}

std::string IndentedItem(const Json& item)
{
  std::string text = "    ";
  for (const char c : item.dump(2))
  {
    text.push_back(c);
    if (c == '\n')
    {
      text += "    ";
    }
  }
  return text;
}

Json TipDistanceReportJson(const TipDistanceRequest& request, const TipDistanceAnswer& answer, bool ras, double loadMs)
{
  Json out = TipDistanceHeaderJson(request, ras);
  Json list = Json::array();
  for (std::size_t i = 0; i < answer.Results.size(); ++i)
  {
    list.push_back(TipResultJson(answer, i, ras));
  }
  out["results"] = list;
  TipDistanceTotals totals;
  totals.Compared = !answer.Exact.empty();
  totals.Comparison = answer.Comparison;
  totals.BatchMs = answer.BatchMs;
  totals.Tips = answer.Results.size();
  const Json trailer = TipDistanceTrailerJson(request, totals, loadMs);
  for (auto it = trailer.begin(); it != trailer.end(); ++it)
  {
    out[it.key()] = it.value();
  }
  return out;
}
} // namespace vp
