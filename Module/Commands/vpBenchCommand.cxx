// vesselproximity bench: the distance engines side by side with the brute-force reference, on
// vessel meshes grown to fixed triangle counts, in one run.
#include "vpBuiltInPhantom.h"
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpMeshRefinement.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshWriter.h"

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
#include <thread>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

const char* Usage =
  "usage: vesselproximity bench [--vessels CLASS=FILE,...] [--sizes N,N,...] [--queries N]\n"
  "         [--brute-queries N] [--seed N] [--json] [-o FILE.json]\n"
  "  Grows each vessel mesh to each size (longest-edge bisection: same surface, more triangles)\n"
  "  and measures, per class, in one run: the exact engine (Embree BVH) on random tips and on a\n"
  "  tracked tip (0.5 mm steps, the previous answer bounding the search), VTK's\n"
  "  vtkStaticCellLocator, and the paper's brute-force CPU algorithm; with the speed-up over\n"
  "  brute force and the largest disagreement between engines.\n"
  "  Defaults: the built-in analytic vessels, sizes 50000,400000,1500000, 2000 queries,\n"
  "  30 brute-force queries. Progress goes to stderr.\n";

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

Json Timing(const std::vector<double>& ms)
{
  return { { "median_ms", Quantile(ms, 0.5) }, { "p95_ms", Quantile(ms, 0.95) }, { "queries", ms.size() } };
}

std::vector<NamedMesh> BuiltInVessels()
{
  std::vector<NamedMesh> vessels;
  for (const auto& v : MakeBuiltInVessels())
  {
    vessels.push_back({ v.first, "built-in", v.second });
  }
  return vessels;
}
} // namespace

int RunBenchCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage;
    return 0;
  }
  const Arguments args(argv, { "--vessels", "--sizes", "--queries", "--brute-queries", "--seed", "-o" }, { "--json" });
  const std::vector<std::size_t> sizes = ParseSizes(args.Get("--sizes", "50000,400000,1500000"));
  const int queries = args.GetInteger("--queries", 2000);
  const int bruteQueries = std::min(queries, args.GetInteger("--brute-queries", 30));
  const unsigned seed = static_cast<unsigned>(args.GetInteger("--seed", 1));
  const std::vector<NamedMesh> vessels =
    args.Has("--vessels") ? LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels")) : BuiltInVessels();

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

  // The bench measures the full search: no range cut-off, like the brute-force reference.
  const double rangeMm = 1e6;
  Json report;
  report["benchmark"] = "exact distance engines vs the paper's brute-force CPU algorithm";
  report["hardware_threads"] = std::thread::hardware_concurrency();
  report["source"] = args.Has("--vessels") ? "files" : "built-in analytic vessels";
  report["queries"] = queries;
  report["brute_queries"] = bruteQueries;
  report["tracked_step_mm"] = 0.5;
  Json sizeList = Json::array();
  for (std::size_t target : sizes)
  {
    Json sizeEntry;
    sizeEntry["target_triangles"] = target;
    Json classList = Json::array();
    for (const NamedMesh& vessel : vessels)
    {
      std::fprintf(stderr, "bench: %s at %zu triangles: refining", vessel.ClassName.c_str(), target);
      vtkSmartPointer<vtkPolyData> mesh = RefineToTriangleCount(vessel.Mesh, target);
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
    sizeList.push_back(sizeEntry);
  }
  report["sizes"] = sizeList;

  if (args.Has("-o"))
  {
    WriteFileAtomically(args.Get("-o"), report.dump(2) + "\n");
  }
  if (args.Has("--json"))
  {
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  std::printf("%-15s %9s | %9s %10s %10s %10s | %9s %10s | %10s | %9s %9s\n", "class", "triangles", "build ms",
    "exact med", "exact p95", "tracked", "vtk build", "vtk med", "brute med", "speedup", "diff mm");
  for (const Json& s : report["sizes"])
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
    }
  }
  return 0;
}
} // namespace vp
