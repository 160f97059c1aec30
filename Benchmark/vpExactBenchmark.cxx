#include "vpExactBenchmark.h"

#include "vpClock.h"
#include "vpInsideVoteField.h"
#include "vpQuantile.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"

#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vp
{
namespace
{
using Json = BenchJson;
constexpr double FullSearchRangeMm = 1e6;

/// One engine's times on the tips, and the largest difference from the exact distances.
struct Times
{
  std::vector<double> Ms;
  double BuildMs = 0.0;
  double MaxDifferenceMm = 0.0;
};

struct ExactTimes
{
  Times Random, Tracked, WithoutVote;
  /// On a surface that is not closed, the vote alone at the random tips: from the inside vote
  /// field where it holds the tip's (as the z-buffer's vote engine has it), and from the rays
  /// only (this engine's default), side by side.
  Times VoteFromField, VoteFromRays;
  std::size_t VotesHeld = 0;
  Json Field;
  std::vector<double> DistanceMm; ///< per random tip: the reference for the others
  bool Closed = true;
};

ExactTimes TimeExact(const NamedMesh& vessel, const BenchPoints& tips, const BenchPoints& track)
{
  auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  exact->SetRangeMm(FullSearchRangeMm);
  exact->AddVessel(vessel.ClassName, vessel.Mesh);
  exact->Build();
  ExactTimes t;
  t.Random.BuildMs = exact->GetBuildTimeMs();
  ProximityResult result, previous;
  for (const auto& tip : tips)
  {
    const double start = NowMs();
    exact->ComputeProximity(tip.data(), nullptr, result);
    t.Random.Ms.push_back(NowMs() - start);
    t.DistanceMm.push_back(result.Classes[0].DistanceMm);
  }
  for (std::size_t i = 0; i < track.size(); ++i)
  {
    const double start = NowMs();
    exact->ComputeProximity(track[i].data(), nullptr, result, i ? &previous : nullptr);
    t.Tracked.Ms.push_back(NowMs() - start);
    std::swap(result, previous);
  }
  // A surface that is not closed has its inside decided by a vote of rays: the same tips
  // without it, for what the vote costs.
  t.Closed = exact->GetSurface(0).IsClosed();
  auto fielded = vtkSmartPointer<vtkExactVesselDistance>::New();
  fielded->SetRangeMm(vtkVesselDistanceEngine::DefaultRangeMm); // the field reaches the range
  fielded->SetVoteFieldCellMm(1.0); // the z-buffer's vote engine's
  fielded->AddVessel(vessel.ClassName, vessel.Mesh);
  if (const InsideVoteField* field = t.Closed ? nullptr : fielded->GetVoteField(0)) // built when asked
  {
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      bool uncertain = false, inside = false;
      t.VotesHeld += field->Lookup(tips[i].data(), inside, uncertain) ? 1 : 0;
      double start = NowMs();
      fielded->VoteInside(0, tips[i].data(), t.DistanceMm[i], uncertain);
      t.VoteFromField.Ms.push_back(NowMs() - start);
      start = NowMs();
      exact->VoteInside(0, tips[i].data(), t.DistanceMm[i], uncertain);
      t.VoteFromRays.Ms.push_back(NowMs() - start);
    }
    t.Field = { { "built", field->IsBuilt() }, { "build_ms", field->BuildMs() }, { "cell_mm", field->CellMm() },
      { "cells", field->Cells() }, { "voted_cells", field->VotedCells() }, { "regions", field->Regions() },
      { "swept_edges", field->SweptEdges() } };
  }
  exact->SetVoteOnOpenSurfaces(false);
  for (std::size_t i = 0; !t.Closed && i < tips.size(); ++i)
  {
    const double start = NowMs();
    exact->ComputeProximity(tips[i].data(), nullptr, result);
    t.WithoutVote.Ms.push_back(NowMs() - start);
  }
  return t;
}

Times TimeLocator(vtkPolyData* mesh, const BenchPoints& tips, const std::vector<double>& exactMm)
{
  Times t;
  const double start = NowMs();
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  t.BuildMs = NowMs() - start;
  vtkNew<vtkGenericCell> cell;
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    double closest[3], dist2;
    vtkIdType cellId;
    int subId;
    const double queryStart = NowMs();
    locator->FindClosestPoint(tips[i].data(), closest, cell, cellId, subId, dist2);
    t.Ms.push_back(NowMs() - queryStart);
    t.MaxDifferenceMm = std::max(t.MaxDifferenceMm, std::abs(std::sqrt(dist2) - exactMm[i]));
  }
  return t;
}

Times TimeBrute(const NamedMesh& vessel, const BenchPoints& tips, int queries, const std::vector<double>& exactMm)
{
  auto brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  brute->SetRangeMm(FullSearchRangeMm);
  brute->AddVessel(vessel.ClassName, vessel.Mesh);
  brute->Build();
  Times t;
  ProximityResult result;
  for (int i = 0; i < queries; ++i)
  {
    const double start = NowMs();
    brute->ComputeProximity(tips[i].data(), nullptr, result);
    t.Ms.push_back(NowMs() - start);
    t.MaxDifferenceMm = std::max(t.MaxDifferenceMm, std::abs(result.Classes[0].DistanceMm - exactMm[i]));
  }
  return t;
}

double MedianRatio(const std::vector<double>& slow, const std::vector<double>& fast)
{
  return Quantile(slow, 0.5) / std::max(1e-9, Quantile(fast, 0.5));
}

Json ClassEntry(const NamedMesh& vessel, const ExactTimes& exact, const Times& locator, const Times& brute)
{
  Json exactJson = { { "build_ms", exact.Random.BuildMs } };
  exactJson["random"] = Timing(exact.Random.Ms);
  exactJson["tracked"] = Timing(exact.Tracked.Ms);
  exactJson["closed"] = exact.Closed;
  if (!exact.Closed)
  {
    exactJson["random_without_inside_vote"] = Timing(exact.WithoutVote.Ms);
    exactJson["inside_vote_cost_ratio"] = MedianRatio(exact.Random.Ms, exact.WithoutVote.Ms);
    if (!exact.VoteFromField.Ms.empty())
    {
      Json vote = { { "from_field", Timing(exact.VoteFromField.Ms) }, { "from_rays", Timing(exact.VoteFromRays.Ms) },
        { "speedup_field_vs_rays", MedianRatio(exact.VoteFromRays.Ms, exact.VoteFromField.Ms) },
        { "tips_held_by_field", exact.VotesHeld }, { "field", exact.Field } };
      exactJson["inside_vote"] = vote;
    }
  }
  Json entry;
  entry["class"] = vessel.ClassName;
  entry["triangles"] = static_cast<std::size_t>(vessel.Mesh->GetNumberOfPolys());
  entry["exact"] = exactJson;
  entry["vtk_static_cell_locator"] = { { "build_ms", locator.BuildMs }, { "random", Timing(locator.Ms) } };
  entry["brute"] = { { "random", Timing(brute.Ms) } };
  entry["speedup_exact_vs_brute"] = MedianRatio(brute.Ms, exact.Random.Ms);
  entry["speedup_tracked_vs_brute"] = MedianRatio(brute.Ms, exact.Tracked.Ms);
  entry["max_abs_diff_mm"] = { { "exact_vs_brute", brute.MaxDifferenceMm }, { "exact_vs_vtk_locator", locator.MaxDifferenceMm } };
  return entry;
}
} // namespace

BenchJson BenchExact(const std::vector<NamedMesh>& refined, std::size_t target, const BenchPoints& tips,
  const BenchPoints& track, int bruteQueries)
{
  Json classList = Json::array();
  for (const NamedMesh& vessel : refined)
  {
    std::fprintf(stderr, "bench: %s at %zu triangles:, exact", vessel.ClassName.c_str(), target);
    const ExactTimes exact = TimeExact(vessel, tips, track);
    std::fprintf(stderr, ", vtkStaticCellLocator");
    const Times locator = TimeLocator(vessel.Mesh, tips, exact.DistanceMm);
    std::fprintf(stderr, ", brute force");
    const Times brute = TimeBrute(vessel, tips, bruteQueries, exact.DistanceMm);
    std::fprintf(stderr, "\n");
    classList.push_back(ClassEntry(vessel, exact, locator, brute));
  }
  Json sizeEntry;
  sizeEntry["target_triangles"] = target;
  sizeEntry["classes"] = classList;
  return sizeEntry;
}
} // namespace vp
