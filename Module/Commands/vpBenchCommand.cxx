// vesselproximity bench: the distance engines side by side with the brute-force reference, on
// vessel meshes grown to fixed triangle counts, in one run.
#include "vpBuiltInPhantom.h"
#include "vpArguments.h"
#include "vpBenchReplay.h"
#include "vpAnalyticShapes.h"
#include "vpScalpelLoader.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpTrackingOptions.h"
#include "vtkScalpelModel.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpMeshRefinement.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshWriter.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <sstream>
#include <thread>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

std::vector<std::size_t> ParseSizes(const std::string& text)
{
  std::vector<std::size_t> sizes;
  std::size_t start = 0;
  while (start < text.size())
  {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const long long v = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 1 || v > 100000000LL)
    {
      throw InputError("--sizes", "expected positive triangle counts separated by commas, got '" + item + "'");
    }
    sizes.push_back(static_cast<std::size_t>(v));
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return sizes;
}

/// All tips as one batch (ComputeProximityBatch), five times: time per batch and tips per second
/// (from the median batch). With singles, also how many answers differ from them in any way
/// (there must be none: a batch is the single queries, bit for bit).
Json BenchBatch(vtkVesselDistanceEngine* engine, const std::vector<std::array<double, 3>>& tips,
  const std::vector<ProximityResult>* singles);

Json Timing(const std::vector<double>& ms)
{
  return { { "median_ms", Quantile(ms, 0.5) }, { "p95_ms", Quantile(ms, 0.95) }, { "queries", ms.size() } };
}

Json BenchBatch(vtkVesselDistanceEngine* engine, const std::vector<std::array<double, 3>>& tips,
  const std::vector<ProximityResult>* singles)
{
  std::vector<double> ms;
  std::vector<ProximityResult> batch;
  for (int run = 0; run < 5; ++run)
  {
    const double start = NowMs();
    engine->ComputeProximityBatch(tips, nullptr, batch);
    ms.push_back(NowMs() - start);
  }
  Json out = Timing(ms);
  out["tips"] = tips.size();
  out["tips_per_second"] = 1000.0 * static_cast<double>(tips.size()) / std::max(1e-9, Quantile(ms, 0.5));
  if (singles)
  {
    int differ = 0;
    for (std::size_t i = 0; i < batch.size() && i < singles->size(); ++i)
    {
      for (std::size_t c = 0; c < batch[i].Classes.size(); ++c)
      {
        const ClassProximity& a = batch[i].Classes[c];
        const ClassProximity& b = (*singles)[i].Classes[c];
        differ += a.InRange != b.InRange || (a.InRange && (a.DistanceMm != b.DistanceMm || a.Inside != b.Inside)) ? 1 : 0;
      }
    }
    out["answers_differing_from_single_queries"] = differ;
  }
  return out;
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

/// The exact engine, VTK's locator and brute force, class by class, at one mesh size.
Json BenchExact(const std::vector<NamedMesh>& refined, std::size_t target, const std::vector<std::array<double, 3>>& tips,
  const std::vector<std::array<double, 3>>& track, int bruteQueries)
{
  // The bench measures the full search: no range cut-off, like the brute-force reference.
  const double rangeMm = 1e6;
  Json sizeEntry;
  sizeEntry["target_triangles"] = target;
  Json classList = Json::array();
  for (const NamedMesh& vessel : refined)
  {
    std::fprintf(stderr, "bench: %s at %zu triangles:", vessel.ClassName.c_str(), target);
    vtkPolyData* mesh = vessel.Mesh;
    const std::size_t triangles = static_cast<std::size_t>(mesh->GetNumberOfPolys());

    std::fprintf(stderr, ", exact");
    auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
    exact->SetRangeMm(rangeMm);
    exact->AddVessel(vessel.ClassName, mesh);
    exact->Build();
    std::vector<double> exactMs, trackedMs, exactDistance(tips.size());
    ProximityResult result, previous;
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      const double start = NowMs();
      exact->ComputeProximity(tips[i].data(), nullptr, result);
      exactMs.push_back(NowMs() - start);
      exactDistance[i] = result.Classes[0].DistanceMm;
    }
    for (std::size_t i = 0; i < track.size(); ++i)
    {
      const double start = NowMs();
      exact->ComputeProximity(track[i].data(), nullptr, result, i ? &previous : nullptr);
      trackedMs.push_back(NowMs() - start);
      std::swap(result, previous);
    }
    // A surface that is not closed has its inside decided by a vote of rays: the same tips
    // without it, for what the vote costs.
    std::vector<double> noVoteMs;
    const bool closed = exact->GetSurface(0).IsClosed();
    if (!closed)
    {
      exact->SetVoteOnOpenSurfaces(false);
      for (const auto& tip : tips)
      {
        const double start = NowMs();
        exact->ComputeProximity(tip.data(), nullptr, result);
        noVoteMs.push_back(NowMs() - start);
      }
      exact->SetVoteOnOpenSurfaces(true);
    }

    std::fprintf(stderr, ", vtkStaticCellLocator");
    const double locatorStart = NowMs();
    vtkNew<vtkStaticCellLocator> locator;
    locator->SetDataSet(mesh);
    locator->BuildLocator();
    const double locatorBuildMs = NowMs() - locatorStart;
    vtkNew<vtkGenericCell> cell;
    std::vector<double> locatorMs;
    double locatorDiff = 0;
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      double closest[3], dist2;
      vtkIdType cellId;
      int subId;
      const double start = NowMs();
      locator->FindClosestPoint(tips[i].data(), closest, cell, cellId, subId, dist2);
      locatorMs.push_back(NowMs() - start);
      locatorDiff = std::max(locatorDiff, std::abs(std::sqrt(dist2) - exactDistance[i]));
    }

    std::fprintf(stderr, ", brute force");
    auto brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
    brute->SetRangeMm(rangeMm);
    brute->AddVessel(vessel.ClassName, mesh);
    brute->Build();
    std::vector<double> bruteMs;
    double bruteDiff = 0;
    for (int i = 0; i < bruteQueries; ++i)
    {
      const double start = NowMs();
      brute->ComputeProximity(tips[i].data(), nullptr, result);
      bruteMs.push_back(NowMs() - start);
      bruteDiff = std::max(bruteDiff, std::abs(result.Classes[0].DistanceMm - exactDistance[i]));
    }
    std::fprintf(stderr, "\n");

    Json entry;
    entry["class"] = vessel.ClassName;
    entry["triangles"] = triangles;
    Json exactJson = { { "build_ms", exact->GetBuildTimeMs() } };
    exactJson["random"] = Timing(exactMs);
    exactJson["tracked"] = Timing(trackedMs);
    exactJson["closed"] = closed;
    if (!closed)
    {
      exactJson["random_without_inside_vote"] = Timing(noVoteMs);
      exactJson["inside_vote_cost_ratio"] = Quantile(exactMs, 0.5) / std::max(1e-9, Quantile(noVoteMs, 0.5));
    }
    entry["exact"] = exactJson;
    Json locatorJson = { { "build_ms", locatorBuildMs } };
    locatorJson["random"] = Timing(locatorMs);
    entry["vtk_static_cell_locator"] = locatorJson;
    entry["brute"] = { { "random", Timing(bruteMs) } };
    entry["speedup_exact_vs_brute"] = Quantile(bruteMs, 0.5) / std::max(1e-9, Quantile(exactMs, 0.5));
    entry["speedup_tracked_vs_brute"] = Quantile(bruteMs, 0.5) / std::max(1e-9, Quantile(trackedMs, 0.5));
    entry["max_abs_diff_mm"] = { { "exact_vs_brute", bruteDiff }, { "exact_vs_vtk_locator", locatorDiff } };
    classList.push_back(entry);
  }
  sizeEntry["classes"] = classList;
  return sizeEntry;
}

/// One z-buffer query, its host time in ms and its device time (the engine's timestamps).
void TimedQuery(vtkZBufferVesselDistance* zbuffer, const double* tip, const double* axis, ProximityResult& result,
  std::vector<double>& ms, std::vector<double>& deviceMs)
{
  const double start = NowMs();
  zbuffer->ComputeProximity(tip, axis, result);
  ms.push_back(NowMs() - start);
  deviceMs.push_back(zbuffer->GetLastQueryDeviceMs());
}

/// Two z-buffer engines on the same tips, in turns of SideBySideTurn queries, so that both see the
/// device in the same state (a GPU's clock rises and falls with its load, and a light load leaves
/// it low): host and device times for each, and the second's over the first's. The first query of
/// each turn is left out: each engine holds its own Vulkan device, and a GPU switching between
/// two of them adds about 0.15 ms (H100) to the query after the switch.
Json SideBySide(const std::vector<NamedMesh>& first, const std::vector<NamedMesh>& second, double secondCellMm,
  const std::vector<std::array<double, 3>>& tips, const cli::ParsedArguments& args)
{
  vtkSmartPointer<vtkZBufferVesselDistance> engines[2];
  for (int e = 0; e < 2; ++e)
  {
    engines[e] = vtkZBufferVesselDistance::SafeDownCast(MakeDistanceEngine("zbuffer", args));
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
  std::vector<double> ms[2], deviceMs[2];
  ProximityResult r;
  for (std::size_t first = 0; first < tips.size(); first += SideBySideTurn)
  {
    for (int e = 0; e < 2; ++e)
    {
      engines[e]->ComputeProximity(tips[first].data(), nullptr, r); // the query after the switch
      for (std::size_t i = first + 1; i < std::min(tips.size(), first + SideBySideTurn); ++i)
      {
        TimedQuery(engines[e], tips[i].data(), nullptr, r, ms[e], deviceMs[e]);
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
    out[e == 0 ? "first" : "second"] = side;
  }
  out["ratio_median"] = Quantile(ms[1], 0.5) / std::max(1e-9, Quantile(ms[0], 0.5));
  out["ratio_p95"] = Quantile(ms[1], 0.95) / std::max(1e-9, Quantile(ms[0], 0.95));
  out["ratio_device_median"] = Quantile(deviceMs[1], 0.5) / std::max(1e-9, Quantile(deviceMs[0], 0.5));
  return out;
}

/// The z-buffer engine on all classes at once at one mesh size, beside the exact engine (same
/// range, all classes) and brute force on the same tips.
Json BenchZBuffer(vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& refined, std::size_t target,
  const std::vector<std::array<double, 3>>& tips, const std::vector<std::array<double, 3>>& track, int bruteQueries)
{
  auto* zbuffer = vtkZBufferVesselDistance::SafeDownCast(engine);
  std::fprintf(stderr, "bench: z-buffer, %zu classes at %zu triangles: build", refined.size(), target);
  zbuffer->RemoveAllVessels();
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::ExactIntervals);
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::FixedAroundVessels);
  auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  auto brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  exact->SetRangeMm(zbuffer->GetRangeMm());
  brute->SetRangeMm(zbuffer->GetRangeMm());
  std::size_t triangles = 0;
  for (const NamedMesh& vessel : refined)
  {
    zbuffer->AddVessel(vessel.ClassName, vessel.Mesh);
    exact->AddVessel(vessel.ClassName, vessel.Mesh);
    brute->AddVessel(vessel.ClassName, vessel.Mesh);
    triangles += static_cast<std::size_t>(vessel.Mesh->GetNumberOfPolys());
  }
  zbuffer->Build();
  exact->Build();
  brute->Build();
  const vp::DepthLayerGrid fixedGrid = zbuffer->GetGrid();
  const double buildMs = zbuffer->GetBuildTimeMs(); // upload and the first rendering

  std::fprintf(stderr, ", render");
  std::vector<double> renderMs;
  for (int i = 0; i < 5; ++i)
  {
    zbuffer->RenderLayers();
    renderMs.push_back(zbuffer->GetLastRenderTimeMs());
  }

  std::fprintf(stderr, ", queries");
  const double bound = zbuffer->GetErrorBoundMm();
  std::vector<double> cachedMs, cachedDeviceMs, axisMs, axisDeviceMs, paperMs, exactMs, bruteMs, movingMs;
  ExactComparison check;
  ProximityResult z, e;
  std::vector<ProximityResult> singles;
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    TimedQuery(zbuffer, tips[i].data(), nullptr, z, cachedMs, cachedDeviceMs);
    singles.push_back(z);
    const double start = NowMs();
    exact->ComputeProximity(tips[i].data(), nullptr, e);
    exactMs.push_back(NowMs() - start);
    check.Add(z, e, zbuffer->GetRangeMm(), bound);
  }
  for (int i = 0; i < bruteQueries; ++i)
  {
    const double start = NowMs();
    brute->ComputeProximity(tips[i].data(), nullptr, e);
    bruteMs.push_back(NowMs() - start);
  }
  // With an axis, as tracking asks: the directional distance walks the cells along it.
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    const double axis[3] = { std::cos(0.37 * i), std::sin(0.37 * i), 0.3 };
    TimedQuery(zbuffer, tips[i].data(), axis, z, axisMs, axisDeviceMs);
  }
  std::fprintf(stderr, ", batches");
  const Json zbufferBatch = BenchBatch(zbuffer, tips, &singles);
  // On a GPU, the pass the device did not choose, over the same tips: single tips per tile (a
  // GPU's choice is per pixel), the batch per pixel (its choice is per tile).
  Json otherPass;
  if (zbuffer->GetDeviceDescription().find("llvmpipe") == std::string::npos)
  {
    std::vector<double> tileMs, tileDeviceMs;
    zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassPerTile);
    for (const auto& tip : tips)
    {
      TimedQuery(zbuffer, tip.data(), nullptr, z, tileMs, tileDeviceMs);
    }
    otherPass["cached_per_tile"] = Timing(tileMs);
    otherPass["cached_per_tile_device"] = Timing(tileDeviceMs);
    zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassPerPixel);
    otherPass["batched_per_pixel"] = BenchBatch(zbuffer, tips, &singles);
    zbuffer->SetQueryPass(vtkZBufferVesselDistance::QueryPassByDevice);
  }
  const Json exactBatch = BenchBatch(exact, tips, nullptr);
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
  for (const auto& tip : tips)
  {
    const double start = NowMs();
    zbuffer->ComputeProximity(tip.data(), nullptr, z);
    paperMs.push_back(NowMs() - start);
  }
  zbuffer->SetLayerMode(vtkZBufferVesselDistance::ExactIntervals);

  std::fprintf(stderr, ", moving box");
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::MovingWithTip);
  zbuffer->Build();
  const int rendersBefore = zbuffer->GetNumberOfRenders();
  const std::size_t movingQueries = std::min<std::size_t>(track.size(), 300);
  for (std::size_t i = 0; i < movingQueries; ++i)
  {
    const double start = NowMs();
    zbuffer->ComputeProximity(track[i].data(), nullptr, z);
    movingMs.push_back(NowMs() - start);
  }
  const int movingRenders = zbuffer->GetNumberOfRenders() - rendersBefore;
  const double movingRenderMs = zbuffer->GetLastRenderTimeMs();
  zbuffer->SetBoxMode(vtkZBufferVesselDistance::FixedAroundVessels);
  std::fprintf(stderr, "\n");

  Json entry;
  entry["triangles_per_class"] = target;
  entry["triangles"] = triangles;
  entry["raster_triangles"] = zbuffer->GetNumberOfRasterTriangles();
  entry["grid"] = { fixedGrid.Nx, fixedGrid.Ny, fixedGrid.Nz };
  entry["build_ms"] = buildMs;
  entry["render"] = Timing(renderMs);
  entry["cached"] = Timing(cachedMs);
  // The device's own time for the same queries (its timestamps; negative: none kept): what is
  // left of a query's time is the host's round trip.
  entry["cached_device"] = Timing(cachedDeviceMs);
  entry["cached_with_axis"] = Timing(axisMs);
  entry["cached_with_axis_device"] = Timing(axisDeviceMs);
  entry["batch_capacity"] = zbuffer->GetBatchCapacity();
  if (!otherPass.empty())
  {
    entry["other_pass"] = otherPass;
  }
  entry["paper_mode"] = Timing(paperMs);
  entry["moving_box"] = Timing(movingMs);
  entry["moving_box"]["renders"] = movingRenders;
  entry["moving_box"]["last_render_ms"] = movingRenderMs;
  entry["exact_all_classes"] = Timing(exactMs);
  entry["brute_all_classes"] = Timing(bruteMs);
  entry["batched"] = zbufferBatch;
  entry["exact_batched"] = exactBatch;
  entry["answers_compared"] = check.Compared;
  entry["max_abs_diff_vs_exact_mm"] = check.MaxAbsDifferenceMm;
  entry["outside_bound"] = check.OutsideBound;
  entry["error_bound_mm"] = bound;
  return entry;
}
/// --engines: a list of exact, zbuffer and replay.
std::set<std::string> ParseBenchEngines(const cli::ParsedArguments& args)
{
  std::set<std::string> engineNames;
  std::istringstream engineList(args.GetString("engines"));
  for (std::string name; std::getline(engineList, name, ',');)
  {
    if (name != "exact" && name != "zbuffer" && name != "replay")
    {
      throw InputError("--engines", "expected a list of exact, zbuffer and replay, got '" + name + "'");
    }
    engineNames.insert(name);
  }
  if (engineNames.empty())
  {
    throw InputError("--engines", "expected a list of exact, zbuffer and replay");
  }
  return engineNames;
}

/// The replay's instrument: --scalpel (tip from --tip, its JSON or the finder), else a plain shaft.
vtkSmartPointer<vtkScalpelModel> ReplayScalpel(const cli::ParsedArguments& args)
{
  vtkSmartPointer<vtkScalpelModel> scalpel;
  if (args.IsSet("scalpel"))
  {
    scalpel = LoadScalpel(args.GetString("scalpel"), ParseTipDefinition(args));
  }
  else
  {
    scalpel = vtkSmartPointer<vtkScalpelModel>::New();
    const double z[3] = { 0, 0, 1 };
    const double centre[3] = { 0, 0, -60 };
    scalpel->SetModel(MakeCappedCylinder(centre, z, 1.5, 120.0, 24));
    scalpel->SetTipSource("built-in shaft: tip (0, 0, 0), axis +z");
  }
  return scalpel;
}

/// Random tips in the vessels' box, and a tracked tip's random walk through it.
struct BenchTips
{
  std::vector<std::array<double, 3>> Random, Track;
};

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

using SizedVessels = std::pair<std::vector<NamedMesh>, std::size_t>; // refined, to this many triangles a class

/// The z-buffer's sizes with its settings, the cached query's growth from the smallest size to
/// the largest, and the side-by-side runs (largest beside smallest, --fine-cell beside the cell).

Json ZBufferReport(vtkVesselDistanceEngine* zbufferEngine, const Json& zbufferSizes, const SizedVessels& smallest,
  const SizedVessels& largest, const std::vector<std::array<double, 3>>& tips, const cli::ParsedArguments& args)
{
  Json z;
  auto* engine = vtkZBufferVesselDistance::SafeDownCast(zbufferEngine);
  z["device"] = engine->GetDeviceName();
  z["range_mm"] = engine->GetRangeMm();
  z["cell_mm"] = engine->GetGrid().PixelMm;
  z["error_bound_mm"] = engine->GetErrorBoundMm();
  z["sizes"] = zbufferSizes;
  const double first = zbufferSizes.front()["cached"]["median_ms"].get<double>();
  const double last = zbufferSizes.back()["cached"]["median_ms"].get<double>();
  z["cached_query_ratio_largest_to_smallest"] = last / std::max(1e-9, first);
  if (largest.second != smallest.second)
  {
    std::fprintf(stderr, "bench: z-buffer, smallest and largest size side by side\n");
    z["largest_beside_smallest"] = SideBySide(smallest.first, largest.first, 0.0, tips, args);
  }
  if (args.IsSet("fineCell"))
  {
    std::fprintf(stderr, "bench: z-buffer, the smallest size at %s mm cells beside the set cell\n", args.GetString("fineCell").c_str());
    z["fine_cell_beside_cell"] = SideBySide(smallest.first, smallest.first, args.GetNumber("fineCell"), tips, args);
  }
  return z;
}

void PrintExactTable(const Json& sizes)
{
  std::printf("%-15s %9s | %9s %10s %10s %10s | %9s %10s | %10s | %9s %9s\n", "class", "triangles", "build ms",
    "exact med", "exact p95", "tracked", "vtk build", "vtk med", "brute med", "speedup", "diff mm");
  for (const Json& s : sizes)
  {
    for (const Json& c : s["classes"])
    {
      std::printf("%-15s %9zu | %9.1f %10.4f %10.4f %10.4f | %9.1f %10.4f | %10.3f | %8.0fx %9.1e\n",
        c["class"].get<std::string>().c_str(), c["triangles"].get<std::size_t>(), c["exact"]["build_ms"].get<double>(),
        c["exact"]["random"]["median_ms"].get<double>(), c["exact"]["random"]["p95_ms"].get<double>(),
        c["exact"]["tracked"]["median_ms"].get<double>(), c["vtk_static_cell_locator"]["build_ms"].get<double>(),
        c["vtk_static_cell_locator"]["random"]["median_ms"].get<double>(),
        c["brute"]["random"]["median_ms"].get<double>(), c["speedup_exact_vs_brute"].get<double>(),
        c["max_abs_diff_mm"]["exact_vs_brute"].get<double>());
      if (c["exact"].contains("random_without_inside_vote"))
      {
        std::printf("%-15s   not closed: inside by the vote of rays, median %.4f ms against %.4f without it (%.2fx)\n", "",
          c["exact"]["random"]["median_ms"].get<double>(), c["exact"]["random_without_inside_vote"]["median_ms"].get<double>(),
          c["exact"]["inside_vote_cost_ratio"].get<double>());
      }
    }
  }
}

void PrintZBufferTimes(const Json& z)
{
  std::printf("\nz-buffer on %s, cell %.3f mm, error bound %.3f mm, range %.0f mm (times per query, all classes)\n",
    z["device"].get<std::string>().c_str(), z["cell_mm"].get<double>(), z["error_bound_mm"].get<double>(),
    z["range_mm"].get<double>());
  std::printf("%10s %10s | %9s %9s | %10s %10s %10s | %10s %7s | %10s %10s | %9s %8s\n", "tris/class", "total",
    "build ms", "render ms", "cached med", "cached p95", "paper med", "moving med", "renders", "exact med", "brute med",
    "max diff", "outside");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu %10zu | %9.1f %9.1f | %10.3f %10.3f %10.3f | %10.3f %7d | %10.4f %10.2f | %9.4f %8d\n",
      s["triangles_per_class"].get<std::size_t>(), s["triangles"].get<std::size_t>(), s["build_ms"].get<double>(),
      s["render"]["median_ms"].get<double>(), s["cached"]["median_ms"].get<double>(),
      s["cached"]["p95_ms"].get<double>(), s["paper_mode"]["median_ms"].get<double>(),
      s["moving_box"]["median_ms"].get<double>(), s["moving_box"]["renders"].get<int>(),
      s["exact_all_classes"]["median_ms"].get<double>(), s["brute_all_classes"]["median_ms"].get<double>(),
      s["max_abs_diff_vs_exact_mm"].get<double>(), s["outside_bound"].get<int>());
  }
  std::printf("cached query time, largest size / smallest: %.2f\n", z["cached_query_ratio_largest_to_smallest"].get<double>());
  for (const char* key : { "largest_beside_smallest", "fine_cell_beside_cell" })
  {
    if (z.contains(key))
    {
      const Json& c = z[key];
      std::printf("side by side (%s): %zu triangles at %.3f mm cells %.4f / %.4f ms (device %.4f), %zu at %.3f mm "
                  "%.4f / %.4f ms (device %.4f): ratio %.2f median, %.2f p95, %.2f on the device\n",
        key, c["first"]["triangles"].get<std::size_t>(), c["first"]["cell_mm"].get<double>(),
        c["first"]["cached"]["median_ms"].get<double>(), c["first"]["cached"]["p95_ms"].get<double>(),
        c["first"]["cached_device"]["median_ms"].get<double>(), c["second"]["triangles"].get<std::size_t>(),
        c["second"]["cell_mm"].get<double>(), c["second"]["cached"]["median_ms"].get<double>(),
        c["second"]["cached"]["p95_ms"].get<double>(), c["second"]["cached_device"]["median_ms"].get<double>(),
        c["ratio_median"].get<double>(), c["ratio_p95"].get<double>(), c["ratio_device_median"].get<double>());
    }
  }
}

void PrintZBufferQueries(const Json& z)
{
  std::printf("%10s | %14s %14s | %14s %14s %14s %14s\n", "tris/class", "query med ms", "on device med",
    "axis med ms", "axis p95 ms", "on device med", "on device p95");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu | %14.4f %14.4f | %14.4f %14.4f %14.4f %14.4f\n", s["triangles_per_class"].get<std::size_t>(),
      s["cached"]["median_ms"].get<double>(), s["cached_device"]["median_ms"].get<double>(),
      s["cached_with_axis"]["median_ms"].get<double>(), s["cached_with_axis"]["p95_ms"].get<double>(),
      s["cached_with_axis_device"]["median_ms"].get<double>(), s["cached_with_axis_device"]["p95_ms"].get<double>());
  }
  std::printf("%10s | %14s %14s %16s | %14s\n", "tris/class", "batch med ms", "batch p95 ms", "z-buffer tips/s",
    "exact tips/s");
  for (const Json& s : z["sizes"])
  {
    std::printf("%10zu | %14.2f %14.2f %16.0f | %14.0f   (%zu tips, %zu a submission, %d answers differ from single queries)\n",
      s["triangles_per_class"].get<std::size_t>(), s["batched"]["median_ms"].get<double>(),
      s["batched"]["p95_ms"].get<double>(), s["batched"]["tips_per_second"].get<double>(),
      s["exact_batched"]["tips_per_second"].get<double>(), s["batched"]["tips"].get<std::size_t>(),
      s["batch_capacity"].get<std::size_t>(), s["batched"]["answers_differing_from_single_queries"].get<int>());
  }
}

void PrintReplayTable(const Json& r)
{
  std::printf("\nreplay: %zu poses, %zu classes, %zu triangles, scalpel of %lld triangles\n",
    r["poses"].get<std::size_t>(), r["classes"].get<std::size_t>(), r["triangles"].get<std::size_t>(),
    r["tool_triangles"].get<long long>());
  std::printf("  %-36s %8s %14s %12s %12s\n", "engine", "frames", "frames/s", "median ms", "p95 ms");
  for (const char* key :
    { "exact_tip", "exact_tip_and_surface", "fcl_surface", "spheres_tip_and_surface", "exact_tip_and_surface_within_caution",
      "zbuffer_cached", "zbuffer_tip_and_surface", "zbuffer_full_frame", "brute_tip" })
  {
    if (r.contains(key))
    {
      std::printf("  %-36s %8zu %14.0f %12.4f %12.4f\n", key, r[key]["frames"].get<std::size_t>(),
        r[key]["frames_per_second"].get<double>(), r[key]["frame_median_ms"].get<double>(), r[key]["frame_p95_ms"].get<double>());
    }
  }
  for (const char* key : { "fcl_surface", "spheres_tip_and_surface" })
  {
    std::printf("  %s against exact_tip_and_surface: largest difference %.2e mm, %d in/out of range disagreements\n", key,
      r[key]["vs_exact_tip_and_surface"]["max_abs_diff_mm"].get<double>(),
      r[key]["vs_exact_tip_and_surface"]["in_range_disagreements"].get<int>());
  }
  if (r.contains("zbuffer_cached"))
  {
    std::printf("  z-buffer on %s: layers %.0f ms once; largest |zbuffer - exact| %.4f mm, bound %.3f mm, %d outside\n",
      r["zbuffer_cached"]["device"].get<std::string>().c_str(), r["zbuffer_cached"]["build_and_render_ms"].get<double>(),
      r["zbuffer_cached"]["max_abs_diff_vs_exact_mm"].get<double>(), r["zbuffer_cached"]["error_bound_mm"].get<double>(),
      r["zbuffer_cached"]["outside_bound"].get<int>());
  }
  if (r.contains("zbuffer_tip_and_surface"))
  {
    const Json& w = r["zbuffer_tip_and_surface"];
    const Json& v = w["vs_exact_tip_and_surface"];
    std::printf("  z-buffer whole instrument: field and samples %.0f ms once (%.0f MB); against exact: bound %.3f mm "
                "(%.3f where exact < 5 mm), %d outside it, %d farther than exact\n",
      w["build_ms"].get<double>(), w["field_memory_mb"].get<double>(), v["max_error_bound_mm"].get<double>(),
      v["max_error_bound_within_5mm"].get<double>(), v["outside_bound"].get<int>(), v["farther_than_reference"].get<int>());
  }
  if (r.contains("zbuffer_full_frame"))
  {
    const Json& v = r["zbuffer_full_frame"]["vs_exact_penetration"];
    std::printf("  z-buffer penetration against exact: %d overlapping answers, largest depth difference %.3f mm, volume %.1f "
                "mm3, %d outside the bounds\n",
      v["answers_with_exact_overlap"].get<int>(), v["max_depth_diff_mm"].get<double>(), v["max_volume_diff_mm3"].get<double>(),
      v["outside_bounds"].get<int>());
  }
}

void PrintBenchReport(Json& report)
{
  if (report.contains("sizes"))
  {
    PrintExactTable(report["sizes"]);
  }
  if (report.contains("zbuffer"))
  {
    PrintZBufferTimes(report["zbuffer"]);
    PrintZBufferQueries(report["zbuffer"]);
  }
  if (report.contains("replay"))
  {
    PrintReplayTable(report["replay"]);
  }
}

/// The exact and z-buffer engines on the vessels refined to each size: report["sizes"] and
/// report["zbuffer"].
void BenchSizes(const std::set<std::string>& engines, const std::vector<std::size_t>& sizes,
  vtkVesselDistanceEngine* zbufferEngine, const std::vector<NamedMesh>& vessels, const BenchTips& tips, int bruteQueries,
  const cli::ParsedArguments& args, Json& report)
{
  if (!engines.count("exact") && !engines.count("zbuffer"))
  {
    return;
  }
  Json sizeList = Json::array();
  Json zbufferSizes = Json::array();
  std::vector<NamedMesh> smallest, largest; // for the z-buffer side by side
  std::size_t smallestTarget = 0, largestTarget = 0;
  for (std::size_t target : sizes)
  {
    std::vector<NamedMesh> refined;
    for (const NamedMesh& vessel : vessels)
    {
      std::fprintf(stderr, "bench: refining %s to %zu triangles\n", vessel.ClassName.c_str(), target);
      refined.push_back({ vessel.ClassName, vessel.FileName, RefineToTriangleCount(vessel.Mesh, target), std::nullopt });
    }
    if (engines.count("exact"))
    {
      sizeList.push_back(BenchExact(refined, target, tips.Random, tips.Track, bruteQueries));
    }
    if (engines.count("zbuffer"))
    {
      zbufferSizes.push_back(BenchZBuffer(zbufferEngine, refined, target, tips.Random, tips.Track, bruteQueries));
      if (smallest.empty() || target < smallestTarget)
      {
        smallest = refined;
        smallestTarget = target;
      }
      if (largest.empty() || target > largestTarget)
      {
        largest = refined;
        largestTarget = target;
      }
    }
  }
  if (engines.count("exact"))
  {
    report["sizes"] = sizeList;
  }
  if (engines.count("zbuffer"))
  {
    report["zbuffer"] = ZBufferReport(zbufferEngine, zbufferSizes, { smallest, smallestTarget }, { largest, largestTarget },
      tips.Random, args);
  }
}

} // namespace

cli::ModuleDescription DescribeBenchCommand()
{
  using cli::ParameterType;
  auto count = [](const char* flag, const char* def, const char* description) {
    return Option(ParameterType::Integer, flag, description).SetPlaceholder("N").SetDefault(def).SetRange(1, 100000000, 1);
  };
  std::vector<cli::Parameter> replay = {
    Option(ParameterType::File, "scalpel", "The replay's instrument (default: a 120 mm shaft of 1.5 mm radius).").SetChannel(cli::Channel::Input),
    Option(ParameterType::File, "poses", "A pose file to replay (the demo's poses.csv, say) instead of the generated path.")
      .SetChannel(cli::Channel::Input),
  };
  for (const cli::Parameter& p : ScalpelTipOptions())
  {
    replay.push_back(p);
  }
  cli::ParameterGroup engine = EngineOptions({});
  engine.Parameters.push_back(Option(ParameterType::Double, "fine-cell", "z-buffer: also the smallest size at this cell, beside the set one.").SetPlaceholder("MM"));
  return cli::ModuleDescription::Subcommand("vesselproximity bench", "engines side by side with the brute-force reference, JSON with --json",
    "Grows each vessel mesh to each size (longest-edge bisection: same surface, more triangles) and measures in one run:\n"
    "exact: per class, the exact engine (Embree BVH) on random tips and on a tracked tip (0.5 mm steps, the previous "
    "answer bounding the search), VTK's vtkStaticCellLocator, and the paper's brute-force CPU algorithm; the speed-up "
    "and the largest disagreement.\n"
    "zbuffer: all classes at once, the Vulkan z-buffer engine: rendering the layers, per-query time with cached layers "
    "(exact-interval and paper's mode), the moving box on the tracked tip, beside the exact engine and brute force on "
    "the same tips; the largest |zbuffer - exact| against the error bound. Side by side, query by query (so that both "
    "see the device in the same state: a GPU's clock follows its load), the smallest and the largest size, and with "
    "--fine-cell the smallest size at that cell beside the set one.\n"
    "replay: the tracking pipeline (vtkScalpelTrackingLogic) on the vessels as given, all classes, a scalpel following "
    "the tracked tip: frames per second, exact (tip; tip and whole surface), FCL's whole surface on the same poses (its "
    "answers compared with ours), z-buffer on cached layers: tip, tip and whole instrument from its distance field, "
    "and the full frame with its penetration (with zbuffer among the engines), brute force on the first brute-queries "
    "frames. Progress goes to stderr.",
    {
      { "Workload", "",
        { VesselsOption().SetDescription("The vessels (default: the built-in analytic vessels)."),
          Option(ParameterType::String, "sizes", "Triangles per class to grow each mesh to.").SetPlaceholder("N,N,...").SetDefault("50000,400000,1500000"),
          count("queries", "2000", "Random tips (and tracked steps, and replayed frames)."),
          count("brute-queries", "30", "Of those, how many the brute-force reference answers."),
          count("seed", "1", "The random seed."),
          Option(ParameterType::String, "engines", "Which parts to run: a list of exact, zbuffer and replay.")
            .SetPlaceholder("exact,zbuffer,replay")
            .SetDefault("exact,zbuffer") } },
      { "Replay", "", replay },
      engine,
      { "Output", "",
        { Switch("json", "Print the report as JSON instead of a table."),
          Option(ParameterType::File, "output", "Also write the JSON report to this file.").SetFlag("o").SetChannel(cli::Channel::Output).SetPlaceholder("FILE.json") } },
    });
}

int RunBenchCommand(const cli::ParsedArguments& args)
{
  // Checked before any work: a bad value must not surface after minutes of benchmarks.
  if (args.IsSet("fineCell") && !(args.GetNumber("fineCell") > 0.0))
  {
    throw InputError("--fine-cell", "must be a positive number of millimetres");
  }
  const std::set<std::string> engines = ParseBenchEngines(args);
  const std::vector<std::size_t> sizes = ParseSizes(args.GetString("sizes"));
  // Open the Vulkan device before the long work, so that a missing one fails at once.
  vtkSmartPointer<vtkVesselDistanceEngine> zbufferEngine = engines.count("zbuffer") ? MakeDistanceEngine("zbuffer", args) : nullptr;
  vtkSmartPointer<vtkScalpelModel> scalpel = engines.count("replay") ? ReplayScalpel(args) : nullptr;
  const int queries = args.GetInteger("queries");
  const int bruteQueries = std::min(queries, args.GetInteger("bruteQueries"));
  const unsigned seed = static_cast<unsigned>(args.GetInteger("seed"));
  const std::vector<NamedMesh> vessels =
    args.IsSet("vessels") ? LoadVesselMeshes(ParsePairs(args.GetString("vessels"), "--vessels")) : BuiltInVessels();
  const BenchTips tips = MakeBenchTips(vessels, queries, seed);

  Json report;
  report["benchmark"] = "distance engines vs the paper's brute-force CPU algorithm";
  report["hardware_threads"] = std::thread::hardware_concurrency();
  report["source"] = args.IsSet("vessels") ? "files" : "built-in analytic vessels";
  report["queries"] = queries;
  report["brute_queries"] = bruteQueries;
  report["tracked_step_mm"] = 0.5;
  BenchSizes(engines, sizes, zbufferEngine, vessels, tips, bruteQueries, args, report);
  if (scalpel)
  {
    const std::vector<TrackedPose> poses = args.IsSet("poses") ? ReadPoseFile(args.GetString("poses")) : std::vector<TrackedPose>();
    report["replay"] = BenchReplay(vessels, static_cast<std::size_t>(queries), seed, scalpel,
      zbufferEngine ? MakeDistanceEngine("zbuffer", args) : nullptr, bruteQueries, poses);
    report["replay"]["scalpel"] = scalpel->GetTipSource();
  }
  if (args.IsSet("output"))
  {
    WriteFileAtomically(args.GetString("output"), report.dump(2) + "\n");
  }
  if (args.GetBoolean("json"))
  {
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  PrintBenchReport(report);
  return 0;
}
} // namespace vp
