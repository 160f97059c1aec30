#include "vtkZBufferSurfaceDistance.h"

#include "vpBlockDistanceField.h"
#include "vpInputError.h"
#include "vpSurfaceSamples.h"
#include "vpVesselSurface.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

vtkStandardNewMacro(vtkZBufferSurfaceDistance);

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

std::array<double, 3> Transform(const std::array<double, 16>& m, const std::array<double, 3>& p)
{
  return { m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3], m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
    m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11] };
}
} // namespace

struct vtkZBufferSurfaceDistance::Internals
{
  std::shared_ptr<const vp::SurfaceSamples> Samples;
  vtkPolyData* SamplesFrom = nullptr;
  vtkMTimeType SamplesAt = 0;
  double SamplesSpacingMm = 0.0;

  std::shared_ptr<const vp::BlockDistanceField> Field;
  vtkZBufferVesselDistance* FieldFrom = nullptr;
  vtkMTimeType FieldAt = 0;
  int FieldRenders = -1;
  double FieldBlockMm = 0.0;
};

vtkZBufferSurfaceDistance::vtkZBufferSurfaceDistance()
  : Impl(std::make_unique<Internals>())
{
}

vtkZBufferSurfaceDistance::~vtkZBufferSurfaceDistance() = default;

void vtkZBufferSurfaceDistance::SetZBuffer(vtkZBufferVesselDistance* engine)
{
  if (this->ZBuffer != engine)
  {
    this->ZBuffer = engine;
    this->Modified();
  }
}

long long vtkZBufferSurfaceDistance::GetNumberOfSamples() const
{
  std::lock_guard<std::mutex> lock(this->BuildLock);
  return this->Impl->Samples ? static_cast<long long>(this->Impl->Samples->Points.size()) : 0;
}

long long vtkZBufferSurfaceDistance::GetNumberOfToolTriangles() const
{
  return this->GetNumberOfSamples();
}

double vtkZBufferSurfaceDistance::GetErrorBoundMm() const
{
  if (!this->ZBuffer)
  {
    return 0.0;
  }
  const double spacing = this->SampleSpacingMm > 0.0 ? this->SampleSpacingMm : 0.5 * this->ZBuffer->GetGrid().PixelMm;
  return this->ZBuffer->GetGrid().ErrorBoundMm() + 0.5 * spacing;
}

void vtkZBufferSurfaceDistance::Build()
{
  if (!this->ZBuffer)
  {
    throw std::logic_error("vtkZBufferSurfaceDistance: set the z-buffer engine first");
  }
  if (this->ZBuffer->GetBoxMode() != vtkZBufferVesselDistance::FixedAroundVessels)
  {
    throw vp::InputError("box mode", "the whole instrument needs the layers fixed around the vessels, not a box moving with the tip");
  }
  std::lock_guard<std::mutex> lock(this->BuildLock);
  Internals& s = *this->Impl;
  this->ZBuffer->Build();
  const auto start = std::chrono::steady_clock::now();
  bool worked = false;
  const vp::DepthLayerGrid grid = this->ZBuffer->GetGrid();
  const double spacing = this->SampleSpacingMm > 0.0 ? this->SampleSpacingMm : 0.5 * grid.PixelMm;
  if (!s.Samples || s.SamplesFrom != this->ToolSurface || !this->ToolSurface ||
    s.SamplesAt < this->ToolSurface->GetMTime() || s.SamplesSpacingMm != spacing)
  {
    if (!this->ToolSurface || !this->ToolSurface->GetPoints() || this->ToolSurface->GetNumberOfPolys() == 0)
    {
      throw vp::InputError("scalpel model", "has no surface for the whole-instrument distance");
    }
    const vp::VesselSurface tool("scalpel model", this->ToolSurface);
    // Clusters of about five blocks: few enough to bound them all at every pose, small enough
    // that a cluster's radius keeps its bound tight.
    s.Samples = std::make_shared<const vp::SurfaceSamples>(
      vp::SurfaceSamples::Of(tool.PointArray(), tool.TriangleArray(), spacing, std::max(2.0, 4.0 * spacing)));
    s.SamplesFrom = this->ToolSurface;
    s.SamplesAt = this->ToolSurface->GetMTime();
    s.SamplesSpacingMm = spacing;
    worked = true;
  }
  if (!s.Field || s.FieldFrom != this->ZBuffer || s.FieldAt < this->ZBuffer->GetMTime() ||
    s.FieldRenders != this->ZBuffer->GetNumberOfRenders() || s.FieldBlockMm != this->BlockMm)
  {
    std::vector<std::uint32_t> occupancy;
    this->ZBuffer->CopyOccupancy(occupancy);
    s.Field = std::make_shared<const vp::BlockDistanceField>(grid, this->ZBuffer->GetNumberOfVessels(), occupancy, this->BlockMm);
    s.FieldFrom = this->ZBuffer;
    s.FieldAt = this->ZBuffer->GetMTime();
    s.FieldRenders = this->ZBuffer->GetNumberOfRenders();
    s.FieldBlockMm = this->BlockMm;
    worked = true;
  }
  if (worked)
  {
    this->BuildTimeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

void vtkZBufferSurfaceDistance::ComputeSurfaceProximity(
  const std::array<double, 16>& m, std::vector<vp::SurfaceProximity>& out, const std::vector<vp::SurfaceProximity>* previous) const
{
  const_cast<vtkZBufferSurfaceDistance*>(this)->Build(); // returns at once when nothing changed
  std::shared_ptr<const vp::SurfaceSamples> samplesHeld;
  std::shared_ptr<const vp::BlockDistanceField> fieldHeld;
  {
    std::lock_guard<std::mutex> lock(this->BuildLock);
    samplesHeld = this->Impl->Samples;
    fieldHeld = this->Impl->Field;
  }
  const vp::SurfaceSamples& S = *samplesHeld;
  const vp::BlockDistanceField& field = *fieldHeld;
  const int classes = this->ZBuffer->GetNumberOfVessels();
  const vp::DepthLayerGrid grid = this->ZBuffer->GetGrid();
  const double range = this->RangeMm > 0.0 ? std::min(this->RangeMm, this->ZBuffer->GetRangeMm()) : this->ZBuffer->GetRangeMm();
  const double halfDiagonal = grid.HalfDiagonalMm();
  const double layersBound = grid.ErrorBoundMm();
  const double cellMm = std::min(grid.PixelMm, grid.SliceMm);

  // Distances below are to the nearest marked cell (the engine's answer less half a diagonal),
  // the quantity the field bounds from below.
  std::vector<double> best(classes, Inf);
  std::vector<std::int64_t> bestSample(classes, -1);
  std::vector<std::array<double, 3>> bestVessel(classes);
  // Transformed when needed, not kept: nine products cost less than a per-pose array of every
  // sample (a million for the CUSA).
  auto worldOf = [&](std::size_t i) { return Transform(m, S.Points[i]); };
  long long measured = 0, submissions = 0;
  std::vector<vp::ProximityResult> results;
  vtkZBufferVesselDistance::Points batch;
  std::vector<std::size_t> batchSamples;
  auto measure = [&](double searchMm) {
    // Padded to a power of two with points far outside everything: the engine keeps one prepared
    // submission per batch size, so a handful of sizes serve every pose.
    std::size_t n = 8;
    while (n < batch.size())
    {
      n *= 2;
    }
    const std::array<double, 3> far{ grid.OriginMm[0] - 1e6, grid.OriginMm[1] - 1e6, grid.OriginMm[2] - 1e6 };
    batch.resize(n, far);
    // A few search lengths only, for the same reason: the next power of two of cells, at most the range.
    double search = cellMm;
    while (search < searchMm && search < range)
    {
      search *= 2.0;
    }
    this->ZBuffer->ComputeProximityBatchWithin(batch, std::min(search, range), results);
    ++submissions;
    for (std::size_t j = 0; j < batchSamples.size(); ++j)
    {
      const std::size_t i = batchSamples[j];
      ++measured;
      for (int c = 0; c < classes; ++c)
      {
        const vp::ClassProximity& r = results[j].Classes[c];
        if (r.InRange)
        {
          const double d = r.DistanceMm - halfDiagonal;
          if (d < best[c])
          {
            best[c] = d;
            bestSample[c] = static_cast<std::int64_t>(i);
            bestVessel[c] = { r.ClosestPoint[0], r.ClosestPoint[1], r.ClosestPoint[2] };
          }
        }
      }
    }
    batch.clear();
    batchSamples.clear();
  };
  auto limit = [&](int c) { return std::min(best[c], range); };

  // Per class and cluster, a lower bound on every sample of the cluster.
  const std::size_t clusters = S.Clusters.size();
  std::vector<double> clusterBound(clusters * classes);
  for (std::size_t k = 0; k < clusters; ++k)
  {
    const auto centre = Transform(m, S.Clusters[k].CentreMm);
    for (int c = 0; c < classes; ++c)
    {
      clusterBound[k * classes + c] = std::max(0.0, field.LowerBoundMm(c, centre.data()) - S.Clusters[k].RadiusMm);
    }
  }

  // Seeds: the previous frame's closest samples, and per class the sample nearest by bound in
  // the cluster nearest by bound. They make the first search short.
  for (int c = 0; c < classes; ++c)
  {
    std::size_t seed = S.Points.size();
    if (previous && static_cast<int>(previous->size()) == classes && (*previous)[c].InRange &&
      (*previous)[c].ToolTriangle >= 0 && static_cast<std::size_t>((*previous)[c].ToolTriangle) < S.Points.size())
    {
      seed = static_cast<std::size_t>((*previous)[c].ToolTriangle);
    }
    std::size_t nearest = clusters;
    for (std::size_t k = 0; k < clusters; ++k)
    {
      if (clusterBound[k * classes + c] <= range &&
        (nearest == clusters || clusterBound[k * classes + c] < clusterBound[nearest * classes + c]))
      {
        nearest = k;
      }
    }
    std::size_t byBound = S.Points.size();
    if (nearest < clusters)
    {
      double lowest = Inf;
      const auto& cl = S.Clusters[nearest];
      for (std::size_t i = cl.First; i < cl.First + cl.Count; ++i)
      {
        const double b = field.LowerBoundMm(c, worldOf(i).data());
        if (b < lowest)
        {
          lowest = b;
          byBound = i;
        }
      }
    }
    for (std::size_t i : { seed, byBound })
    {
      if (i < S.Points.size() && std::find(batchSamples.begin(), batchSamples.end(), i) == batchSamples.end())
      {
        batch.push_back(worldOf(i));
        batchSamples.push_back(i);
      }
    }
  }
  const std::vector<std::size_t> seeds = batchSamples;
  if (!batch.empty())
  {
    measure(range);
  }

  // Candidates: the samples, seeds apart, whose bound for some class is below the best found for
  // it. Each sample is in one cluster, so in the list at most once.
  struct Candidate
  {
    double Key;          // the least of its bounds below the best of their class
    std::uint32_t Index; // into candidateSample, and into bounds by class
  };
  std::vector<Candidate> candidates;
  std::vector<std::size_t> candidateSample;
  std::vector<double> bounds; // [candidate][class]
  for (std::size_t k = 0; k < clusters; ++k)
  {
    bool wanted = false;
    for (int c = 0; c < classes; ++c)
    {
      wanted = wanted || clusterBound[k * classes + c] < limit(c);
    }
    if (!wanted)
    {
      continue;
    }
    const auto& cl = S.Clusters[k];
    for (std::size_t i = cl.First; i < cl.First + cl.Count; ++i)
    {
      if (std::find(seeds.begin(), seeds.end(), i) != seeds.end())
      {
        continue;
      }
      double key = Inf;
      const std::size_t at = bounds.size();
      bounds.resize(at + classes);
      const std::array<double, 3> p = worldOf(i);
      for (int c = 0; c < classes; ++c)
      {
        const double b = clusterBound[k * classes + c] < limit(c) ? field.LowerBoundMm(c, p.data()) : Inf;
        bounds[at + c] = b;
        if (b < limit(c))
        {
          key = std::min(key, b);
        }
      }
      if (key == Inf)
      {
        bounds.resize(at);
        continue;
      }
      candidates.push_back({ key, static_cast<std::uint32_t>(candidateSample.size()) });
      candidateSample.push_back(i);
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.Key < b.Key; });

  // Nearest bound first, one batch at a time, each searching no farther than the farthest best
  // it can still improve.
  // The farthest best a candidate can still improve; 0 when it can improve none.
  auto wantedTo = [&](const Candidate& cand) {
    double searchMm = 0.0;
    for (int c = 0; c < classes; ++c)
    {
      if (bounds[cand.Index * classes + c] < limit(c))
      {
        searchMm = std::max(searchMm, limit(c));
      }
    }
    return searchMm;
  };
  std::size_t next = 0;
  while (next < candidates.size() && measured < this->MaxQueriedPoints)
  {
    double searchMm = 0.0;
    while (next < candidates.size() && batch.size() < vtkZBufferVesselDistance::BatchCapacity &&
      measured + static_cast<long long>(batch.size()) < this->MaxQueriedPoints)
    {
      const Candidate& cand = candidates[next++];
      const double wanted = wantedTo(cand);
      if (wanted > 0.0)
      {
        searchMm = std::max(searchMm, wanted);
        batch.push_back(worldOf(candidateSample[cand.Index]));
        batchSamples.push_back(candidateSample[cand.Index]);
      }
    }
    if (!batch.empty())
    {
      measure(searchMm);
    }
  }
  // What the cap left undecided: the least bound, per class, of the candidates not measured.
  std::vector<double> undecided(classes, Inf);
  std::vector<std::size_t> undecidedSample(classes, 0);
  for (std::size_t j = next; j < candidates.size(); ++j)
  {
    for (int c = 0; c < classes; ++c)
    {
      const double b = bounds[candidates[j].Index * classes + c];
      if (b < limit(c) && b < undecided[c])
      {
        undecided[c] = b;
        undecidedSample[c] = candidateSample[candidates[j].Index];
      }
    }
  }

  const double spacing = S.SpacingMm;
  out.assign(classes, vp::SurfaceProximity{});
  for (int c = 0; c < classes; ++c)
  {
    vp::SurfaceProximity& r = out[c];
    const double hi = limit(c);
    const double lo = std::min(hi, undecided[c]);
    if (bestSample[c] < 0 && !(lo < range))
    {
      r.InRange = false;
      continue;
    }
    r.InRange = true;
    // The true distance lies in [lo + h - bound - spacing, hi + h + bound] (h: half a diagonal):
    // reported at the middle, with half that width as its bound.
    r.DistanceMm = std::max(0.0, 0.5 * (lo + hi) + halfDiagonal - 0.5 * spacing);
    r.ErrorBoundMm = 0.5 * (hi - lo) + layersBound + 0.5 * spacing;
    // With nothing measured within range (the cap stopped the search first), the pair is the
    // sample nearest by bound, on both sides: the best the search knows.
    const std::array<double, 3> tool =
      worldOf(bestSample[c] >= 0 ? static_cast<std::size_t>(bestSample[c]) : undecidedSample[c]);
    for (int k = 0; k < 3; ++k)
    {
      r.PointOnToolMm[k] = tool[k];
      r.PointOnVesselMm[k] = bestSample[c] >= 0 ? bestVessel[c][k] : tool[k];
    }
    r.ToolTriangle = bestSample[c];
    r.VesselTriangle = -1;
  }
  this->LastQueried = measured;
  this->LastSubmissions = submissions;
}

void vtkZBufferSurfaceDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ZBuffer: " << this->ZBuffer.GetPointer() << "\n";
  os << indent << "SampleSpacingMm: " << this->SampleSpacingMm << (this->SampleSpacingMm > 0.0 ? "" : " (half a cell)") << "\n";
  os << indent << "BlockMm: " << this->BlockMm << "\n";
  os << indent << "MaxQueriedPoints: " << this->MaxQueriedPoints << "\n";
  os << indent << "Samples: " << this->GetNumberOfSamples() << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
}
