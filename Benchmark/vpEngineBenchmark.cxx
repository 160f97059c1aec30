#include "vpEngineBenchmark.h"

#include "vpBreachBenchmark.h"
#include "vpDefaultScalpel.h"
#include "vpLiveBenchmark.h"

#include "vpDistanceEngineFactory.h"
#include "vpExactBenchmark.h"
#include "vpMeshRefinement.h"
#include "vpPenetrationBenchmark.h"
#include "vpReplayBenchmark.h"
#include "vpZBufferBenchmark.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <thread>

namespace vp
{
namespace
{
using Json = BenchJson;

/// The exact and z-buffer engines on the vessels refined to each size: report["sizes"] and
/// report["zbuffer"].
void BenchSizes(const BenchmarkRequest& request, const BenchTips& tips, Json& report)
{
  const bool exact = request.Parts.count("exact") > 0, zbuffer = request.Parts.count("zbuffer") > 0;
  Json sizeList = Json::array(), zbufferSizes = Json::array();
  SizedVessels smallest, largest; // for the z-buffer side by side
  for (std::size_t target : request.SizesTriangles)
  {
    SizedVessels refined{ {}, target };
    for (const NamedMesh& vessel : request.Vessels)
    {
      std::fprintf(stderr, "bench: refining %s to %zu triangles\n", vessel.ClassName.c_str(), target);
      refined.Vessels.push_back({ vessel.ClassName, vessel.FileName, RefineToTriangleCount(vessel.Mesh, target), std::nullopt });
    }
    if (exact)
    {
      sizeList.push_back(BenchExact(refined.Vessels, target, tips.Random, tips.Track, request.BruteQueries));
    }
    if (zbuffer)
    {
      zbufferSizes.push_back(BenchZBuffer(request.ZBuffer, refined.Vessels, target, tips.Random, tips.Track, request.BruteQueries));
      smallest = smallest.Vessels.empty() || target < smallest.Target ? refined : smallest;
      largest = largest.Vessels.empty() || target > largest.Target ? refined : largest;
    }
  }
  if (exact)
  {
    report["sizes"] = sizeList;
  }
  if (zbuffer)
  {
    report["zbuffer"] = ZBufferReport(request.ZBuffer, zbufferSizes, smallest, largest, tips.Random,
      request.ZBufferSettings, request.FineCellMm);
  }
}
} // namespace

vtkSmartPointer<vtkZBufferVesselDistance> MakeBenchZBuffer(const DistanceEngineSettings& settings)
{
  return vtkZBufferVesselDistance::SafeDownCast(MakeDistanceEngine(settings));
}

BenchJson RunBenchmark(const BenchmarkRequest& request)
{
  const BenchTips tips = MakeBenchTips(request.Vessels, request.Queries, request.Seed);
  Json report;
  report["benchmark"] = "distance engines vs the paper's brute-force CPU algorithm";
  report["hardware_threads"] = std::thread::hardware_concurrency();
  report["source"] = request.Source;
  report["queries"] = request.Queries;
  report["brute_queries"] = request.BruteQueries;
  report["tracked_step_mm"] = 0.5;
  if (request.Parts.count("exact") || request.Parts.count("zbuffer"))
  {
    BenchSizes(request, tips, report);
  }
  if (request.Parts.count("replay"))
  {
    report["replay"] = BenchReplay(request.Vessels, static_cast<std::size_t>(request.Queries), request.Seed, request.Scalpel,
      request.Parts.count("zbuffer") ? &request.ZBufferSettings : nullptr, request.BruteQueries, request.Poses);
    report["replay"]["scalpel"] = request.Scalpel->GetTipSource();
  }
  if (request.Parts.count("live"))
  {
    if (request.Parts.count("breach"))
    {
      // At the breach: the breach's poses streamed with its instrument, the tip alone beside.
      vtkSmartPointer<vtkScalpelModel> tool = request.BreachScalpel ? request.BreachScalpel : MakeDefaultScalpel();
      LiveBenchSettings live = request.Live;
      live.TipOnlyBeside = true;
      live.EngineBeside = &request.ZBufferSettings;
      report["live"] = BenchLive(request.Vessels, tool, BreachPoses(request.Vessels, tool, request.Breach), live);
      report["live"]["poses"] = "the breach's";
    }
    else
    {
      const std::vector<TrackedPose> poses = request.Poses.empty()
        ? PosesNearVessels(request.Vessels, static_cast<std::size_t>(request.Queries), request.Seed, request.Scalpel)
        : request.Poses;
      report["live"] = BenchLive(request.Vessels, request.Scalpel, poses, request.Live);
    }
  }
  if (request.Parts.count("penetration"))
  {
    report["penetration"] = BenchPenetration(request.PenetrationPoses, &request.ZBufferSettings);
  }
  if (request.Parts.count("breach"))
  {
    report["breach"] = BenchBreach(request.Vessels, request.BreachScalpel, request.Breach, &request.ZBufferSettings);
    report["breach"]["scalpel"] = request.BreachScalpel ? request.BreachScalpel->GetTipSource() : "the built-in CUSA handpiece";
  }
  if (request.Parts.count("models"))
  {
    ModelsBenchSettings models = request.Models;
    models.WorkFolder = models.WorkFolder.empty()
      ? (std::filesystem::temp_directory_path() / ("vp-models-bench-" + std::to_string(::getpid()))).string()
      : models.WorkFolder;
    report["models"] = BenchModels(models);
  }
  return report;
}
} // namespace vp
