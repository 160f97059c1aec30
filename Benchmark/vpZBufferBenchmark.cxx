#include "vpZBufferBenchmark.h"

#include "vpDistanceEngineFactory.h"
#include "vpClock.h"
#include "vpExactComparison.h"
#include "vpQuantile.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace vp
{
namespace
{
using Json = BenchJson;

/// The references beside the z-buffer: the exact engine and brute force, same range, same classes.
struct References
{
  vtkSmartPointer<vtkExactVesselDistance> Exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  vtkSmartPointer<vtkBruteForceVesselDistance> Brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  std::size_t Triangles = 0;
};

References BuildAll(vtkZBufferVesselDistance* zbuffer, const std::vector<NamedMesh>& refined)
{
  zbuffer->RemoveAllVessels();
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::ExactIntervals);
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::FixedAroundVessels);
  References r;
  r.Exact->SetRangeMm(zbuffer->GetRangeMm());
  r.Brute->SetRangeMm(zbuffer->GetRangeMm());
  for (const NamedMesh& vessel : refined)
  {
    zbuffer->AddVessel(vessel.ClassName, vessel.Mesh);
    r.Exact->AddVessel(vessel.ClassName, vessel.Mesh);
    r.Brute->AddVessel(vessel.ClassName, vessel.Mesh);
    r.Triangles += static_cast<std::size_t>(vessel.Mesh->GetNumberOfPolys());
  }
  zbuffer->Build();
  r.Exact->Build();
  r.Brute->Build();
  return r;
}

/// Single queries on cached layers: the z-buffer (without and with an axis, host and device
/// time), the exact engine and brute force, the z-buffer checked against exact.
struct QueryTimes
{
  std::vector<double> Cached, CachedDevice, Axis, AxisDevice, Exact, Brute;
  ExactComparison Check;
  std::vector<ProximityResult> Singles;
};

QueryTimes TimeQueries(vtkZBufferVesselDistance* zbuffer, const References& refs, const BenchPoints& tips, int bruteQueries)
{
  QueryTimes t;
  ProximityResult z, e;
  for (const auto& tip : tips)
  {
    TimedQuery(zbuffer, tip.data(), nullptr, z, t.Cached, t.CachedDevice);
    t.Singles.push_back(z);
    const double start = NowMs();
    refs.Exact->ComputeProximity(tip.data(), nullptr, e);
    t.Exact.push_back(NowMs() - start);
    t.Check.Add(z, e, zbuffer->GetRangeMm(), zbuffer->GetErrorBoundMm());
  }
  for (int i = 0; i < bruteQueries; ++i)
  {
    const double start = NowMs();
    refs.Brute->ComputeProximity(tips[i].data(), nullptr, e);
    t.Brute.push_back(NowMs() - start);
  }
  // With an axis, as tracking asks: the directional distance walks the cells along it.
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    const double axis[3] = { std::cos(0.37 * i), std::sin(0.37 * i), 0.3 };
    TimedQuery(zbuffer, tips[i].data(), axis, z, t.Axis, t.AxisDevice);
  }
  return t;
}

/// On a GPU, the pass the device did not choose, over the same tips: single tips per tile (a
/// GPU's choice is per pixel), the batch per pixel (its choice is per tile). Empty on lavapipe.
Json OtherPass(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips, const std::vector<ProximityResult>& singles)
{
  Json other;
  if (zbuffer->GetDeviceDescription().find("llvmpipe") != std::string::npos)
  {
    return other;
  }
  std::vector<double> tileMs, tileDeviceMs;
  ProximityResult z;
  zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassPerTile);
  for (const auto& tip : tips)
  {
    TimedQuery(zbuffer, tip.data(), nullptr, z, tileMs, tileDeviceMs);
  }
  other["cached_per_tile"] = Timing(tileMs);
  other["cached_per_tile_device"] = Timing(tileDeviceMs);
  zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassPerPixel);
  other["batched_per_pixel"] = BenchBatch(zbuffer, tips, &singles);
  zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassByDevice);
  return other;
}

/// The query's ceilings off and on (SetQueryCeilings), taking turns of 20 queries on the same
/// engine so that both see the same clock: the random tips, and the tracked walk (where the
/// answer before sets the ceiling). Host and device time, the share of the range's tiles
/// dispatched, the batch off and on, and the answers that differ (none may).
Json Ceilings(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips, const BenchPoints& track)
{
  constexpr std::size_t Turn = 20;
  Json out;
  int differ = 0;
  for (const auto& [name, points] : { std::make_pair("random", &tips), std::make_pair("tracked", &track) })
  {
    std::vector<double> ms[2], deviceMs[2], share;
    std::vector<ProximityResult> answers[2];
    for (std::size_t first = 0; first < points->size(); first += Turn)
    {
      for (int on = 0; on < 2; ++on)
      {
        zbuffer->SetQueryCeilings(on == 1);
        for (std::size_t i = first; i < std::min(points->size(), first + Turn); ++i)
        {
          ProximityResult r;
          TimedQuery(zbuffer, (*points)[i].data(), nullptr, r, ms[on], deviceMs[on]);
          answers[on].push_back(r);
          if (on == 1)
          {
            share.push_back(static_cast<double>(zbuffer->GetLastQueryTiles()) /
              static_cast<double>(std::max<std::size_t>(1, zbuffer->GetLastQueryTilesInRange())));
          }
        }
      }
    }
    differ += CountDifferingAnswers(answers[0], answers[1]);
    Json entry;
    entry["off"] = Timing(ms[0]);
    entry["on"] = Timing(ms[1]);
    entry["off_device"] = Timing(deviceMs[0]);
    entry["on_device"] = Timing(deviceMs[1]);
    entry["tiles_share_median"] = Quantile(share, 0.5);
    entry["tiles_share_p95"] = Quantile(share, 0.95);
    out[name] = entry;
  }
  zbuffer->SetQueryCeilings(false);
  out["batched_off"] = BenchBatch(zbuffer, tips, nullptr);
  zbuffer->SetQueryCeilings(true);
  out["batched_on"] = BenchBatch(zbuffer, tips, nullptr);
  out["build_ms"] = zbuffer->GetCeilingBuildTimeMs();
  out["answers_differing"] = differ;
  return out;
}

/// One side of a batch measured in turns: its times, where they went, and its answers.
struct BatchSide
{
  std::vector<double> Ms;
  CallTimeSeries Parts;
  std::vector<ProximityResult> Answers;
};

/// The batch of all tips under each of `sides` settings (setSide(k) sets side k), five rounds,
/// the sides taking turns within each round so that all see the device alike (a GPU's clock
/// follows its load).
std::vector<BatchSide> BatchesInTurn(
  vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips, int sides, const std::function<void(int)>& setSide)
{
  std::vector<BatchSide> out(static_cast<std::size_t>(sides));
  for (int run = 0; run < 5; ++run)
  {
    for (int k = 0; k < sides; ++k)
    {
      BatchSide& side = out[static_cast<std::size_t>(k)];
      setSide(k);
      const double start = NowMs();
      zbuffer->ComputeProximityBatch(tips, nullptr, side.Answers);
      side.Ms.push_back(NowMs() - start);
      side.Parts.Add(zbuffer->GetLastCallTimes());
    }
  }
  return out;
}

/// The batch's tiles listed before they are visited, or visited straight from the order table
/// (SetTileListing), taking turns on the same engine: the batch of all tips five times each way,
/// single tips in turns of 20 (listed by the host, the default, and by the device's workgroups),
/// the tiles one submission lists and dispatches per tip, and the answers that differ (none may).
Json TileListing(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  using Z = vtkZBufferVesselDistance;
  constexpr std::size_t Turn = 20;
  constexpr int Listings[3] = { Z::TileListingOff, Z::TileListingOn, Z::TileListingOn };
  constexpr int Passes[3] = { Z::ListingPassByDevice, Z::ListingPassByDevice, Z::ListingPassPerWorkgroup };
  auto set = [&](int k) {
    zbuffer->SetTileListing(Listings[k]);
    zbuffer->SetListingPass(Passes[k]);
  };
  std::vector<double> ms[3], deviceMs[3];
  std::vector<ProximityResult> single[3];
  const std::vector<BatchSide> batch = BatchesInTurn(zbuffer, tips, 2, set);
  for (std::size_t first = 0; first < tips.size(); first += Turn)
  {
    for (int k = 0; k < 3; ++k)
    {
      set(k);
      for (std::size_t i = first; i < std::min(tips.size(), first + Turn); ++i)
      {
        ProximityResult r;
        TimedQuery(zbuffer, tips[i].data(), nullptr, r, ms[k], deviceMs[k]);
        single[k].push_back(r);
      }
    }
  }
  zbuffer->SetListingPass(Z::ListingPassByDevice);
  // One full submission, for what it dispatches and lists per tip.
  const std::size_t n = std::min(tips.size(), zbuffer->GetBatchCapacity());
  std::vector<ProximityResult> one;
  zbuffer->SetTileListing(vtkZBufferVesselDistance::TileListingOn);
  zbuffer->ComputeProximityBatch(BenchPoints(tips.begin(), tips.begin() + static_cast<std::ptrdiff_t>(n)), nullptr, one);
  Json out;
  for (int on = 0; on < 2; ++on)
  {
    Json side;
    side["batched"] = Timing(batch[on].Ms);
    side["batched_tips_per_second"] = TipsPerSecond(tips.size(), Quantile(batch[on].Ms, 0.5));
    side["single"] = Timing(ms[on]);
    side["single_device"] = Timing(deviceMs[on]);
    out[on == 1 ? "on" : "off"] = side;
  }
  out["on"]["single_device_listed"] = Timing(ms[2]);
  out["on"]["single_device_listed_device"] = Timing(deviceMs[2]);
  out["tiles_dispatched_per_tip"] = zbuffer->GetLastQueryTiles();
  out["tiles_listed_per_tip"] = static_cast<double>(zbuffer->GetLastQueryTilesListed()) / static_cast<double>(std::max<std::size_t>(1, n));
  out["answers_differing"] = CountDifferingAnswers(batch[0].Answers, batch[1].Answers) +
    CountDifferingAnswers(single[0], single[1]) + CountDifferingAnswers(batch[1].Answers, single[1]) +
    CountDifferingAnswers(single[2], single[1]);
  zbuffer->SetTileListing(vtkZBufferVesselDistance::TileListingByDevice);
  return out;
}

/// Where a single tip's time goes (GetLastCallTimes), median over the tips: the whole call, the
/// device's part, the host's wait for it (the device's part included), the inside votes, the
/// ceilings and the answers read; what is left is the results' set-up and the submission's
/// recording.
Json SingleTipTimes(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  CallTimeSeries parts;
  ProximityResult r;
  for (const auto& tip : tips)
  {
    zbuffer->ComputeProximity(tip.data(), nullptr, r);
    parts.Add(zbuffer->GetLastCallTimes());
  }
  return parts.Json();
}

/// A batch through each query pass and each listing pass (its tiles listed), taking turns on the
/// same engine (five rounds): visited per tile and per pixel, listed by a workgroup or by an
/// invocation per answer; tips per second on the host's clock and on the device's, the device's
/// listing and visiting, and the answers that differ from the first pass's (none may).
Json BatchPasses(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  struct Pass
  {
    const char* Name;
    int QueryPass;
    int ListingPass;
  };
  using Z = vtkZBufferVesselDistance;
  constexpr Pass Passes[] = { { "per_tile_listed", Z::QueryPassPerTile, Z::ListingPassPerWorkgroup },
    { "per_pixel_listed", Z::QueryPassPerPixel, Z::ListingPassPerWorkgroup },
    { "per_tile_listed_per_invocation", Z::QueryPassPerTile, Z::ListingPassPerInvocation },
    { "per_pixel_listed_per_invocation", Z::QueryPassPerPixel, Z::ListingPassPerInvocation } };
  constexpr int Count = static_cast<int>(sizeof Passes / sizeof Passes[0]);
  zbuffer->SetTileListing(Z::TileListingOn);
  const std::vector<BatchSide> sides = BatchesInTurn(zbuffer, tips, Count, [&](int p) {
    zbuffer->SetQueryPass(Passes[p].QueryPass);
    zbuffer->SetListingPass(Passes[p].ListingPass);
  });
  zbuffer->SetTileListing(Z::TileListingByDevice);
  zbuffer->SetQueryPass(Z::QueryPassByDevice);
  zbuffer->SetListingPass(Z::ListingPassByDevice);
  Json out;
  for (int p = 0; p < Count; ++p)
  {
    const BatchSide& b = sides[static_cast<std::size_t>(p)];
    const Json parts = b.Parts.Json();
    Json side;
    side["batched"] = Timing(b.Ms);
    side["device"] = parts["device"];
    side["device_listing"] = parts["device_listing"];
    side["device_visiting"] = parts["device_visiting"];
    side["tips_per_second"] = TipsPerSecond(tips.size(), Quantile(b.Ms, 0.5));
    side["device_tips_per_second"] = TipsPerSecond(tips.size(), b.Parts.DeviceMedianMs());
    side["tiles_listed_per_tip"] =
      parts["tiles_listed_in_last_call"].get<double>() / static_cast<double>(std::max<std::size_t>(1, tips.size()));
    side["answers_differing_from_per_tile"] = CountDifferingAnswers(b.Answers, sides[0].Answers);
    out[Passes[p].Name] = side;
  }
  out["tips"] = tips.size();
  return out;
}

/// Two settings' batches taken in turn (BatchesInTurn) as JSON: each side under its name, with
/// its times, tips per second on the host's clock and on the device's, and its parts; the tips,
/// and the answers that differ between the sides (none may).
Json TwoSides(const std::vector<BatchSide>& sides, const char* first, const char* second, std::size_t tips)
{
  Json out;
  for (int k = 0; k < 2; ++k)
  {
    const BatchSide& b = sides[static_cast<std::size_t>(k)];
    Json side = Timing(b.Ms);
    side["tips_per_second"] = TipsPerSecond(tips, Quantile(b.Ms, 0.5));
    side["device_tips_per_second"] = TipsPerSecond(tips, b.Parts.DeviceMedianMs());
    side["parts"] = b.Parts.Json();
    out[k == 0 ? first : second] = side;
  }
  out["tips"] = tips;
  out["answers_differing"] = CountDifferingAnswers(sides[1].Answers, sides[0].Answers);
  return out;
}

/// The batch with one submission in flight and with two (the host reading one and writing the
/// next while the device works), run after run in turn so that both see the device alike, with
/// their parts and the answers that differ (none: the ceilings may differ, not the answers).
/// The engine is left at its default (two).
Json SubmissionsInFlight(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  const std::vector<BatchSide> sides =
    BatchesInTurn(zbuffer, tips, 2, [&](int k) { zbuffer->SetSubmissionsInFlight(k + 1); });
  zbuffer->SetSubmissionsInFlight(2);
  return TwoSides(sides, "one", "two", tips.size());
}

/// The batch's tips submitted in space order and as given (SetBatchOrder), run after run in
/// turn, with their parts and the answers that differ (none may). The engine is left at its
/// default (space order).
Json BatchOrders(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  constexpr int Orders[2] = { vtkZBufferVesselDistance::BatchOrderAsGiven, vtkZBufferVesselDistance::BatchOrderSpatial };
  const std::vector<BatchSide> sides = BatchesInTurn(zbuffer, tips, 2, [&](int k) { zbuffer->SetBatchOrder(Orders[k]); });
  zbuffer->SetBatchOrder(vtkZBufferVesselDistance::BatchOrderSpatial);
  return TwoSides(sides, "as_given", "spatial", tips.size());
}

/// The paper's layers (nearest and farthest depth only) on the same tips.
Json PaperMode(vtkZBufferVesselDistance* zbuffer, const BenchPoints& tips)
{
  std::vector<double> ms;
  ProximityResult z;
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
  for (const auto& tip : tips)
  {
    const double start = NowMs();
    zbuffer->ComputeProximity(tip.data(), nullptr, z);
    ms.push_back(NowMs() - start);
  }
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::ExactIntervals);
  return Timing(ms);
}

/// The box moving with the tracked tip (up to 300 steps): each query re-renders when it leaves.
Json MovingBox(vtkZBufferVesselDistance* zbuffer, const BenchPoints& track)
{
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::MovingWithTip);
  zbuffer->Build();
  const int rendersBefore = zbuffer->GetNumberOfRenders();
  std::vector<double> ms;
  ProximityResult z;
  for (std::size_t i = 0; i < std::min<std::size_t>(track.size(), 300); ++i)
  {
    const double start = NowMs();
    zbuffer->ComputeProximity(track[i].data(), nullptr, z);
    ms.push_back(NowMs() - start);
  }
  Json out = Timing(ms);
  out["renders"] = zbuffer->GetNumberOfRenders() - rendersBefore;
  out["last_render_ms"] = zbuffer->GetLastRenderTimeMs();
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::FixedAroundVessels);
  return out;
}

/// On surfaces that are not closed, the batch's inside votes from the vote field (the engine's
/// setting) and from the rays alone (VoteFieldCellMm 0: the engine built again), one after the
/// other on the same tips, with the answers that differ (in the bands behind folds only, see
/// vp::InsideVoteField). Empty when every surface is closed. The engine is left as it was.
Json VotesFromFieldAndRays(vtkZBufferVesselDistance* zbuffer, const std::vector<NamedMesh>& refined, const BenchPoints& tips)
{
  Json out;
  bool open = false;
  for (int c = 0; c < zbuffer->GetNumberOfVessels(); ++c)
  {
    open = open || !zbuffer->GetSurface(c).IsClosed();
  }
  const double cellMm = zbuffer->GetVoteFieldCellMm();
  if (!open || cellMm <= 0.0)
  {
    return out;
  }
  auto rebuild = [&](double fieldCellMm) {
    zbuffer->RemoveAllVessels();
    zbuffer->SetVoteFieldCellMm(fieldCellMm);
    for (const NamedMesh& vessel : refined)
    {
      zbuffer->AddVessel(vessel.ClassName, vessel.Mesh);
    }
    zbuffer->Build();
    zbuffer->BuildQueryCeilings();
  };
  std::vector<ProximityResult> answers[2];
  for (int rays = 0; rays < 2; ++rays)
  {
    if (rays == 1)
    {
      rebuild(0.0);
    }
    out[rays ? "rays" : "field"] = BenchBatch(zbuffer, tips, nullptr);
    zbuffer->ComputeProximityBatch(tips, nullptr, answers[rays]);
  }
  rebuild(cellMm);
  // The distances must be the same; the inside (or its flag) may differ in a band.
  int distances = 0, votes = 0;
  for (std::size_t i = 0; i < answers[0].size() && i < answers[1].size(); ++i)
  {
    for (std::size_t c = 0; c < answers[0][i].Classes.size(); ++c)
    {
      const ClassProximity& x = answers[0][i].Classes[c];
      const ClassProximity& y = answers[1][i].Classes[c];
      distances += x.InRange != y.InRange || x.DistanceMm != y.DistanceMm ? 1 : 0;
      votes += x.Inside != y.Inside || x.InsideUncertain != y.InsideUncertain ? 1 : 0;
    }
  }
  out["distances_differing"] = distances;
  out["votes_differing"] = votes;
  return out;
}

Json QueryEntries(const QueryTimes& t, double boundMm)
{
  Json entry;
  entry["cached"] = Timing(t.Cached);
  // The device's own time for the same queries (its timestamps; negative: none kept): what is
  // left of a query's time is the host's round trip.
  entry["cached_device"] = Timing(t.CachedDevice);
  entry["cached_with_axis"] = Timing(t.Axis);
  entry["cached_with_axis_device"] = Timing(t.AxisDevice);
  entry["exact_all_classes"] = Timing(t.Exact);
  entry["brute_all_classes"] = Timing(t.Brute);
  entry["answers_compared"] = t.Check.Compared;
  entry["max_abs_diff_vs_exact_mm"] = t.Check.MaxAbsDifferenceMm;
  entry["outside_bound"] = t.Check.OutsideBound;
  entry["error_bound_mm"] = boundMm;
  return entry;
}
} // namespace

BenchJson BenchZBuffer(vtkZBufferVesselDistance* zbuffer, const std::vector<NamedMesh>& refined, std::size_t target,
  const BenchPoints& tips, const BenchPoints& track, int bruteQueries)
{
  std::fprintf(stderr, "bench: z-buffer, %zu classes at %zu triangles: build", refined.size(), target);
  const References refs = BuildAll(zbuffer, refined);
  const DepthLayerGrid fixedGrid = zbuffer->GetGrid();
  Json entry;
  entry["triangles_per_class"] = target;
  entry["triangles"] = refs.Triangles;
  entry["raster_triangles"] = zbuffer->GetNumberOfRasterTriangles();
  entry["grid"] = { fixedGrid.Nx, fixedGrid.Ny, fixedGrid.Nz };
  entry["build_ms"] = zbuffer->GetBuildTimeMs(); // upload and the first rendering
  std::fprintf(stderr, ", render");
  std::vector<double> renderMs;
  for (int i = 0; i < 5; ++i)
  {
    zbuffer->RenderLayers();
    renderMs.push_back(zbuffer->GetLastRenderTimeMs());
  }
  entry["render"] = Timing(renderMs);
  zbuffer->BuildQueryCeilings(); // for the layers just rendered: not in a timed query
  std::fprintf(stderr, ", queries");
  const QueryTimes queries = TimeQueries(zbuffer, refs, tips, bruteQueries);
  entry.update(QueryEntries(queries, zbuffer->GetErrorBoundMm()));
  std::fprintf(stderr, ", batches");
  entry["batch_capacity"] = zbuffer->GetBatchCapacity();
  entry["batched"] = BenchBatch(zbuffer, tips, &queries.Singles);
  const Json other = OtherPass(zbuffer, tips, queries.Singles);
  if (!other.empty())
  {
    entry["other_pass"] = other;
  }
  entry["exact_batched"] = BenchBatch(refs.Exact, tips, nullptr);
  entry["paper_mode"] = PaperMode(zbuffer, tips);
  std::fprintf(stderr, ", ceilings");
  entry["ceilings"] = Ceilings(zbuffer, tips, track);
  std::fprintf(stderr, ", tile listing");
  entry["tile_listing"] = TileListing(zbuffer, tips);
  std::fprintf(stderr, ", batch passes");
  entry["batch_passes"] = BatchPasses(zbuffer, tips);
  entry["single_tip_times"] = SingleTipTimes(zbuffer, tips);
  entry["single_tip_times_tracked"] = SingleTipTimes(zbuffer, track); // the answer before bounds each
  std::fprintf(stderr, ", submissions in flight");
  entry["batch_in_flight"] = SubmissionsInFlight(zbuffer, tips);
  std::fprintf(stderr, ", batch order");
  entry["batch_order"] = BatchOrders(zbuffer, tips);
  std::fprintf(stderr, ", votes");
  const Json votes = VotesFromFieldAndRays(zbuffer, refined, tips);
  if (!votes.empty())
  {
    entry["batch_votes"] = votes;
  }
  std::fprintf(stderr, ", moving box");
  entry["moving_box"] = MovingBox(zbuffer, track);
  std::fprintf(stderr, "\n");
  return entry;
}

BenchJson SideBySide(const std::vector<NamedMesh>& first, const std::vector<NamedMesh>& second, double secondCellMm,
  const BenchPoints& tips, const DistanceEngineSettings& settings)
{
  vtkSmartPointer<vtkZBufferVesselDistance> engines[2];
  for (int e = 0; e < 2; ++e)
  {
    engines[e] = vtkZBufferVesselDistance::SafeDownCast(MakeDistanceEngine(settings));
    if (e == 1 && secondCellMm > 0.0)
    {
      engines[e]->SetCellSizeMm(secondCellMm);
    }
    for (const NamedMesh& vessel : e == 0 ? first : second)
    {
      engines[e]->AddVessel(vessel.ClassName, vessel.Mesh);
    }
    engines[e]->Build();
  }
  constexpr std::size_t SideBySideTurn = 20;
  std::vector<double> ms[2], deviceMs[2], dispatched[2], listed[2];
  ProximityResult r;
  for (std::size_t first = 0; first < tips.size(); first += SideBySideTurn)
  {
    for (int e = 0; e < 2; ++e)
    {
      engines[e]->ComputeProximity(tips[first].data(), nullptr, r); // the query after the switch
      for (std::size_t i = first + 1; i < std::min(tips.size(), first + SideBySideTurn); ++i)
      {
        TimedQuery(engines[e], tips[i].data(), nullptr, r, ms[e], deviceMs[e]);
        dispatched[e].push_back(static_cast<double>(engines[e]->GetLastQueryTiles()));
        listed[e].push_back(static_cast<double>(engines[e]->GetLastQueryTilesListed()));
      }
    }
  }
  Json out;
  for (int e = 0; e < 2; ++e)
  {
    std::size_t triangles = 0;
    for (const NamedMesh& vessel : e == 0 ? first : second)
    {
      triangles += static_cast<std::size_t>(vessel.Mesh->GetNumberOfPolys());
    }
    Json side = { { "triangles", triangles }, { "cell_mm", engines[e]->GetCellSizeMm() },
      { "error_bound_mm", engines[e]->GetErrorBoundMm() } };
    side["cached"] = Timing(ms[e]);
    side["cached_device"] = Timing(deviceMs[e]);
    // What the time follows: the tiles each query started, and those it listed (0 unlisted).
    side["tiles_dispatched_median"] = Quantile(dispatched[e], 0.5);
    side["tiles_listed_median"] = Quantile(listed[e], 0.5);
    out[e == 0 ? "first" : "second"] = side;
  }
  out["ratio_median"] = Quantile(ms[1], 0.5) / std::max(1e-9, Quantile(ms[0], 0.5));
  out["ratio_p95"] = Quantile(ms[1], 0.95) / std::max(1e-9, Quantile(ms[0], 0.95));
  out["ratio_device_median"] = Quantile(deviceMs[1], 0.5) / std::max(1e-9, Quantile(deviceMs[0], 0.5));
  return out;
}

BenchJson ZBufferReport(vtkZBufferVesselDistance* zbuffer, const BenchJson& sizes, const SizedVessels& smallest,
  const SizedVessels& largest, const BenchPoints& tips, const DistanceEngineSettings& settings,
  std::optional<double> fineCellMm)
{
  Json z;
  z["device"] = zbuffer->GetDeviceName();
  z["range_mm"] = zbuffer->GetRangeMm();
  z["cell_mm"] = zbuffer->GetGrid().PixelMm;
  z["error_bound_mm"] = zbuffer->GetErrorBoundMm();
  z["sizes"] = sizes;
  const double first = sizes.front()["cached"]["median_ms"].get<double>();
  const double last = sizes.back()["cached"]["median_ms"].get<double>();
  z["cached_query_ratio_largest_to_smallest"] = last / std::max(1e-9, first);
  if (largest.Target != smallest.Target)
  {
    std::fprintf(stderr, "bench: z-buffer, smallest and largest size side by side\n");
    z["largest_beside_smallest"] = SideBySide(smallest.Vessels, largest.Vessels, 0.0, tips, settings);
  }
  if (fineCellMm)
  {
    std::fprintf(stderr, "bench: z-buffer, the smallest size at %g mm cells beside the set cell\n", *fineCellMm);
    z["fine_cell_beside_cell"] = SideBySide(smallest.Vessels, smallest.Vessels, *fineCellMm, tips, settings);
  }
  return z;
}
} // namespace vp
