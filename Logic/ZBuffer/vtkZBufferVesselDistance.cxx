#include "vtkZBufferVesselDistanceInternals.h"

#include "vpClock.h"
#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpQueryState.h"
#include "vpSpatialOrder.h"
#include "vpTriangleGeometry.h"


#include <vtkObjectFactory.h>
#include <vtkSMPThreadLocal.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

vtkStandardNewMacro(vtkZBufferVesselDistance);

using namespace vp::zbuffer;

vtkZBufferVesselDistance::vtkZBufferVesselDistance()
  : Impl(std::make_unique<Internals>())
{
}

vtkZBufferVesselDistance::~vtkZBufferVesselDistance()
{
  this->Impl->Release();
}

void vtkZBufferVesselDistance::Invalidate()
{
  this->Built = false;
  this->Modified();
}

double vtkZBufferVesselDistance::BinWidthMm() const
{
  return this->DistanceBins ? this->RangeMm / this->DistanceBins : 0.0;
}

void vtkZBufferVesselDistance::CheckMovingBox(double cellMm) const
{
  for (int k = 0; k < 3; ++k)
  {
    if (0.5 * this->MovingBoxSizeMm[k] < this->RangeMm + cellMm)
    {
      throw vp::ParameterError("MovingBoxSizeMm", "each half of the moving box must hold the range (" +
          std::to_string(this->RangeMm) + " mm) plus a cell");
    }
  }
}

void vtkZBufferVesselDistance::SetLayerMode(int mode)
{
  if (mode != ExactIntervals && mode != PaperNearFar)
  {
    throw vp::ParameterError("LayerMode", "must be exact or paper");
  }
  // The layers hold both; only the query changes.
  this->LayerMode = mode;
  this->Modified();
}

void vtkZBufferVesselDistance::SetBoxMode(int mode)
{
  if (mode != FixedAroundVessels && mode != MovingWithTip)
  {
    throw vp::ParameterError("BoxMode", "must be fixed or moving");
  }
  if (mode != this->BoxMode)
  {
    this->BoxMode = mode;
    this->Invalidate();
  }
}

void vtkZBufferVesselDistance::SetCellSizeMm(double cellMm)
{
  if (!(cellMm >= vp::limits::MinVoxelMm && cellMm <= vp::limits::MaxVoxelMm))
  {
    throw vp::ParameterError("CellSizeMm", "must be from " + vp::NumberText(vp::limits::MinVoxelMm) + " to " +
        vp::NumberText(vp::limits::MaxVoxelMm) + " millimetres");
  }
  if (cellMm != this->CellSizeMm)
  {
    this->CellSizeMm = cellMm;
    this->Invalidate();
  }
}

void vtkZBufferVesselDistance::SetResolutionPx(int pixels)
{
  if (pixels < 0 || pixels > 16384)
  {
    throw vp::ParameterError("ResolutionPx", "must be between 1 and 16384 pixels (0 for the default cell size)");
  }
  if (pixels != this->ResolutionPx)
  {
    this->ResolutionPx = pixels;
    this->Invalidate();
  }
}

void vtkZBufferVesselDistance::SetMovingBoxSizeMm(double x, double y, double z)
{
  for (double v : { x, y, z })
  {
    if (!(v > 0.0) || !std::isfinite(v))
    {
      throw vp::ParameterError("MovingBoxSizeMm", "must be three positive numbers of millimetres");
    }
  }
  this->MovingBoxSizeMm[0] = x;
  this->MovingBoxSizeMm[1] = y;
  this->MovingBoxSizeMm[2] = z;
  this->Invalidate();
}

void vtkZBufferVesselDistance::SetDistanceBins(int bins)
{
  if (bins < 0 || bins % 16 != 0 || bins > 768)
  {
    throw vp::ParameterError("DistanceBins", "must be 0 (off) or a multiple of 16 up to 768");
  }
  this->DistanceBins = bins;
  this->Modified();
}

void vtkZBufferVesselDistance::SetQueryPass(int pass)
{
  if (pass != QueryPassByDevice && pass != QueryPassPerTile && pass != QueryPassPerPixel)
  {
    throw vp::InputError("query pass", "must be by device, per tile or per pixel");
  }
  this->QueryPass = pass;
  this->Modified();
}

void vtkZBufferVesselDistance::SetTileListing(int listing)
{
  if (listing != TileListingByDevice && listing != TileListingOff && listing != TileListingOn)
  {
    throw vp::InputError("tile listing", "must be by device, off or on");
  }
  this->TileListing = listing; // no Modified(): the answers are the same
}

void vtkZBufferVesselDistance::SetListingPass(int pass)
{
  if (pass != ListingPassByDevice && pass != ListingPassPerWorkgroup && pass != ListingPassPerInvocation &&
    pass != ListingPassOnHost)
  {
    throw vp::InputError("listing pass", "must be by device, per workgroup, per invocation or on the host");
  }
  this->ListingPass = pass; // no Modified(): the answers are the same
}

std::size_t vtkZBufferVesselDistance::GetLastQueryTilesListed() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->LastTilesListed;
}

void vtkZBufferVesselDistance::SetDirectionalLanes(int lanes)
{
  if (lanes < 0 || lanes > 1024)
  {
    throw vp::InputError("directional lanes", "must be between 0 (by device) and 1024");
  }
  this->DirectionalLanes = lanes;
  this->Modified();
}

void vtkZBufferVesselDistance::SetDeviceSelector(const std::string& selector)
{
  if (selector != this->DeviceSelector)
  {
    this->DeviceSelector = selector;
    this->Invalidate();
  }
}

void vtkZBufferVesselDistance::RenderLayers()
{
  this->EnsureBuilt();
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  if (this->Impl->Classes() > 0)
  {
    this->Impl->Render();
  }
}

std::string vtkZBufferVesselDistance::GetDeviceName()
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->Device(this->DeviceSelector).Device().Name;
}

double vtkZBufferVesselDistance::ErrorBoundForCellMm(double cellMm)
{
  vp::DepthLayerGrid grid;
  grid.PixelMm = cellMm;
  grid.SliceMm = cellMm;
  return grid.ErrorBoundMm();
}

double vtkZBufferVesselDistance::GetErrorBoundMm() const
{
  this->EnsureBuilt();
  return this->Impl->Grid.ErrorBoundMm(this->BinWidthMm());
}

vp::DepthLayerGrid vtkZBufferVesselDistance::GetGrid() const
{
  return this->Impl->Grid;
}

int vtkZBufferVesselDistance::GetNumberOfRenders() const
{
  return this->Impl->Renders;
}

double vtkZBufferVesselDistance::GetLastRenderTimeMs() const
{
  return this->Impl->LastRenderMs;
}

std::size_t vtkZBufferVesselDistance::GetBatchCapacity() const
{
  return this->Impl->Capacity;
}

vtkZBufferVesselDistance::CallTimes vtkZBufferVesselDistance::GetLastCallTimes() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->LastCall;
}

double vtkZBufferVesselDistance::GetLastQueryDeviceMs() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->Context && this->Impl->Capacity > 0 ? this->Impl->DeviceMsOf(this->Impl->LastSlot) : -1.0;
}

std::size_t vtkZBufferVesselDistance::GetLastQueryTiles() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->LastTiles;
}

std::size_t vtkZBufferVesselDistance::GetLastQueryTilesInRange() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->LastTilesInRange;
}

double vtkZBufferVesselDistance::GetCeilingBuildTimeMs() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->CeilingBuildMs;
}

void vtkZBufferVesselDistance::BuildQueryCeilings()
{
  this->EnsureBuilt();
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  if (this->QueryCeilings && this->BoxMode == FixedAroundVessels && this->Impl->Rendered)
  {
    this->Impl->PrepareCeilings(true);
  }
}

void vtkZBufferVesselDistance::SetQueryCeilings(bool on)
{
  // No Modified(): no answer changes, and what is built on the layers (the whole instrument's
  // field) must not be built again.
  this->QueryCeilings = on;
}

std::size_t vtkZBufferVesselDistance::GetNumberOfRasterTriangles() const
{
  return this->Impl->RasterTriangles;
}

void vtkZBufferVesselDistance::BuildInternal()
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  Internals& s = *this->Impl;
  vp::VulkanContext& context = s.Device(this->DeviceSelector);
  s.Release();
  if (!context.HasInt64Atomics())
  {
    throw vp::DeviceError("Vulkan device '" + context.Device().Name +
      "' has no 64-bit buffer atomics (shaderBufferInt64Atomics), which the z-buffer query needs to pick its answers");
  }
  s.BuildVotes(this->Surfaces, this->Meshes, this->VoteFieldCellMm, this->RangeMm);
  double cell = 0.0;
  s.Grid = this->PlaceGrid(s.AnchorMm, cell);
  const std::uint32_t classes = static_cast<std::uint32_t>(this->Surfaces.size());
  const VkDeviceSize layerBytes =
    static_cast<VkDeviceSize>(s.Grid.Pixels()) * s.Grid.Words() * 4ull * std::max(classes, 1u);
  if (layerBytes > context.Limits().maxStorageBufferRange)
  {
    throw vp::ParameterError("CellSizeMm/ResolutionPx", "the depth layers would need " + std::to_string(layerBytes >> 20) +
        " MiB, more than the Vulkan device allows in one buffer (" +
        std::to_string(context.Limits().maxStorageBufferRange >> 20) + " MiB); use larger cells");
  }
  s.UploadGeometry(this->Surfaces, cell);
  s.CreateLayers(layerBytes);
  s.Renders = 0; // Release() dropped the ceilings of the renderings before
  if (this->BoxMode != MovingWithTip && classes > 0)
  {
    s.Render();
  }
}

vp::DepthLayerGrid vtkZBufferVesselDistance::PlaceGrid(double anchorMm[3], double& cellMm) const
{
  double bounds[6] = { std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
    -std::numeric_limits<double>::max() };
  for (const auto& surface : this->Surfaces)
  {
    for (int k = 0; k < 3; ++k)
    {
      bounds[2 * k] = std::min(bounds[2 * k], surface->Bounds()[2 * k]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], surface->Bounds()[2 * k + 1]);
    }
  }
  if (this->Surfaces.empty())
  {
    std::fill(bounds, bounds + 6, 0.0);
  }
  for (int k = 0; k < 3; ++k)
  {
    anchorMm[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
  }
  const bool moving = this->BoxMode == MovingWithTip;
  cellMm = this->CellSizeMm;
  if (this->ResolutionPx > 0)
  {
    const double side = moving ? std::max(this->MovingBoxSizeMm[0], this->MovingBoxSizeMm[1])
                               : std::max(bounds[1] - bounds[0], bounds[3] - bounds[2]);
    cellMm = std::max(side, 1e-3) / this->ResolutionPx;
  }
  if (moving)
  {
    this->CheckMovingBox(cellMm);
    return vp::DepthLayerGrid::Centred(anchorMm, this->MovingBoxSizeMm, cellMm, cellMm, anchorMm);
  }
  return vp::DepthLayerGrid::Covering(bounds, cellMm, cellMm, 2.0 * cellMm);
}

void vtkZBufferVesselDistance::ComputeProximity(
  const double tip[3], const double* axis, vp::ProximityResult& result, const vp::ProximityResult*) const
{
  std::vector<vp::ProximityResult> one;
  const Points tips{ { tip[0], tip[1], tip[2] } };
  const Points axes{ { axis ? axis[0] : 0.0, axis ? axis[1] : 0.0, axis ? axis[2] : 0.0 } };
  this->ComputeProximityBatch(tips, axis ? &axes : nullptr, one);
  result = std::move(one.front());
}

void vtkZBufferVesselDistance::ComputeProximityBatch(
  const Points& tips, const Points* axes, std::vector<vp::ProximityResult>& results) const
{
  this->AnswerAll(tips, axes, this->RangeMm, true, true, results);
}

void vtkZBufferVesselDistance::ComputeProximityBatchWithin(
  const Points& points, double searchMm, std::vector<vp::ProximityResult>& results) const
{
  if (this->BoxMode == MovingWithTip)
  {
    throw vp::InputError("box mode", "a search of many points needs the box fixed around the vessels (each point would move the box)");
  }
  this->AnswerAll(points, nullptr, std::min(searchMm, this->RangeMm), false, false, results);
}

namespace
{
/// The largest of fn(begin, end) over [0, count), split as ForEachAnswer splits it.
template <typename Fn>
double MaxOverAnswers(std::size_t count, const Fn& fn)
{
  double all = -std::numeric_limits<double>::infinity();
  ForEachAnswerGathered(
    count, all, [&](std::size_t begin, std::size_t end, double& mine) { mine = std::max(mine, fn(begin, end)); },
    [&](double mine) { all = std::max(all, mine); });
  return all;
}
} // namespace

void vtkZBufferVesselDistance::AnswerAll(const Points& tips, const Points* axes, double searchMm, bool bins,
  bool spaceOrder, std::vector<vp::ProximityResult>& results) const
{
  const std::size_t count = tips.size();
  results.resize(count);
  this->EnsureBuilt(); // before any thread starts
  ForEachAnswer(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      this->BeginResult(tips[i].data(), results[i]);
    }
  });
  const std::array<double, 3>* axis = axes ? axes->data() : nullptr;
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  Internals& s = *this->Impl;
  s.LastCall = CallTimes{};
  const double startMs = vp::NowMs();
  struct Total // the call's time, however it returns
  {
    CallTimes& Times;
    double StartMs;
    ~Total() { this->Times.TotalMs = vp::NowMs() - this->StartMs; }
  } total{ s.LastCall, startMs };
  s.TipQuery = bins;
  s.StampStages = Internals::StampsStages(count);
  const double binWidth = bins ? this->BinWidthMm() : 0.0;
  for (vp::ProximityResult& r : results)
  {
    r.ErrorBoundMm = s.Grid.ErrorBoundMm(binWidth);
  }
  if (s.Classes() == 0 || count == 0)
  {
    return;
  }
  if (this->BoxMode == MovingWithTip)
  {
    this->CheckMovingBox(s.Grid.PixelMm); // the range may have changed since Build()
    for (std::size_t i = 0; i < count; ++i)
    {
      const double* tip = tips[i].data();
      if (!s.Rendered || !s.Grid.ContainsBall(tip, this->RangeMm))
      {
        s.Grid = vp::DepthLayerGrid::Centred(tip, this->MovingBoxSizeMm, s.Grid.PixelMm, s.Grid.SliceMm, s.AnchorMm);
        s.Render();
      }
      this->FinishBatch(this->StartBatch(&tips[i], 1, axis ? axis + i : nullptr, searchMm, binWidth, &results[i], 0));
    }
    return;
  }
  s.PrepareOrder(this->RangeMm);
  if (!spaceOrder || this->BatchOrder == BatchOrderAsGiven || count <= PerPixelMaxTips)
  {
    this->SubmitAll(tips.data(), count, axis, searchMm, binWidth, results.data());
    return;
  }
  // The tips in space order, their results moved along and back (each holds a vector): reading
  // the answers straight into the caller's results, out of order, made the reading slower than
  // the moves (two misses a tip, one waiting on the other).
  const double orderMs = vp::NowMs();
  const std::vector<std::uint32_t> order = vp::SpatialOrder(tips.data(), count, s.Grid.OriginMm, TilePx * s.Grid.PixelMm);
  Points ordered(count), orderedAxes(axis ? count : 0);
  std::vector<vp::ProximityResult> answers(count);
  ForEachAnswer(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      ordered[i] = tips[order[i]];
      if (axis)
      {
        orderedAxes[i] = axis[order[i]];
      }
      answers[i] = std::move(results[order[i]]);
    }
  });
  s.LastCall.OrderMs += vp::NowMs() - orderMs;
  this->SubmitAll(ordered.data(), count, axis ? orderedAxes.data() : nullptr, searchMm, binWidth, answers.data());
  const double backMs = vp::NowMs();
  ForEachAnswer(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      results[order[i]] = std::move(answers[i]);
    }
  });
  s.LastCall.OrderMs += vp::NowMs() - backMs;
}

void vtkZBufferVesselDistance::SubmitAll(const std::array<double, 3>* tips, std::size_t count,
  const std::array<double, 3>* axes, double searchMm, double binWidth, vp::ProximityResult* results) const
{
  Internals& s = *this->Impl;
  const std::size_t capacity = s.Capacity;
  const auto inFlight = static_cast<std::uint32_t>(this->SubmissionsInFlight);
  // With two in flight, each submission is started before the previous one is read: the device
  // works on it while the host reads (and votes on) the one before.
  std::optional<Submission> running;
  std::uint32_t started = 0;
  for (std::size_t first = 0; first < count; first += capacity)
  {
    const std::size_t n = std::min(capacity, count - first);
    const Submission next = this->StartBatch(
      tips + first, n, axes ? axes + first : nullptr, searchMm, binWidth, results + first, started++ % inFlight);
    if (running)
    {
      this->FinishBatch(*running);
    }
    running = next;
    if (inFlight == 1)
    {
      this->FinishBatch(next);
      running.reset();
    }
  }
  if (running)
  {
    this->FinishBatch(*running);
  }
}

void vtkZBufferVesselDistance::SetBatchOrder(int order)
{
  if (order != BatchOrderSpatial && order != BatchOrderAsGiven)
  {
    throw vp::InputError("batch order", "must be BatchOrderSpatial or BatchOrderAsGiven");
  }
  this->BatchOrder = order; // no Modified(): the answers are the same
}

void vtkZBufferVesselDistance::SetSubmissionsInFlight(int submissions)
{
  if (submissions < 1 || submissions > static_cast<int>(vp::VulkanContext::Slots))
  {
    throw vp::InputError("submissions in flight", "must be 1 or 2");
  }
  this->SubmissionsInFlight = submissions; // no Modified(): the answers are the same
}

void vtkZBufferVesselDistance::CopyOccupancy(std::vector<std::uint32_t>& words) const
{
  this->CopyLayer(LayerPlane::Occupancy, words);
}

void vtkZBufferVesselDistance::CopyCrossings(std::vector<std::uint32_t>& words) const
{
  this->CopyLayer(LayerPlane::Crossings, words);
}

void vtkZBufferVesselDistance::CopyCrossingPlaces(std::vector<std::uint32_t>& halves, std::vector<std::uint32_t>& quarters) const
{
  this->CopyLayer(LayerPlane::CrossingHalves, halves);
  this->CopyLayer(LayerPlane::CrossingQuarters, quarters);
}

void vtkZBufferVesselDistance::CopyLayer(LayerPlane plane, std::vector<std::uint32_t>& words) const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  this->Impl->CopyLayer(plane, words);
}

double vtkZBufferVesselDistance::WriteCeilings(
  const std::array<double, 3>* tips, std::size_t count, double searchMm, AnswerCeiling* ceiling) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  const std::uint32_t orderCount = s.FineTable.Within(searchMm);
  constexpr float None = std::numeric_limits<float>::infinity();
  if (!this->QueryCeilings || this->BoxMode != FixedAroundVessels)
  {
    std::fill(ceiling, ceiling + count * classes, AnswerCeiling{ None, orderCount });
    return searchMm;
  }
  const vp::BlockDistanceField* blocks = s.PrepareCeilings();
  constexpr double Unknown = std::numeric_limits<double>::infinity();
  // The device's distances are floats from float coordinates: margins far above their rounding.
  auto above = [](double mm) { return mm * (1.0 + 1e-5) + 1e-3; };
  // The farthest any answer needs to look (none: below 0).
  return MaxOverAnswers(count, [&](std::size_t begin, std::size_t end) {
    double highest = -1.0;
    std::vector<double> lower(classes, -Unknown), upper(classes, Unknown);
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* tip = tips[i].data();
      if (blocks)
      {
        // Random tips each miss the cache: the one a few tips ahead is on its way meanwhile.
        if (i + CeilingPrefetchTips < end)
        {
          blocks->Prefetch(tips[i + CeilingPrefetchTips].data());
        }
        blocks->BoundsMm(tip, lower.data(), upper.data());
      }
      for (std::uint32_t c = 0; c < classes; ++c)
      {
        double bound = upper[c];
        const Internals::LastAnswer& last = s.Last[c];
        if (last.Known)
        {
          bound = std::min(bound, last.CellMm + std::sqrt(vp::Distance2(tip, last.TipMm)));
        }
        bound = above(bound);
        const float mm = bound < searchMm ? std::nextafter(static_cast<float>(bound), None) : None;
        ceiling[i * classes + c] = AnswerCeiling{ mm, std::min(orderCount, s.FineTable.Within(mm)) };
        // A class whose marked cells all lie beyond the search needs no tile (it is out of range,
        // as the tiles would have found): its ceiling does not size the dispatch.
        if (lower[c] <= above(searchMm))
        {
          highest = std::max(highest, std::min(bound, searchMm));
        }
      }
    }
    return highest;
  });
}

vtkZBufferVesselDistance::Submission vtkZBufferVesselDistance::StartBatch(const std::array<double, 3>* tips,
  std::size_t count, const std::array<double, 3>* axes, double searchMm, double binWidth, vp::ProximityResult* results,
  std::uint32_t slot) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  s.PrepareOrder(this->RangeMm);
  s.Context->WaitRecorded(slot); // its buffers are rewritten here (a call that threw may have left it in flight)
  const vp::DepthLayerGrid& g = s.Grid;
  const std::uint32_t orderCount = s.FineTable.Within(searchMm);
  s.WritePoints(tips, count, axes, slot);
  QueryParameters q = MakeQueryParameters(g, searchMm, binWidth, this->DistanceBins, orderCount,
    this->LayerMode == PaperNearFar, classes,
    this->DirectionalLanes > 0 ? this->DirectionalLanes : (s.Context->IsCpuDevice() ? 1 : GpuDirectionalLanes));
  q.OrderReach = s.FineTable.Reach;
  q.CoarseCount = static_cast<std::int32_t>(s.CoarseTable.Within(searchMm));
  q.FirstPoint = static_cast<std::int32_t>(s.FirstPointOf(slot));
  q.AnswerCount = static_cast<std::int32_t>(count * classes);

  // A workgroup per tile: the per-pixel pass needs the device to take that many in one dispatch.
  const std::uint32_t lanes = static_cast<std::uint32_t>(q.DirectionalLanes);
  const std::uint32_t laneGroups = (lanes + 63) / 64;
  const bool perPixel =
    (this->QueryPass == QueryPassPerPixel ||
      (this->QueryPass == QueryPassByDevice && !s.Context->IsCpuDevice() && count <= PerPixelMaxTips)) &&
    orderCount + laneGroups <= s.Context->Limits().maxComputeWorkGroupCount[0];
  const std::uint32_t n = static_cast<std::uint32_t>(count);
  const bool list = this->TileListing != TileListingOff;
  // A few tips are listed on the host: one dispatch then visits their tiles. Listed on the
  // device per workgroup (a few tips' answers on the device's invocations would leave most of a
  // CPU device's threads idle: a single tip on lavapipe 0.43 ms against 0.31) or per invocation.
  bool hostList = list &&
    (this->ListingPass == ListingPassOnHost || (this->ListingPass == ListingPassByDevice && n <= PerPixelMaxTips));
  const double ceilingsMs = vp::NowMs();
  // The host's listing reads the ceilings as written here: memory the device reads may be slow
  // for the host to read back (write-combined on a GPU).
  auto* mapped = static_cast<AnswerCeiling*>(s.Ceilings->Mapped()) + s.FirstPointOf(slot) * classes;
  s.HostCeilings.resize(hostList ? count * classes : 0);
  const double reachMm = this->WriteCeilings(tips, count, searchMm, hostList ? s.HostCeilings.data() : mapped);
  std::copy(s.HostCeilings.begin(), s.HostCeilings.end(), mapped);
  s.LastCall.CeilingsMs += vp::NowMs() - ceilingsMs;
  const std::uint32_t tiles = reachMm < 0.0 ? 0 : std::min(orderCount, s.FineTable.Within(reachMm));
  // The listed tiles are visited per pixel where the order table would be: for a few tips on a
  // GPU, where a workgroup per listed tile is work for every invocation. A batch's listed tiles
  // fill a GPU per tile too, at less of its time (20,000 tips at 1.5M triangles per class on an
  // H100: 3.5 ms per tile, 4.4 ms per pixel; bench's batch passes).
  const bool listPerPixel = this->QueryPass == QueryPassPerPixel ||
    (this->QueryPass == QueryPassByDevice && !s.Context->IsCpuDevice() && n <= PerPixelMaxTips);
  const int listing = list ? (listPerPixel ? 2 : 1) : 0;
  long long hostListed = -1;
  if (hostList)
  {
    const double listingMs = vp::NowMs();
    hostListed = s.ListOnHost(q, tips, count, listPerPixel, slot);
    hostList = hostListed >= 0;
    s.LastCall.ListingMs += vp::NowMs() - listingMs;
  }
  const bool listPerInvocation = list && !hostList &&
    (this->ListingPass == ListingPassPerInvocation ||
      (this->ListingPass == ListingPassByDevice && s.Context->IsCpuDevice() && n > PerPixelMaxTips));
  // Without a list, a batch first visits its near tiles, so that the best falls before the rest
  // start. A list needs no such pass: the ceilings alone leave a few tiles per tip to list
  // (IRCADb patient 1, 0.4 mm cells: 24 of 2,691 per tip, 20 after a near pass of 2 tiles,
  // which made lavapipe no faster).
  const std::uint32_t nearEntries =
    n > PerPixelMaxTips && !list ? std::min(orderCount, s.FineTable.Within(NearTiles * TilePx * g.PixelMm)) : 0;
  auto groups = [](bool pixels, std::uint32_t slots) { return pixels ? slots : (slots + 63) / 64; };
  auto* sizes = static_cast<VkDispatchIndirectCommand*>(s.DispatchSizes->Mapped()) + 2 * slot;
  sizes[0] = { groups(perPixel, std::min(nearEntries, tiles)), classes, n };
  std::uint32_t laneSlots = 0;
  // A host's list: ListOnHost sized the visit.
  if (list && !hostList)
  {
    // The listing's workgroups per answer: one for a batch (its answers fill the device) and on
    // a CPU device (which runs them one after another anyway); for a few tips on a GPU enough
    // that no invocation loops over more than 4 coarse tiles.
    const bool one = n > PerPixelMaxTips || s.Context->IsCpuDevice();
    const std::uint32_t coarse = reachMm < 0.0 ? 0 : s.CoarseTable.Within(reachMm);
    sizes[1] = listPerInvocation ? VkDispatchIndirectCommand{ (n * classes + 63) / 64, 1, 1 }
                                 : VkDispatchIndirectCommand{ one ? 1u : std::max(1u, (coarse + 255) / 256), classes, n };
  }
  else if (!list)
  {
    // Lanes first in the last dispatch over the order table: invocations per tile, workgroups
    // per pixel.
    laneSlots = perPixel ? laneGroups : lanes;
    sizes[1] = { groups(perPixel, laneSlots + (tiles > nearEntries ? tiles - nearEntries : 0)), classes, n };
  }
  s.LastTiles = tiles * classes;
  s.LastTilesInRange = orderCount * classes;
  const double submitMs = vp::NowMs();
  s.PreparedQueryFor(q, n, slot, perPixel, listing, listPerInvocation, hostList, s.StampStages, nearEntries, laneSlots)
    .Start(slot);
  s.LastCall.SubmitWaitMs += vp::NowMs() - submitMs;
  ++s.LastCall.Submissions;
  return Submission{ tips, count, axes != nullptr, searchMm, q.Bins, binWidth, results, slot, hostListed };
}

void vtkZBufferVesselDistance::FinishBatch(const Submission& batch) const
{
  Internals& s = *this->Impl;
  const double waitMs = vp::NowMs();
  s.Context->WaitRecorded(batch.Slot);
  s.LastCall.SubmitWaitMs += vp::NowMs() - waitMs;
  s.LastSlot = batch.Slot;
  s.AddDeviceMs(s.LastCall, batch.Slot); // the stamps it copied
  // The device's count: the first answer's word 7 (ReduceProximity.comp).
  s.LastTilesListed = batch.HostListed >= 0 ? static_cast<std::uint32_t>(batch.HostListed) : s.AnswersOf(batch.Slot)[7];
  s.LastCall.TilesListed += s.LastTilesListed;
  const double readMs = vp::NowMs(), votesBeforeMs = s.LastCall.VotesMs;
  this->ReadAnswers(batch);
  s.LastCall.ReadMs += vp::NowMs() - readMs - (s.LastCall.VotesMs - votesBeforeMs);
}

void vtkZBufferVesselDistance::ReadAnswers(const Submission& batch) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  const vp::DepthLayerGrid& g = s.Grid;
  const std::array<double, 3>* tips = batch.Tips;
  const std::size_t count = batch.Count;
  const bool axes = batch.Axes;
  const double searchMm = batch.SearchMm;
  const int bins = batch.Bins;
  const double binWidth = batch.BinWidthMm;
  vp::ProximityResult* results = batch.Results;
  const std::uint32_t* hostState = s.AnswersOf(batch.Slot);
  // What the answers still need once read, gathered per thread: a vote on a surface that is not
  // closed, or their answer beyond the range. No pass over every answer runs on one thread: on
  // an H100's host such a pass (a millisecond per 20,000 tips) had been most of a batch's reading.
  struct Remaining
  {
    std::vector<InsideVote> Votes;
    std::vector<std::pair<std::size_t, std::uint32_t>> Beyond; // (tip, class)
    bool Deep = false; // whether one of them needs the exact engine of every class
  };
  std::vector<InsideVote> votes;
  std::vector<std::pair<std::size_t, std::uint32_t>> beyond;
  bool deep = false;
  auto read = [&](std::size_t begin, std::size_t end, Remaining& mine) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* tip = tips[i].data();
      for (std::uint32_t c = 0; c < classes; ++c)
      {
        vp::ClassProximity& out = results[i].Classes[c];
        const std::uint32_t* cs = hostState + (i * classes + c) * StateStride;
        const float directional = Bits(cs[2]);
        if (axes && std::isfinite(directional) && directional <= searchMm)
        {
          out.DirectionalMm = directional;
        }
        const double cellMm = ChosenCellMm(cs);
        const double distance = cellMm <= searchMm ? ReportedDistanceMm(cs, cellMm, g.HalfDiagonalMm(), bins, binWidth) : 0.0;
        if (!(cellMm <= searchMm) || distance > this->RangeMm)
        {
          mine.Beyond.emplace_back(i, c);
          mine.Deep = mine.Deep || (s.TipQuery && s.ExactIndex[c] < 0 && cs[1] != 0u);
          continue;
        }
        out.InRange = true;
        // On a surface that is not closed the one ray's parity is no answer (an opening it passes
        // through turns it): the exact engine's vote over five rays decides there.
        if (this->Surfaces[c]->IsClosed())
        {
          out.Inside = cs[1] != 0u;
        }
        else
        {
          mine.Votes.push_back({ i, c, cellMm + g.HalfDiagonalMm() });
        }
        out.DistanceMm = distance;
        ClosestPointInChosenCell(g, tip, cs, out.ClosestPoint);
        out.TriangleId = -1;
      }
    }
  };
  ForEachAnswerGathered(count, Remaining{}, read, [&](const Remaining& part) {
    votes.insert(votes.end(), part.Votes.begin(), part.Votes.end());
    beyond.insert(beyond.end(), part.Beyond.begin(), part.Beyond.end());
    deep = deep || part.Deep;
  });
  // Each class's last answer with a cell: that cell stays marked until the next rendering, so no
  // later answer is farther than it (the next ceilings).
  for (std::uint32_t c = 0; c < classes && c < s.Last.size(); ++c)
  {
    for (std::size_t i = count; i-- > 0;)
    {
      const double cellMm = ChosenCellMm(hostState + (i * classes + c) * StateStride);
      if (cellMm <= searchMm)
      {
        Internals::LastAnswer& last = s.Last[c];
        last.Known = true;
        std::copy(tips[i].data(), tips[i].data() + 3, last.TipMm);
        last.CellMm = cellMm;
        break;
      }
    }
  }
  if (deep)
  {
    this->EnsureDeepEngine(); // before any thread starts
  }
  ForEachAnswer(beyond.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const auto [i, c] = beyond[k];
      const std::uint32_t* cs = hostState + (i * classes + c) * StateStride;
      this->AnswerBeyondRange(c, tips[i].data(), cs[1] != 0u, results[i].Classes[c]);
    }
  });
  s.VoteInside(votes, tips, results);
}

void vtkZBufferVesselDistance::AnswerBeyondRange(
  std::uint32_t c, const double tip[3], bool centreRayInside, vp::ClassProximity& out) const
{
  // As the exact engine: no wall within the range is no distance, unless the tip is inside, which
  // is a breach however far the wall. An open surface is voted on (its exact engine is at hand);
  // on a closed one the tip's own ray says it, and an exact engine, made the first time a tip is
  // that deep, measures the depth.
  Internals& s = *this->Impl;
  out.InRange = false;
  if (!s.TipQuery)
  {
    return; // the whole instrument's search asks only what lies within its distance
  }
  if (s.ExactIndex[c] >= 0)
  {
    s.Votes->FindDepthBeyondRange(s.ExactIndex[c], tip, out);
    return;
  }
  if (!centreRayInside)
  {
    return;
  }
  this->EnsureDeepEngine();
  s.Deep->FindDepthBeyondRange(static_cast<int>(c), tip, out);
}

void vtkZBufferVesselDistance::EnsureDeepEngine() const
{
  Internals& s = *this->Impl;
  if (!s.Deep)
  {
    s.Deep = vtkSmartPointer<vtkExactVesselDistance>::New();
    for (const auto& [name, mesh] : this->Meshes)
    {
      s.Deep->AddVessel(name, mesh);
    }
    s.Deep->Build();
  }
}

void vtkZBufferVesselDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LayerMode: " << (this->LayerMode == PaperNearFar ? "PaperNearFar" : "ExactIntervals") << "\n";
  os << indent << "BoxMode: " << (this->BoxMode == MovingWithTip ? "MovingWithTip" : "FixedAroundVessels") << "\n";
  os << indent << "CellSizeMm: " << this->CellSizeMm << "\n";
  os << indent << "ResolutionPx: " << this->ResolutionPx << "\n";
  os << indent << "MovingBoxSizeMm: " << this->MovingBoxSizeMm[0] << " x " << this->MovingBoxSizeMm[1] << " x "
     << this->MovingBoxSizeMm[2] << "\n";
  os << indent << "DistanceBins: " << this->DistanceBins << "\n";
  os << indent << "QueryPass: "
     << (this->QueryPass == QueryPassPerTile ? "PerTile" : this->QueryPass == QueryPassPerPixel ? "PerPixel" : "(by device)")
     << "\n";
  os << indent << "TileListing: "
     << (this->TileListing == TileListingOff ? "Off" : this->TileListing == TileListingOn ? "On" : "(by device)") << "\n";
  os << indent << "ListingPass: "
     << (this->ListingPass == ListingPassPerWorkgroup ? "PerWorkgroup"
           : this->ListingPass == ListingPassPerInvocation ? "PerInvocation" : "(by device)")
     << "\n";
  os << indent << "DirectionalLanes: " << this->DirectionalLanes << (this->DirectionalLanes ? "" : " (by device)") << "\n";
  os << indent << "SubmissionsInFlight: " << this->SubmissionsInFlight << "\n";
  os << indent << "BatchOrder: " << (this->BatchOrder == BatchOrderAsGiven ? "AsGiven" : "Spatial") << "\n";
  os << indent << "VoteFieldCellMm: " << this->VoteFieldCellMm << (this->VoteFieldCellMm > 0.0 ? "" : " (none)") << "\n";
  os << indent << "DeviceSelector: " << (this->DeviceSelector.empty() ? "(best)" : this->DeviceSelector) << "\n";
  const vp::DepthLayerGrid& g = this->Impl->Grid;
  os << indent << "Grid: " << g.Nx << " x " << g.Ny << " x " << g.Nz << " cells of " << g.PixelMm << " x "
     << g.PixelMm << " x " << g.SliceMm << " mm\n";
  os << indent << "Renders: " << this->Impl->Renders << " (last " << this->Impl->LastRenderMs << " ms)\n";
}
