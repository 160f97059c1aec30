#include "vtkZBufferSurfaceDistance.h"

#include "vpCellDistanceField.h"
#include "vpInputError.h"
#include "vpSurfaceSamples.h"
#include "vpVesselSurface.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
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

/// The instrument's samples nearest each class at one pose, as the field bounds them: per class
/// the least lower bound of any sample, the least upper bound of the samples evaluated (the
/// distance is at most it), and the sample holding the upper one.
class NearestSamples
{
public:
  NearestSamples(const vp::SurfaceSamples& samples, const vp::CellDistanceField& field, const std::array<double, 16>& m,
    int classes, double rangeMm)
    : Low(classes, Inf)
    , High(classes, Inf)
    , BestSample(classes, -1)
    , BestPoint(classes)
    , S(samples)
    , Field(field)
    , M(m)
    , Classes(classes)
    , RangeMm(rangeMm)
  {
  }

  /// Sample i, for the classes nodeBound (its node's bounds; null: every class) does not rule out.
  void Evaluate(std::size_t i, const double* nodeBound)
  {
    const std::array<double, 3> p = Transform(this->M, this->S.Points[i]);
    ++this->Evaluated;
    for (int c = 0; c < this->Classes; ++c)
    {
      if (nodeBound && nodeBound[c] >= this->Limit(c))
      {
        continue;
      }
      double lo, hi;
      this->Field.Bounds(c, p.data(), lo, hi);
      this->Low[c] = std::min(this->Low[c], lo);
      if (hi < this->High[c])
      {
        this->High[c] = hi;
        this->BestSample[c] = static_cast<std::int64_t>(i);
        this->BestPoint[c] = p;
      }
    }
  }

  /// Best first down the samples' tree. Per node and class, a lower bound on every sample of the
  /// node (the distance moves no faster than the point; never below its parent's), or infinity
  /// once the class is set aside higher up; a node is opened while it can still hold a nearer
  /// sample for some class, so a part of the instrument far from every vessel costs one bound.
  void Walk()
  {
    this->Consider(this->S.Root(), NoParent);
    while (!this->Open.empty())
    {
      std::pop_heap(this->Open.begin(), this->Open.end(), std::greater<Opened>());
      const Opened o = this->Open.back();
      this->Open.pop_back();
      bool wanted = false;
      for (int c = 0; c < this->Classes && !wanted; ++c)
      {
        wanted = this->Bounds[o.Bounds + c] < this->Limit(c);
      }
      if (!wanted)
      {
        // Taken by its least bound over the classes; a later one may still serve a class whose
        // best is farther, so go on rather than stop.
        continue;
      }
      const vp::SurfaceSamples::Node& node = this->S.Nodes[o.Node];
      if (node.ChildCount == 0)
      {
        for (std::size_t i = node.First; i < node.First + node.Count; ++i)
        {
          this->Evaluate(i, this->Bounds.data() + o.Bounds);
        }
      }
      for (std::uint32_t j = 0; j < node.ChildCount; ++j)
      {
        this->Consider(this->S.Children[node.FirstChild + j], o.Bounds);
      }
    }
  }

  std::vector<double> Low, High;
  std::vector<std::int64_t> BestSample;
  std::vector<std::array<double, 3>> BestPoint;
  long long Evaluated = 0;

private:
  static constexpr std::size_t NoParent = std::numeric_limits<std::size_t>::max();
  struct Opened
  {
    double Key; // the least bound of the classes it is opened for
    std::uint32_t Node;
    std::size_t Bounds; // its bounds: Bounds[Bounds, Bounds + classes)
    bool operator>(const Opened& o) const { return this->Key != o.Key ? this->Key > o.Key : this->Node > o.Node; }
  };

  /// A node whose bound is not below the least lower bound found is set aside: each of its
  /// samples is truly at least that far (the distance moves no faster than the point), so the
  /// least lower bound stays at or below the instrument's true distance. Which samples are looked
  /// at decides how close below it lies; the interval stays within twice the field's bound: the
  /// sample holding the least lower bound has an upper one at most that much above it.
  double Limit(int c) const { return std::min(this->Low[c], this->RangeMm); }

  /// Bounds node n (parent: where its parent's bounds are) and opens it when some class wants it.
  void Consider(std::uint32_t n, std::size_t parent)
  {
    const vp::SurfaceSamples::Node& node = this->S.Nodes[n];
    const auto centre = Transform(this->M, node.CentreMm);
    const std::size_t at = this->Bounds.size();
    this->Bounds.resize(at + this->Classes, Inf);
    double key = Inf;
    for (int c = 0; c < this->Classes; ++c)
    {
      const double above = parent == NoParent ? 0.0 : this->Bounds[parent + c];
      if (above < this->Limit(c))
      {
        double lo, hi;
        this->Field.Bounds(c, centre.data(), lo, hi);
        const double b = std::max(above, lo - node.RadiusMm);
        this->Bounds[at + c] = b;
        if (b < this->Limit(c))
        {
          key = std::min(key, b);
        }
      }
    }
    if (key < Inf)
    {
      this->Open.push_back({ key, n, at });
      std::push_heap(this->Open.begin(), this->Open.end(), std::greater<Opened>());
    }
    else
    {
      this->Bounds.resize(at);
    }
  }

  const vp::SurfaceSamples& S;
  const vp::CellDistanceField& Field;
  const std::array<double, 16>& M;
  const int Classes;
  const double RangeMm;
  std::vector<double> Bounds;
  std::vector<Opened> Open;
};
} // namespace

struct vtkZBufferSurfaceDistance::Internals
{
  std::shared_ptr<const vp::SurfaceSamples> Samples;
  vtkPolyData* SamplesFrom = nullptr;
  vtkMTimeType SamplesAt = 0;
  double SamplesSpacingMm = 0.0;

  std::shared_ptr<const vp::CellDistanceField> Field;
  vtkZBufferVesselDistance* FieldFrom = nullptr;
  vtkMTimeType FieldAt = 0;
  int FieldRenders = -1;
  double FieldBlockMm = 0.0;
  long long FieldMaxCells = 0;
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
  const vp::DepthLayerGrid grid = this->ZBuffer->GetGrid();
  const double spacing = this->SampleSpacingMm > 0.0 ? this->SampleSpacingMm : 0.5 * grid.PixelMm;
  std::lock_guard<std::mutex> lock(this->BuildLock);
  if (this->Impl->Field)
  {
    return 2.0 * this->Impl->Field->BoundMm() + spacing;
  }
  // Before the field is built: its cells are the layers' (the default size allows 2^26 of them).
  return 2.0 * (grid.ErrorBoundMm() + grid.HalfDiagonalMm() + std::min(grid.PixelMm, grid.SliceMm) / 16.0 + 1e-4) + spacing;
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
  if (this->ZBuffer->GetNumberOfRenders() == 0)
  {
    this->ZBuffer->RenderLayers(); // the field is built from them
  }
  const auto start = std::chrono::steady_clock::now();
  bool worked = false;
  const vp::DepthLayerGrid grid = this->ZBuffer->GetGrid();
  const double spacing = this->SampleSpacingMm > 0.0 ? this->SampleSpacingMm : 0.5 * grid.PixelMm;
  // The samples (one thread) are made while the field is built (the others): they share nothing.
  std::future<std::shared_ptr<const vp::SurfaceSamples>> samples;
  if (!s.Samples || s.SamplesFrom != this->ToolSurface || !this->ToolSurface ||
    s.SamplesAt < this->ToolSurface->GetMTime() || s.SamplesSpacingMm != spacing)
  {
    if (!this->ToolSurface || !this->ToolSurface->GetPoints() || this->ToolSurface->GetNumberOfPolys() == 0)
    {
      throw vp::InputError("scalpel model", "has no surface for the whole-instrument distance");
    }
    auto tool = std::make_shared<const vp::VesselSurface>("scalpel model", this->ToolSurface);
    // Leaves of 2.5 spacings (a handful of samples): a leaf's radius, which widens its bound,
    // is then about a cell. Measured on the demo's 918 poses (bench replay): leaves of 2, 1,
    // 0.5 and 0.25 mm (spacing 0.2) evaluated 17,950, 5,217, 1,418 and 357 samples at p95, and
    // the frame was fastest at 0.5 mm; 0.25 mm built slower and loosened the bound.
    samples = std::async(std::launch::async, [tool, spacing]() {
      return std::make_shared<const vp::SurfaceSamples>(
        vp::SurfaceSamples::Of(tool->PointArray(), tool->TriangleArray(), spacing, 2.5 * spacing));
    });
    worked = true;
  }
  if (!s.Field || s.FieldFrom != this->ZBuffer || s.FieldAt < this->ZBuffer->GetMTime() ||
    s.FieldRenders != this->ZBuffer->GetNumberOfRenders() || s.FieldBlockMm != this->BlockMm ||
    s.FieldMaxCells != this->MaxFieldCells)
  {
    std::vector<std::uint32_t> occupancy, crossings, halves, quarters;
    this->ZBuffer->CopyOccupancy(occupancy);
    this->ZBuffer->CopyCrossings(crossings);              // for the penetration's inside
    this->ZBuffer->CopyCrossingPlaces(halves, quarters); // and its volume's cells at the walls
    s.Field = std::make_shared<const vp::CellDistanceField>(grid, this->ZBuffer->GetNumberOfVessels(), occupancy,
      crossings, halves, quarters, this->MaxFieldCells, this->BlockMm);
    s.FieldFrom = this->ZBuffer;
    s.FieldAt = this->ZBuffer->GetMTime();
    s.FieldRenders = this->ZBuffer->GetNumberOfRenders();
    s.FieldBlockMm = this->BlockMm;
    s.FieldMaxCells = this->MaxFieldCells;
    worked = true;
  }
  if (samples.valid())
  {
    s.Samples = samples.get();
    s.SamplesFrom = this->ToolSurface;
    s.SamplesAt = this->ToolSurface->GetMTime();
    s.SamplesSpacingMm = spacing;
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
  std::shared_ptr<const vp::CellDistanceField> fieldHeld;
  {
    std::lock_guard<std::mutex> lock(this->BuildLock);
    samplesHeld = this->Impl->Samples;
    fieldHeld = this->Impl->Field;
  }
  const vp::SurfaceSamples& S = *samplesHeld;
  const vp::CellDistanceField& field = *fieldHeld;
  const int classes = this->ZBuffer->GetNumberOfVessels();
  const double range = this->RangeMm > 0.0 ? std::min(this->RangeMm, this->ZBuffer->GetRangeMm()) : this->ZBuffer->GetRangeMm();
  NearestSamples search(S, field, m, classes, range);
  // Seeds: the previous frame's closest samples set a tight upper bound before any node.
  if (previous && static_cast<int>(previous->size()) == classes)
  {
    for (const vp::SurfaceProximity& r : *previous)
    {
      if (r.InRange && r.ToolTriangle >= 0 && static_cast<std::size_t>(r.ToolTriangle) < S.Points.size())
      {
        search.Evaluate(static_cast<std::size_t>(r.ToolTriangle), nullptr);
      }
    }
  }
  search.Walk();
  const std::vector<double>& low = search.Low;
  const std::vector<double>& high = search.High;
  const std::vector<std::int64_t>& bestSample = search.BestSample;
  const std::vector<std::array<double, 3>>& bestPoint = search.BestPoint;

  // The samples' least distance is within the spacing above the surface's: the true distance
  // lies in [low - spacing, high]. Reported at its lower end, with the width as its bound: the
  // answer may overstate proximity, never understate it (contact reads 0, as the penetration
  // expects).
  long long submissions = 0;
  out.assign(classes, vp::SurfaceProximity{});
  for (int c = 0; c < classes; ++c)
  {
    vp::SurfaceProximity& r = out[c];
    if (bestSample[c] < 0 || !(low[c] < range))
    {
      r.InRange = false;
      continue;
    }
    r.InRange = true;
    const double lower = std::max(0.0, low[c] - S.SpacingMm);
    r.DistanceMm = lower;
    r.ErrorBoundMm = high[c] - lower;
    const std::array<double, 3>& tool = bestPoint[c];
    double vessel[3];
    if (!field.NearestMarkedPoint(c, tool.data(), vessel))
    {
      // Beyond the field's reach (or stalled on its rounding): the layers say where.
      vtkZBufferVesselDistance::Points one{ tool };
      std::vector<vp::ProximityResult> answer;
      this->ZBuffer->ComputeProximityBatchWithin(one, std::min(range, high[c] + 1.0), answer);
      ++submissions;
      const vp::ClassProximity& a = answer.front().Classes[c];
      for (int k = 0; k < 3; ++k)
      {
        vessel[k] = a.InRange ? a.ClosestPoint[k] : tool[k];
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      r.PointOnToolMm[k] = tool[k];
      r.PointOnVesselMm[k] = vessel[k];
    }
    r.ToolTriangle = bestSample[c];
    r.VesselTriangle = -1;
  }
  this->LastEvaluated = search.Evaluated;
  this->LastSubmissions = submissions;
}

void vtkZBufferSurfaceDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ZBuffer: " << this->ZBuffer.GetPointer() << "\n";
  os << indent << "SampleSpacingMm: " << this->SampleSpacingMm << (this->SampleSpacingMm > 0.0 ? "" : " (half a cell)") << "\n";
  os << indent << "BlockMm: " << this->BlockMm << "\n";
  os << indent << "MaxFieldCells: " << this->MaxFieldCells << "\n";
  os << indent << "Samples: " << this->GetNumberOfSamples() << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
}

std::shared_ptr<const vp::CellDistanceField> vtkZBufferSurfaceDistance::GetDistanceField() const
{
  const_cast<vtkZBufferSurfaceDistance*>(this)->Build();
  std::lock_guard<std::mutex> lock(this->BuildLock);
  return this->Impl->Field;
}

std::size_t vtkZBufferSurfaceDistance::GetFieldMemoryBytes() const
{
  std::lock_guard<std::mutex> lock(this->BuildLock);
  return this->Impl->Field ? this->Impl->Field->MemoryBytes() : 0;
}

int vtkZBufferSurfaceDistance::GetFieldLayerCellsPerCell() const
{
  std::lock_guard<std::mutex> lock(this->BuildLock);
  return this->Impl->Field ? this->Impl->Field->LayerCellsPerCell() : 0;
}
