#include "vpBenchmarkSupport.h"

#include "vpBuiltInPhantom.h"
#include "vpClock.h"
#include "vpQuantile.h"
#include "vtkZBufferVesselDistance.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace vp
{
using Json = BenchJson;

Json Timing(const std::vector<double>& ms)
{
  return { { "median_ms", Quantile(ms, 0.5) }, { "p95_ms", Quantile(ms, 0.95) }, { "queries", ms.size() } };
}

double TipsPerSecond(std::size_t tips, double ms)
{
  return 1000.0 * static_cast<double>(tips) / std::max(1e-9, ms);
}

Json BenchBatch(vtkVesselDistanceEngine* engine, const BenchPoints& tips, const std::vector<ProximityResult>* singles)
{
  std::vector<double> ms;
  std::vector<ProximityResult> batch;
  auto* zbuffer = vtkZBufferVesselDistance::SafeDownCast(engine);
  CallTimeSeries parts;
  for (int run = 0; run < 5; ++run)
  {
    const double start = NowMs();
    engine->ComputeProximityBatch(tips, nullptr, batch);
    ms.push_back(NowMs() - start);
    if (zbuffer)
    {
      parts.Add(zbuffer->GetLastCallTimes());
    }
  }
  Json out = Timing(ms);
  out["tips"] = tips.size();
  out["tips_per_second"] = TipsPerSecond(tips.size(), Quantile(ms, 0.5));
  if (zbuffer)
  {
    // Where a batch's time goes: the device's own work, the host's wait for it, and the host's
    // parts; the device's rate is what the kernel alone would give.
    out["parts"] = parts.Json();
    out["device_tips_per_second"] = TipsPerSecond(tips.size(), parts.DeviceMedianMs());
  }
  if (singles)
  {
    out["answers_differing_from_single_queries"] = CountDifferingAnswers(batch, *singles);
  }
  return out;
}

void CallTimeSeries::Add(const vtkZBufferVesselDistance::CallTimes& t)
{
  this->Total.push_back(t.TotalMs);
  this->Device.push_back(t.DeviceMs);
  this->Listing.push_back(t.DeviceListingMs);
  this->Visiting.push_back(t.DeviceVisitingMs);
  this->Reducing.push_back(t.DeviceReducingMs);
  this->Wait.push_back(t.SubmitWaitMs);
  this->Votes.push_back(t.VotesMs);
  this->Ceilings.push_back(t.CeilingsMs);
  this->Read.push_back(t.ReadMs);
  this->Order.push_back(t.OrderMs);
  this->HostListing.push_back(t.ListingMs);
  this->LastTilesListed = t.TilesListed;
  this->LastVotes = t.Votes;
  this->LastSubmissions = t.Submissions;
}

BenchJson CallTimeSeries::Json() const
{
  return { { "total", Timing(this->Total) }, { "device", Timing(this->Device) },
    { "device_listing", Timing(this->Listing) }, { "device_visiting", Timing(this->Visiting) },
    { "device_reducing", Timing(this->Reducing) }, { "submit_wait", Timing(this->Wait) },
    { "votes", Timing(this->Votes) }, { "ceilings", Timing(this->Ceilings) }, { "read", Timing(this->Read) },
    { "order", Timing(this->Order) }, { "host_listing", Timing(this->HostListing) },
    { "tiles_listed_in_last_call", this->LastTilesListed },
    { "votes_in_last_call", this->LastVotes }, { "submissions_in_last_call", this->LastSubmissions } };
}

double CallTimeSeries::DeviceMedianMs() const
{
  return Quantile(this->Device, 0.5);
}

int CountDifferingAnswers(const std::vector<ProximityResult>& a, const std::vector<ProximityResult>& b)
{
  int differ = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    for (std::size_t c = 0; c < a[i].Classes.size(); ++c)
    {
      const ClassProximity& x = a[i].Classes[c];
      const ClassProximity& y = b[i].Classes[c];
      differ += x.InRange != y.InRange || (x.InRange && (x.DistanceMm != y.DistanceMm || x.Inside != y.Inside)) ? 1 : 0;
    }
  }
  return differ;
}

void TimedQuery(vtkZBufferVesselDistance* zbuffer, const double* tip, const double* axis, ProximityResult& result,
  std::vector<double>& ms, std::vector<double>& deviceMs)
{
  const double start = NowMs();
  zbuffer->ComputeProximity(tip, axis, result);
  ms.push_back(NowMs() - start);
  deviceMs.push_back(zbuffer->GetLastQueryDeviceMs());
}

BenchTips MakeBenchTips(const std::vector<NamedMesh>& vessels, int queries, unsigned seed)
{
  // Tips: uniform in the vessels' joint bounding box grown by 10 mm (where a scalpel works).
  double bounds[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (const auto& v : vessels)
  {
    const double* b = v.Mesh->GetBounds();
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], b[2 * a] - 10.0);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], b[2 * a + 1] + 10.0);
    }
  }
  std::mt19937 random(seed);
  std::vector<std::array<double, 3>> tips(static_cast<std::size_t>(queries));
  for (auto& t : tips)
  {
    for (int a = 0; a < 3; ++a)
    {
      t[a] = std::uniform_real_distribution<double>(bounds[2 * a], bounds[2 * a + 1])(random);
    }
  }
  // A tracked tip: a random walk of 0.5 mm steps, reflected at the box.
  std::vector<std::array<double, 3>> track(static_cast<std::size_t>(queries));
  std::normal_distribution<double> normal;
  track[0] = tips[0];
  for (std::size_t i = 1; i < track.size(); ++i)
  {
    double step[3] = { normal(random), normal(random), normal(random) };
    const double n = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
    for (int a = 0; a < 3; ++a)
    {
      double x = track[i - 1][a] + 0.5 * step[a] / n;
      if (x < bounds[2 * a] || x > bounds[2 * a + 1])
      {
        x = track[i - 1][a] - 0.5 * step[a] / n;
      }
      track[i][a] = x;
    }
  }
  return { tips, track };
}

std::vector<NamedMesh> BuiltInVessels()
{
  std::vector<NamedMesh> vessels;
  for (const auto& v : MakeBuiltInVessels())
  {
    vessels.push_back({ v.first, "built-in", v.second, std::nullopt });
  }
  return vessels;
}
} // namespace vp
