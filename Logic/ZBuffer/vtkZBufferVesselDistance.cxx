#include "vtkZBufferVesselDistance.h"

#include "vpBlockDistanceField.h"
#include "vpComputeKernel.h"
#include "vpEdgeSplitting.h"
#include "vpGpuBuffer.h"
#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpPreparedCommands.h"
#include "vpTriangleGeometry.h"
#include "vpVulkanContext.h"
#include "vtkExactVesselDistance.h"

#include "QueryProximityPerPixel_comp_spv.h"
#include "QueryProximity_comp_spv.h"
#include "RasterizeLayers_comp_spv.h"
#include "ReduceProximity_comp_spv.h"
#include "SummarizeColumns_comp_spv.h"
#include "SummarizeTiles_comp_spv.h"

#include <vtkObjectFactory.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <vector>

vtkStandardNewMacro(vtkZBufferVesselDistance);

namespace
{
constexpr std::uint32_t StateStride = 32; // words per class in the query state, as in the shader
// Triangles are split until no edge is longer than this many cells, which bounds the pixels one
// rasteriser invocation visits (and so the longest invocation).
constexpr double MaxEdgeCells = 4.0;

// Push constant blocks, laid out as the shaders declare them.
struct RasterParameters
{
  float Origin[3];
  float InvPixelMm;
  float InvSliceMm;
  std::int32_t Nx, Ny, Nz, Words;
  std::uint32_t Class, FirstTriangle, TriangleCount;
};
static_assert(sizeof(RasterParameters) == 48, "push constant layout of RasterizeLayers.comp");

struct ColumnParameters
{
  std::uint32_t Pixels, Classes, Words, RangeStride;
};

struct TileParameters
{
  std::int32_t Nx, Ny, TilesX, TilesY;
  std::uint32_t Classes, RangeStride;
  std::int32_t TilePx;
  std::uint32_t Offset;
};

// Tiles per coarse tile along x and y, as CoarseTiles in QueryProximityCommon.glsl.
constexpr int CoarseTiles = 4;

int CoarseAcross(int tiles)
{
  return (tiles + CoarseTiles - 1) / CoarseTiles;
}

// Offsets from a centre tile, nearest first: by the least distance from any point of the centre
// tile (the square root of the first of the pair, in tiles), then from the centre. Reach: the
// tiles within rangeMm, and no more than the grid is wide (so --range 1e9 asks for no more);
// GapMm: each offset's least distance, ascending, so that a shorter search needs a prefix.
struct TileOrder
{
  std::vector<std::array<std::int32_t, 2>> Offsets;
  std::vector<double> GapMm;
  int Reach = 0;

  // The entries within searchMm of any tip in the centre tile: a prefix of the table.
  std::uint32_t Within(double searchMm) const
  {
    return static_cast<std::uint32_t>(std::upper_bound(this->GapMm.begin(), this->GapMm.end(), searchMm) - this->GapMm.begin());
  }
};

TileOrder NearestFirst(double rangeMm, double edgePx, double pixelMm, int tilesAcross)
{
  TileOrder order;
  order.Reach = static_cast<int>(std::min(std::ceil(rangeMm / (edgePx * pixelMm)) + 1.0, static_cast<double>(tilesAcross)));
  for (int dy = -order.Reach; dy <= order.Reach; ++dy)
  {
    for (int dx = -order.Reach; dx <= order.Reach; ++dx)
    {
      order.Offsets.push_back({ dx, dy });
    }
  }
  auto gap = [](const std::array<std::int32_t, 2>& o) {
    const int gx = std::max(0, std::abs(o[0]) - 1), gy = std::max(0, std::abs(o[1]) - 1);
    return std::make_pair(gx * gx + gy * gy, o[0] * o[0] + o[1] * o[1]);
  };
  std::stable_sort(
    order.Offsets.begin(), order.Offsets.end(), [&](const auto& a, const auto& b) { return gap(a) < gap(b); });
  for (const auto& o : order.Offsets)
  {
    order.GapMm.push_back(std::sqrt(static_cast<double>(gap(o).first)) * edgePx * pixelMm);
  }
  return order;
}

struct QueryParameters
{
  float PixelMm;
  float SliceMm;
  float RangeMm;
  float HalfDiagonalMm;
  float BinWidthMm;
  std::int32_t Bins, Nx, Ny, Nz, Words, TilesX, TilesY, OrderCount, PaperMode;
  std::uint32_t RangeStride;
  std::int32_t Classes;
  std::int32_t DirectionalLanes;
  std::int32_t FirstEntry, EndEntry;
  std::int32_t LaneSlots;
  std::int32_t Stage, TilesPerGroup;
  std::int32_t OrderReach, CoarseCount;
};
static_assert(sizeof(QueryParameters) == 96, "push constant layout of QueryProximity.comp");

// Lanes that share the directional walk on a GPU (see QueryProximity.comp).
constexpr std::int32_t GpuDirectionalLanes = 64;
// Submissions of up to this many tips take the per-pixel pass over the order table on a GPU;
// larger ones list their tiles first (SetTileListing) and visit the listed ones per pixel.
// Measured on an H100 before the list: one tip 0.025 ms on the device per pixel, 0.042 per tile;
// 1,000 tips 1.95 ms per pixel, 0.57 per tile (the per-pixel pass paid a workgroup for every tile
// of the order table, nearly all of which it then skipped: the list leaves only the others).
constexpr std::uint32_t PerPixelMaxTips = 8;
// A larger batch without a list first visits, for every tip, the tiles within this many tiles of its own: on a
// GPU all of a dispatch's tiles run at once, so a far tile would start before a near one had
// lowered the best; after this first dispatch most far tiles are skipped at once.
constexpr double NearTiles = 2.0;
// The query's stages (QueryProximityCommon.glsl).
constexpr std::int32_t VisitOrderedTiles = 0, SelectTiles = 1, VisitListedTiles = 2;
// Tips per submission: as many as the records of a batch allow within RecordBudgetBytes, and at
// most these (a CPU device answers a batch's tips one after another: larger batches only cost
// memory there; a GPU answers them side by side, so larger batches spread a submission's fixed
// cost over more tips).
constexpr std::uint32_t CpuBatchCapacity = 256;
constexpr std::uint32_t GpuBatchCapacity = 4096;
constexpr VkDeviceSize RecordBudgetBytes = 256ull << 20;

struct ReduceParameters
{
  std::uint32_t Step, Answers, OrderCount;
};

/// What a query writes per point: the tip in grid units, then the unit axis (QueryProximity.comp).
struct PointRecord
{
  float Tip[4];
  float Axis[4];
};
static_assert(sizeof(PointRecord) == 32, "Points layout of QueryProximity.comp");

/// Per point and class, the answer's ceiling and the order table's entries within it (Ceilings
/// in QueryProximityCommon.glsl).
struct AnswerCeiling
{
  float Mm;
  std::uint32_t Entries;
};
static_assert(sizeof(AnswerCeiling) == 8, "Ceilings layout of QueryProximity.comp");

float Bits(std::uint32_t u)
{
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

QueryParameters MakeQueryParameters(const vp::DepthLayerGrid& g, double searchMm, double binWidth, int bins,
  std::uint32_t orderCount, bool paper, std::uint32_t classes, int directionalLanes)
{
  QueryParameters q{};
  q.PixelMm = static_cast<float>(g.PixelMm);
  q.SliceMm = static_cast<float>(g.SliceMm);
  q.RangeMm = static_cast<float>(searchMm);
  q.HalfDiagonalMm = static_cast<float>(g.HalfDiagonalMm());
  q.BinWidthMm = static_cast<float>(binWidth);
  q.Bins = binWidth > 0.0 ? bins : 0;
  q.Nx = g.Nx;
  q.Ny = g.Ny;
  q.Nz = g.Nz;
  q.Words = g.Words();
  q.TilesX = g.TilesX();
  q.TilesY = g.TilesY();
  q.OrderCount = static_cast<std::int32_t>(orderCount);
  q.PaperMode = paper ? 1 : 0;
  q.RangeStride = static_cast<std::uint32_t>(g.Pixels()) * classes;
  q.Classes = static_cast<std::int32_t>(classes);
  q.DirectionalLanes = directionalLanes;
  return q;
}

double Clamp(double x, double lo, double hi)
{
  return std::min(std::max(x, lo), hi);
}

// A point and class's answer, as the query leaves it in its State words (QueryProximityCommon.glsl):
// [1] the ray's parity, [2] the directional distance, [3] the chosen record (all ones: none within
// the search), [4] its cell's distance, [5] its pixel, [6] its depth in slices, [8...] the
// paper's distance bits.

/// The chosen cell's distance, mm; infinite when nothing lies within the search.
double ChosenCellMm(const std::uint32_t* state)
{
  return state[3] == 0xFFFFFFFFu ? std::numeric_limits<double>::infinity() : Bits(state[4]);
}

/// The distance the answer reports: the nearest marked cell is at most a cell diagonal nearer
/// than the surface it holds, so its distance plus half a diagonal is within half a diagonal of
/// the truth; with the paper's bits on, the middle of the first bin set instead.
double ReportedDistanceMm(const std::uint32_t* state, double cellMm, double halfDiagonalMm, int bins, double binWidthMm)
{
  for (int bin = 0; bin < bins; ++bin)
  {
    if (state[8 + bin / 32] & (1u << (bin % 32)))
    {
      return (bin + 0.5) * binWidthMm;
    }
  }
  return cellMm + halfDiagonalMm;
}

/// The point of the chosen cell nearest the tip across its pixel, at the cell's depth.
void ClosestPointInChosenCell(const vp::DepthLayerGrid& g, const double* tip, const std::uint32_t* state, double point[3])
{
  const std::uint32_t pixel = state[5];
  const int px = static_cast<int>(pixel % static_cast<std::uint32_t>(g.Nx));
  const int py = static_cast<int>(pixel / static_cast<std::uint32_t>(g.Nx));
  point[0] = Clamp(tip[0], g.OriginMm[0] + px * g.PixelMm, g.OriginMm[0] + (px + 1) * g.PixelMm);
  point[1] = Clamp(tip[1], g.OriginMm[1] + py * g.PixelMm, g.OriginMm[1] + (py + 1) * g.PixelMm);
  point[2] = g.OriginMm[2] + Bits(state[6]) * g.SliceMm;
}

/// An inside answer the exact engine's vote decides: on a surface that is not closed.
struct InsideVote
{
  std::size_t Tip;
  std::uint32_t Class;
  double DistanceMm;
};
} // namespace

struct vtkZBufferVesselDistance::Internals
{
  std::mutex Lock;
  std::unique_ptr<vp::VulkanContext> Context;
  std::string ContextSelector;

  // Geometry, uploaded once per Build().
  double AnchorMm[3] = { 0, 0, 0 };
  std::vector<std::uint32_t> FirstTriangle, TriangleCount;
  std::size_t RasterTriangles = 0;
  std::unique_ptr<vp::GpuBuffer> Positions, Indices;

  // Layers.
  vp::DepthLayerGrid Grid;
  bool Rendered = false;
  int Renders = 0;
  double LastRenderMs = 0.0;
  std::unique_ptr<vp::GpuBuffer> Occupancy, Crossings, DepthRanges, TileRanges;

  // Query.
  double OrderRangeMm = -1.0;
  std::uint32_t OrderCount = 0;
  // The order table of tiles and that of coarse tiles, as uploaded (their gaps say which
  // entries a search needs).
  TileOrder FineTable, CoarseTable;
  std::unique_ptr<vp::GpuBuffer> Order, State, Choices, Records, HostState, Points;
  // The coarse tiles' order table and each offset's entry in the order table (see CoarseOrder in
  // QueryProximityCommon.glsl).
  std::unique_ptr<vp::GpuBuffer> CoarseOrder, EntryIndex;
  // Per point and class the answer's ceiling (mm), and the sizes of the query's two dispatches
  // (VkDispatchIndirectCommand: the near tiles of a batch, then the lanes and the rest), written
  // by the host before every submission.
  std::unique_ptr<vp::GpuBuffer> Ceilings, DispatchSizes;
  // The tiles a submission lists, and the list's size with the workgroup counts of the
  // dispatch that visits them (written by the device; see TileList in the shaders).
  std::unique_ptr<vp::GpuBuffer> TileList, TileListSize;
  // The ceilings' sources: the coarse blocks of the current rendering, and per class the latest
  // answer (tip, and the distance to its nearest marked cell) on the rendering it was made on.
  std::unique_ptr<vp::BlockDistanceField> CeilingBlocks;
  int CeilingBlocksRender = -1;
  double CeilingBuildMs = 0.0;
  struct LastAnswer
  {
    bool Known = false;
    double TipMm[3] = { 0, 0, 0 };
    double CellMm = 0.0;
  };
  std::vector<LastAnswer> Last;
  int LastRender = -1;
  int SubmissionsOnRender = 0;
  std::uint32_t LastTiles = 0, LastTilesInRange = 0, LastTilesListed = 0;
  // Tips per submission for the current order table (PrepareOrder).
  std::uint32_t Capacity = 0;

  std::unique_ptr<vp::ComputeKernel> Raster, Columns, Tiles, Query, QueryPerPixel, Reduce;
  // The query's submissions, each recorded once for one batch size and one set of parameters
  // (the whole instrument's search asks for a few ranges and sizes again and again).
  struct PreparedQuery
  {
    std::uint32_t Points = 0;
    bool PerPixel = false;
    int Listing = 0; // 0: no list; 1: listed tiles visited per tile; 2: per pixel
    QueryParameters Parameters{};
    std::unique_ptr<vp::PreparedCommands> Commands;
  };
  std::vector<PreparedQuery> Prepared;
  // The classes whose surface is not closed, in an exact engine of their own: their inside is its
  // vote (one ray along +z cannot vote), and ExactIndex maps a class to its place there (-1: closed).
  vtkSmartPointer<vtkExactVesselDistance> Votes;
  std::vector<int> ExactIndex;
  // Every class in an exact engine, made when a tip is first found deeper inside a closed class
  // than the range reaches (AnswerBeyondRange); none until then.
  vtkSmartPointer<vtkExactVesselDistance> Deep;
  // Whether the answers being read are tips' (ComputeProximityBatch), whose inside counts however
  // deep, or the whole instrument's points within a search distance.
  bool TipQuery = true;
  static constexpr std::size_t MaxPrepared = 64;

  // The votes run on the host, five rays each: a batch's on all cores (Embree's queries are
  // thread-safe), so that a batch on a defective surface does not wait for them one by one.
  void VoteInside(const std::vector<InsideVote>& votes, const std::array<double, 3>* tips, vp::ProximityResult* results) const
  {
    auto vote = [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType k = begin; k < end; ++k)
      {
        const InsideVote& v = votes[static_cast<std::size_t>(k)];
        vp::ClassProximity& out = results[v.Tip].Classes[v.Class];
        out.Inside = this->Votes->VoteInside(this->ExactIndex[v.Class], tips[v.Tip].data(), v.DistanceMm, out.InsideUncertain);
      }
    };
    if (votes.size() >= 64)
    {
      vtkSMPTools::For(0, static_cast<vtkIdType>(votes.size()), vote);
    }
    else
    {
      vote(0, static_cast<vtkIdType>(votes.size()));
    }
  }

  vp::VulkanContext& Device(const std::string& selector)
  {
    if (!this->Context || this->ContextSelector != selector)
    {
      this->Release();
      this->Context.reset();
      this->Context = std::make_unique<vp::VulkanContext>(selector);
      this->ContextSelector = selector;
    }
    return *this->Context;
  }

  void Release()
  {
    this->Prepared.clear(); // before the buffers and kernels it names
    this->Raster.reset();
    this->Columns.reset();
    this->Tiles.reset();
    this->Query.reset();
    this->QueryPerPixel.reset();
    this->Reduce.reset();
    this->Points.reset();
    this->Positions.reset();
    this->Indices.reset();
    this->Occupancy.reset();
    this->Crossings.reset();
    this->DepthRanges.reset();
    this->TileRanges.reset();
    this->Order.reset();
    this->CoarseOrder.reset();
    this->EntryIndex.reset();
    this->State.reset();
    this->Choices.reset();
    this->Records.reset();
    this->HostState.reset();
    this->Ceilings.reset();
    this->DispatchSizes.reset();
    this->TileList.reset();
    this->TileListSize.reset();
    this->CeilingBlocks.reset();
    this->CeilingBlocksRender = -1;
    this->CeilingBuildMs = 0.0;
    this->Last.clear();
    this->LastRender = -1;
    this->Rendered = false;
    this->OrderRangeMm = -1.0;
    this->Capacity = 0;
  }

  std::uint32_t Classes() const { return static_cast<std::uint32_t>(this->FirstTriangle.size()); }

  // The occupancy or the crossings, copied to the host (lock held).
  void CopyLayer(bool crossings, std::vector<std::uint32_t>& words)
  {
    words.clear();
    const vp::GpuBuffer* layer = crossings ? this->Crossings.get() : this->Occupancy.get();
    if (!this->Rendered || !layer)
    {
      return;
    }
    const VkDeviceSize bytes = layer->Size();
    vp::GpuBuffer host(*this->Context, bytes, vp::GpuBuffer::Placement::Host);
    this->Context->Submit([&](VkCommandBuffer cmd) {
      VkBufferCopy region{ 0, 0, bytes };
      vkCmdCopyBuffer(cmd, layer->Handle(), host.Handle(), 1, &region);
      vp::ComputeKernel::Barrier(cmd);
    });
    words.resize(static_cast<std::size_t>(bytes / 4));
    std::memcpy(words.data(), host.Mapped(), words.size() * 4);
  }

  // The ceilings' blocks for the current rendering, and no answer remembered from an older one.
  // None for a rendering's first submission: a one-shot query (`distance --tip`) does not wait
  // the tenths of a second they take on large layers.
  const vp::BlockDistanceField* PrepareCeilings(bool now = false)
  {
    if (this->LastRender != this->Renders)
    {
      this->Last.assign(this->Classes(), LastAnswer{});
      this->LastRender = this->Renders;
      this->SubmissionsOnRender = 0;
    }
    if (this->CeilingBlocks && this->CeilingBlocksRender == this->Renders)
    {
      return this->CeilingBlocks.get();
    }
    if (this->SubmissionsOnRender++ == 0 && !now)
    {
      return nullptr;
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> occupancy;
    this->CopyLayer(false, occupancy);
    // Blocks of 4 cells, at least 1.6 mm: about a 64th of the cells (a few MB at 0.4 mm), and
    // the bound a few millimetres above the truth, which leaves a tip a few hundred tiles of
    // a 50 mm range's thousands.
    this->CeilingBlocks = std::make_unique<vp::BlockDistanceField>(
      this->Grid, static_cast<int>(this->Classes()), occupancy, std::max(1.6, 4.0 * this->Grid.PixelMm));
    this->CeilingBlocksRender = this->Renders;
    this->CeilingBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return this->CeilingBlocks.get();
  }

  // Each tip in grid units and its unit axis (or zero), where the query reads them.
  void WritePoints(const std::array<double, 3>* tips, std::size_t count, const std::array<double, 3>* axes)
  {
    const vp::DepthLayerGrid& g = this->Grid;
    auto* points = static_cast<PointRecord*>(this->Points->Mapped());
    for (std::size_t i = 0; i < count; ++i)
    {
      const double* tip = tips[i].data();
      PointRecord& p = points[i];
      p = PointRecord{};
      p.Tip[0] = static_cast<float>((tip[0] - g.OriginMm[0]) / g.PixelMm);
      p.Tip[1] = static_cast<float>((tip[1] - g.OriginMm[1]) / g.PixelMm);
      p.Tip[2] = static_cast<float>((tip[2] - g.OriginMm[2]) / g.SliceMm);
      if (axes)
      {
        const double* axis = axes[i].data();
        const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
        for (int k = 0; k < 3 && n > 0.0; ++k)
        {
          p.Axis[k] = static_cast<float>(axis[k] / n);
        }
      }
    }
  }

  // The query's submission for these parameters, batch size and passes, recorded once: the two
  // dispatches over the order table (their sizes read from DispatchSizes when it runs), then the
  // answers. With a list (listing 1: visited per tile, 2: per pixel), the second dispatch lists
  // the tiles it would have visited and a third, sized by the device, visits them.
  vp::PreparedCommands& PreparedQueryFor(const QueryParameters& q, std::uint32_t n, bool perPixel, int listing,
    std::uint32_t nearEntries, std::uint32_t laneSlots)
  {
    const std::uint32_t orderCount = static_cast<std::uint32_t>(q.OrderCount);
    auto prepared = std::find_if(this->Prepared.begin(), this->Prepared.end(), [&](const PreparedQuery& p) {
      return p.Points == n && p.PerPixel == perPixel && p.Listing == listing &&
        std::memcmp(&p.Parameters, &q, sizeof q) == 0;
    });
    if (prepared == this->Prepared.end())
    {
      if (this->Prepared.size() >= MaxPrepared)
      {
        this->Prepared.clear();
      }
      const std::uint32_t answers = n * this->Classes();
      const ReduceParameters copy{ 1, answers, orderCount };
      PreparedQuery entry;
      entry.Points = n;
      entry.PerPixel = perPixel;
      entry.Listing = listing;
      entry.Parameters = q;
      entry.Commands = std::make_unique<vp::PreparedCommands>(*this->Context, [&](VkCommandBuffer cmd) {
        this->Context->ResetStamps(cmd);
        this->Context->Stamp(cmd, 0);
        // Entries: a workgroup per tile (per pixel) or an invocation per tile (per tile); the
        // lanes come first in the last dispatch, whose size after them follows the ceilings.
        auto visit = [&](std::int32_t stage, bool pixels, std::uint32_t first, std::uint32_t last, std::uint32_t slots,
                       const vp::GpuBuffer& sizes, VkDeviceSize sizesAt) {
          QueryParameters part = q;
          part.FirstEntry = static_cast<std::int32_t>(first);
          part.EndEntry = static_cast<std::int32_t>(last);
          part.LaneSlots = static_cast<std::int32_t>(slots);
          part.Stage = stage;
          part.TilesPerGroup = listing == 2 ? 1 : 64;
          (pixels ? *this->QueryPerPixel : *this->Query).RecordIndirect(cmd, &part, sizes.Handle(), sizesAt);
          vp::ComputeKernel::Barrier(cmd);
        };
        const VkDeviceSize second = sizeof(VkDispatchIndirectCommand);
        if (nearEntries > 0)
        {
          visit(VisitOrderedTiles, perPixel, 0, nearEntries, 0, *this->DispatchSizes, 0);
        }
        if (listing == 0)
        {
          visit(VisitOrderedTiles, perPixel, nearEntries, orderCount, laneSlots, *this->DispatchSizes, second);
        }
        else
        {
          // The listing: workgroups per answer (DispatchSizes' second), each looping over its
          // share of the answer's lanes and entries.
          visit(SelectTiles, false, nearEntries, orderCount, 0, *this->DispatchSizes, second);
          visit(VisitListedTiles, listing == 2, 0, 0, 0, *this->TileListSize, 4);
        }
        this->Reduce->Record(cmd, &copy, (answers + 63) / 64); // into the host-visible answers, and resets
        vp::ComputeKernel::Barrier(cmd);
        this->Context->Stamp(cmd, 1);
      });
      this->Prepared.push_back(std::move(entry));
      prepared = this->Prepared.end() - 1;
    }
    return *prepared->Commands;
  }

  void Render()
  {
    const auto start = std::chrono::steady_clock::now();
    const vp::DepthLayerGrid& g = this->Grid;
    const std::uint32_t classes = this->Classes();
    const std::uint32_t rangeStride = static_cast<std::uint32_t>(g.Pixels()) * classes;
    RasterParameters raster{};
    for (int k = 0; k < 3; ++k)
    {
      raster.Origin[k] = static_cast<float>(g.OriginMm[k] - this->AnchorMm[k]);
    }
    raster.InvPixelMm = static_cast<float>(1.0 / g.PixelMm);
    raster.InvSliceMm = static_cast<float>(1.0 / g.SliceMm);
    raster.Nx = g.Nx;
    raster.Ny = g.Ny;
    raster.Nz = g.Nz;
    raster.Words = g.Words();
    const std::uint32_t pixels = static_cast<std::uint32_t>(g.Pixels());
    ColumnParameters columns{ pixels, classes, static_cast<std::uint32_t>(g.Words()), rangeStride };
    TileParameters tiles{ g.Nx, g.Ny, g.TilesX(), g.TilesY(), classes, rangeStride, 8, 0 };
    const std::uint32_t tileCount = static_cast<std::uint32_t>(g.TilesX() * g.TilesY()) * classes;
    TileParameters coarse{ g.Nx, g.Ny, CoarseAcross(g.TilesX()), CoarseAcross(g.TilesY()), classes, rangeStride,
      8 * CoarseTiles, 2 * tileCount };
    const std::uint32_t coarseCount = static_cast<std::uint32_t>(coarse.TilesX * coarse.TilesY) * classes;

    this->Context->Submit([&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, this->Occupancy->Handle(), 0, VK_WHOLE_SIZE, 0u);
      vkCmdFillBuffer(cmd, this->Crossings->Handle(), 0, VK_WHOLE_SIZE, 0u);
      vp::ComputeKernel::Barrier(cmd);
      for (std::uint32_t c = 0; c < classes; ++c)
      {
        raster.Class = c;
        raster.FirstTriangle = this->FirstTriangle[c];
        raster.TriangleCount = this->TriangleCount[c];
        this->Raster->Record(cmd, &raster, (raster.TriangleCount + 63) / 64);
      }
      vp::ComputeKernel::Barrier(cmd);
      this->Columns->Record(cmd, &columns, (pixels * classes + 63) / 64);
      vp::ComputeKernel::Barrier(cmd);
      this->Tiles->Record(cmd, &tiles, (tileCount + 63) / 64);
      this->Tiles->Record(cmd, &coarse, (coarseCount + 63) / 64);
      vp::ComputeKernel::Barrier(cmd);
    });
    this->Rendered = true;
    ++this->Renders;
    this->LastRenderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  // The tiles within rangeMm of the tip's tile, nearest first: the query visits them in this
  // order so that the running best shrinks early and far tiles skip their work. The offsets
  // start at the grid's tile nearest the tip, so the table is never wider than the grid,
  // whatever the range (--range 1e9 asked for gigabytes before). Beside it the coarse tiles'
  // table, which the listing walks, and each offset's entry in the order table.
  void PrepareOrder(double rangeMm)
  {
    if (this->OrderRangeMm == rangeMm)
    {
      return;
    }
    const vp::DepthLayerGrid& g = this->Grid;
    this->FineTable = NearestFirst(rangeMm, 8.0, g.PixelMm, std::max(g.TilesX(), g.TilesY()));
    this->CoarseTable = NearestFirst(
      rangeMm, 8.0 * CoarseTiles, g.PixelMm, std::max(CoarseAcross(g.TilesX()), CoarseAcross(g.TilesY())));
    const std::vector<std::array<std::int32_t, 2>>& order = this->FineTable.Offsets;
    const int reach = this->FineTable.Reach;
    const int width = 2 * reach + 1;
    std::vector<std::uint32_t> entryOf(order.size());
    for (std::size_t e = 0; e < order.size(); ++e)
    {
      entryOf[static_cast<std::size_t>((order[e][1] + reach) * width + order[e][0] + reach)] = static_cast<std::uint32_t>(e);
    }
    this->Prepared.clear(); // it names the buffers replaced here
    this->OrderCount = static_cast<std::uint32_t>(order.size());
    using Placement = vp::GpuBuffer::Placement;
    auto upload = [&](const void* data, std::size_t bytes) {
      auto buffer = std::make_unique<vp::GpuBuffer>(*this->Context, bytes, Placement::Device);
      buffer->Upload(data, bytes);
      return buffer;
    };
    this->Order = upload(order.data(), order.size() * 8);
    this->CoarseOrder = upload(this->CoarseTable.Offsets.data(), this->CoarseTable.Offsets.size() * 8);
    this->EntryIndex = upload(entryOf.data(), entryOf.size() * 4);
    const std::uint32_t classes = std::max(this->Classes(), 1u);
    const VkDeviceSize recordBytesPerTip = static_cast<VkDeviceSize>(this->OrderCount) * classes * 16;
    const VkDeviceSize budget =
      std::min<VkDeviceSize>(RecordBudgetBytes, this->Context->Limits().maxStorageBufferRange);
    this->Capacity = static_cast<std::uint32_t>(std::clamp<VkDeviceSize>(budget / recordBytesPerTip, 1,
      this->Context->IsCpuDevice() ? CpuBatchCapacity : GpuBatchCapacity));
    this->Records = std::make_unique<vp::GpuBuffer>(*this->Context, recordBytesPerTip * this->Capacity, Placement::Device);
    const VkDeviceSize stateBytes = StateStride * 4ull * classes * this->Capacity;
    this->State = std::make_unique<vp::GpuBuffer>(*this->Context, stateBytes, Placement::Device);
    this->Choices = std::make_unique<vp::GpuBuffer>(*this->Context, 8ull * classes * this->Capacity, Placement::Device);
    // The answers are written there by the device, and the points by the host, for every batch:
    // host-visible, no copy. Every invocation of a query reads its point: in device memory where
    // the host can write it.
    this->HostState = std::make_unique<vp::GpuBuffer>(*this->Context, stateBytes, Placement::Host);
    this->Points =
      std::make_unique<vp::GpuBuffer>(*this->Context, sizeof(PointRecord) * this->Capacity, Placement::HostToDevice);
    this->Ceilings = std::make_unique<vp::GpuBuffer>(
      *this->Context, sizeof(AnswerCeiling) * classes * this->Capacity, Placement::HostToDevice);
    this->DispatchSizes =
      std::make_unique<vp::GpuBuffer>(*this->Context, 2 * sizeof(VkDispatchIndirectCommand), Placement::HostToDevice);
    // At most one listed tile per answer and entry: half the records' bytes.
    this->TileList = std::make_unique<vp::GpuBuffer>(*this->Context, recordBytesPerTip * this->Capacity / 2, Placement::Device);
    this->TileListSize = std::make_unique<vp::GpuBuffer>(*this->Context, 16, Placement::Device);
    for (vp::ComputeKernel* query : { this->Query.get(), this->QueryPerPixel.get() })
    {
      query->BindBuffers({ this->Occupancy->Handle(), this->Crossings->Handle(), this->DepthRanges->Handle(),
        this->TileRanges->Handle(), this->Order->Handle(), this->State->Handle(), this->Records->Handle(),
        this->Points->Handle(), this->Choices->Handle(), this->Ceilings->Handle(), this->TileList->Handle(),
        this->TileListSize->Handle(), this->CoarseOrder->Handle(), this->EntryIndex->Handle() });
    }
    this->Reduce->BindBuffers({ this->State->Handle(), this->Records->Handle(), this->HostState->Handle(),
      this->Choices->Handle(), this->TileListSize->Handle() });
    // The state starts reset; every query leaves it so.
    const std::uint32_t answers = this->Capacity * classes;
    const ReduceParameters reset{ 0, answers, this->OrderCount };
    this->Context->Submit([&](VkCommandBuffer cmd) {
      this->Reduce->Record(cmd, &reset, (answers + 63) / 64);
      vp::ComputeKernel::Barrier(cmd);
    });
    this->OrderRangeMm = rangeMm;
  }
};

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

double vtkZBufferVesselDistance::GetLastQueryDeviceMs() const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  return this->Impl->Context && this->Impl->Capacity > 0 ? this->Impl->Context->DeviceMs() : -1.0;
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
  s.Votes = nullptr;
  s.Deep = nullptr;
  s.ExactIndex.assign(this->Surfaces.size(), -1);
  for (std::size_t c = 0; c < this->Surfaces.size(); ++c)
  {
    if (!this->Surfaces[c]->IsClosed())
    {
      if (!s.Votes)
      {
        s.Votes = vtkSmartPointer<vtkExactVesselDistance>::New();
      }
      s.ExactIndex[c] = s.Votes->GetNumberOfVessels();
      s.Votes->AddVessel(this->Meshes[c].first, this->Meshes[c].second);
    }
  }
  if (s.Votes)
  {
    s.Votes->Build();
  }

  // Cell size, box and anchor.
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
    s.AnchorMm[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
  }
  const bool moving = this->BoxMode == MovingWithTip;
  double cell = this->CellSizeMm;
  if (this->ResolutionPx > 0)
  {
    const double side = moving ? std::max(this->MovingBoxSizeMm[0], this->MovingBoxSizeMm[1])
                               : std::max(bounds[1] - bounds[0], bounds[3] - bounds[2]);
    cell = std::max(side, 1e-3) / this->ResolutionPx;
  }
  if (moving)
  {
    this->CheckMovingBox(cell);
    s.Grid = vp::DepthLayerGrid::Centred(s.AnchorMm, this->MovingBoxSizeMm, cell, cell, s.AnchorMm);
  }
  else
  {
    s.Grid = vp::DepthLayerGrid::Covering(bounds, cell, cell, 2.0 * cell);
  }
  const std::uint32_t classes = static_cast<std::uint32_t>(this->Surfaces.size());
  const VkDeviceSize layerBytes =
    static_cast<VkDeviceSize>(s.Grid.Pixels()) * s.Grid.Words() * 4ull * std::max(classes, 1u);
  if (layerBytes > context.Limits().maxStorageBufferRange)
  {
    throw vp::ParameterError("CellSizeMm/ResolutionPx", "the depth layers would need " + std::to_string(layerBytes >> 20) +
        " MiB, more than the Vulkan device allows in one buffer (" +
        std::to_string(context.Limits().maxStorageBufferRange >> 20) + " MiB); use larger cells");
  }

  // Geometry: long edges split so that one rasteriser invocation never walks many pixels; float
  // positions relative to the anchor, so that rounding stays far below a micrometre.
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  s.FirstTriangle.clear();
  s.TriangleCount.clear();
  for (const auto& surface : this->Surfaces)
  {
    auto points = surface->PointArray();
    auto triangles = surface->TriangleArray();
    vp::SplitLongEdges(points, triangles, MaxEdgeCells * cell);
    const std::uint32_t base = static_cast<std::uint32_t>(positions.size() / 3);
    s.FirstTriangle.push_back(static_cast<std::uint32_t>(indices.size() / 3));
    s.TriangleCount.push_back(static_cast<std::uint32_t>(triangles.size()));
    for (const auto& p : points)
    {
      for (int k = 0; k < 3; ++k)
      {
        positions.push_back(static_cast<float>(p[k] - s.AnchorMm[k]));
      }
    }
    for (const auto& t : triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        indices.push_back(base + static_cast<std::uint32_t>(t[k]));
      }
    }
  }
  s.RasterTriangles = indices.size() / 3;
  if (positions.size() * 4 > context.Limits().maxStorageBufferRange ||
    indices.size() * 4 > context.Limits().maxStorageBufferRange)
  {
    throw vp::InputError("(vessels)", "too many triangles for one Vulkan buffer on this device");
  }
  using Placement = vp::GpuBuffer::Placement;
  s.Positions = std::make_unique<vp::GpuBuffer>(context, positions.size() * 4, Placement::Device);
  s.Positions->Upload(positions.data(), positions.size() * 4);
  s.Indices = std::make_unique<vp::GpuBuffer>(context, indices.size() * 4, Placement::Device);
  s.Indices->Upload(indices.data(), indices.size() * 4);

  const VkDeviceSize rangeBytes = 2ull * s.Grid.Pixels() * std::max(classes, 1u) * 4ull;
  // The tiles' ranges, then the coarse tiles'.
  const VkDeviceSize tileBytes = 2ull *
    static_cast<VkDeviceSize>(s.Grid.TilesX() * s.Grid.TilesY() + CoarseAcross(s.Grid.TilesX()) * CoarseAcross(s.Grid.TilesY())) *
    std::max(classes, 1u) * 4ull;
  s.Occupancy = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  s.Crossings = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  s.DepthRanges = std::make_unique<vp::GpuBuffer>(context, rangeBytes, Placement::Device);
  s.TileRanges = std::make_unique<vp::GpuBuffer>(context, tileBytes, Placement::Device);

  s.Raster = std::make_unique<vp::ComputeKernel>(
    context, RasterizeLayers_comp, RasterizeLayers_comp_size, 4, static_cast<std::uint32_t>(sizeof(RasterParameters)));
  s.Raster->BindBuffers({ s.Positions->Handle(), s.Indices->Handle(), s.Occupancy->Handle(), s.Crossings->Handle() });
  s.Columns = std::make_unique<vp::ComputeKernel>(
    context, SummarizeColumns_comp, SummarizeColumns_comp_size, 2, static_cast<std::uint32_t>(sizeof(ColumnParameters)));
  s.Columns->BindBuffers({ s.Occupancy->Handle(), s.DepthRanges->Handle() });
  s.Tiles = std::make_unique<vp::ComputeKernel>(
    context, SummarizeTiles_comp, SummarizeTiles_comp_size, 2, static_cast<std::uint32_t>(sizeof(TileParameters)));
  s.Tiles->BindBuffers({ s.DepthRanges->Handle(), s.TileRanges->Handle() });
  s.Query = std::make_unique<vp::ComputeKernel>(
    context, QueryProximity_comp, QueryProximity_comp_size, 14, static_cast<std::uint32_t>(sizeof(QueryParameters)));
  s.QueryPerPixel = std::make_unique<vp::ComputeKernel>(context, QueryProximityPerPixel_comp,
    QueryProximityPerPixel_comp_size, 14, static_cast<std::uint32_t>(sizeof(QueryParameters)));
  s.Reduce = std::make_unique<vp::ComputeKernel>(
    context, ReduceProximity_comp, ReduceProximity_comp_size, 5, static_cast<std::uint32_t>(sizeof(ReduceParameters)));

  s.Renders = 0; // Release() dropped the ceilings of the renderings before
  if (!moving && classes > 0)
  {
    s.Render();
  }
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
  this->AnswerAll(tips, axes, this->RangeMm, true, results);
}

void vtkZBufferVesselDistance::ComputeProximityBatchWithin(
  const Points& points, double searchMm, std::vector<vp::ProximityResult>& results) const
{
  if (this->BoxMode == MovingWithTip)
  {
    throw vp::InputError("box mode", "a search of many points needs the box fixed around the vessels (each point would move the box)");
  }
  this->AnswerAll(points, nullptr, std::min(searchMm, this->RangeMm), false, results);
}

void vtkZBufferVesselDistance::AnswerAll(
  const Points& tips, const Points* axes, double searchMm, bool bins, std::vector<vp::ProximityResult>& results) const
{
  const std::size_t count = tips.size();
  results.resize(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    this->BeginResult(tips[i].data(), results[i]);
  }
  const std::array<double, 3>* axis = axes ? axes->data() : nullptr;
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  Internals& s = *this->Impl;
  s.TipQuery = bins;
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
      this->AnswerBatch(&tips[i], 1, axis ? axis + i : nullptr, searchMm, binWidth, &results[i]);
    }
    return;
  }
  s.PrepareOrder(this->RangeMm);
  const std::size_t capacity = s.Capacity;
  for (std::size_t first = 0; first < count; first += capacity)
  {
    const std::size_t n = std::min(capacity, count - first);
    this->AnswerBatch(&tips[first], n, axis ? axis + first : nullptr, searchMm, binWidth, &results[first]);
  }
}

void vtkZBufferVesselDistance::CopyOccupancy(std::vector<std::uint32_t>& words) const
{
  this->CopyLayer(false, words);
}

void vtkZBufferVesselDistance::CopyCrossings(std::vector<std::uint32_t>& words) const
{
  this->CopyLayer(true, words);
}

void vtkZBufferVesselDistance::CopyLayer(bool crossings, std::vector<std::uint32_t>& words) const
{
  std::lock_guard<std::mutex> lock(this->Impl->Lock);
  this->Impl->CopyLayer(crossings, words);
}

double vtkZBufferVesselDistance::WriteCeilings(
  const std::array<double, 3>* tips, std::size_t count, double searchMm) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  const std::uint32_t orderCount = s.FineTable.Within(searchMm);
  auto* ceiling = static_cast<AnswerCeiling*>(s.Ceilings->Mapped());
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
  double highest = -1.0; // the farthest any answer needs to look (none: below 0)
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* tip = tips[i].data();
    for (std::uint32_t c = 0; c < classes; ++c)
    {
      double bound = blocks ? blocks->UpperBoundMm(static_cast<int>(c), tip) : Unknown;
      const Internals::LastAnswer& last = s.Last[c];
      if (last.Known)
      {
        bound = std::min(bound, last.CellMm + std::sqrt(vp::Distance2(tip, last.TipMm)));
      }
      bound = above(bound);
      const float mm = bound < searchMm ? std::nextafter(static_cast<float>(bound), None) : None;
      ceiling[i * classes + c] = { mm, std::min(orderCount, s.FineTable.Within(mm)) };
      // A class whose marked cells all lie beyond the search needs no tile (it is out of range,
      // as the tiles would have found): its ceiling does not size the dispatch.
      if (!blocks || blocks->LowerBoundMm(static_cast<int>(c), tip) <= above(searchMm))
      {
        highest = std::max(highest, std::min(bound, searchMm));
      }
    }
  }
  return highest;
}

void vtkZBufferVesselDistance::AnswerBatch(const std::array<double, 3>* tips, std::size_t count,
  const std::array<double, 3>* axes, double searchMm, double binWidth, vp::ProximityResult* results) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  s.PrepareOrder(this->RangeMm);
  const vp::DepthLayerGrid& g = s.Grid;
  const std::uint32_t orderCount = s.FineTable.Within(searchMm);
  s.WritePoints(tips, count, axes);
  QueryParameters q = MakeQueryParameters(g, searchMm, binWidth, this->DistanceBins, orderCount,
    this->LayerMode == PaperNearFar, classes,
    this->DirectionalLanes > 0 ? this->DirectionalLanes : (s.Context->IsCpuDevice() ? 1 : GpuDirectionalLanes));
  q.OrderReach = s.FineTable.Reach;
  q.CoarseCount = static_cast<std::int32_t>(s.CoarseTable.Within(searchMm));

  // A workgroup per tile: the per-pixel pass needs the device to take that many in one dispatch.
  const std::uint32_t lanes = static_cast<std::uint32_t>(q.DirectionalLanes);
  const std::uint32_t laneGroups = (lanes + 63) / 64;
  const bool perPixel =
    (this->QueryPass == QueryPassPerPixel ||
      (this->QueryPass == QueryPassByDevice && !s.Context->IsCpuDevice() && count <= PerPixelMaxTips)) &&
    orderCount + laneGroups <= s.Context->Limits().maxComputeWorkGroupCount[0];
  const std::uint32_t n = static_cast<std::uint32_t>(count);
  const double reachMm = this->WriteCeilings(tips, count, searchMm);
  const std::uint32_t tiles = reachMm < 0.0 ? 0 : std::min(orderCount, s.FineTable.Within(reachMm));
  // The listed tiles are visited per pixel where the order table would be: on a GPU, where a
  // workgroup per listed tile is work for every invocation.
  const bool listPerPixel = this->QueryPass != QueryPassPerTile &&
    (this->QueryPass == QueryPassPerPixel || !s.Context->IsCpuDevice());
  const bool list = this->TileListing == TileListingOn ||
    (this->TileListing == TileListingByDevice && (n > PerPixelMaxTips || s.Context->IsCpuDevice()));
  const int listing = list ? (listPerPixel ? 2 : 1) : 0;
  // Without a list, a batch first visits its near tiles, so that the best falls before the rest
  // start. A list needs no such pass: the ceilings alone leave a few tiles per tip to list
  // (IRCADb patient 1, 0.4 mm cells: 24 of 2,691 per tip, 20 after a near pass of 2 tiles,
  // which made lavapipe no faster).
  const std::uint32_t nearEntries =
    n > PerPixelMaxTips && !list ? std::min(orderCount, s.FineTable.Within(NearTiles * 8.0 * g.PixelMm)) : 0;
  auto groups = [](bool pixels, std::uint32_t slots) { return pixels ? slots : (slots + 63) / 64; };
  auto* sizes = static_cast<VkDispatchIndirectCommand*>(s.DispatchSizes->Mapped());
  sizes[0] = { groups(perPixel, std::min(nearEntries, tiles)), classes, n };
  std::uint32_t laneSlots = 0;
  if (list)
  {
    // The listing's workgroups per answer: one for a batch (its answers fill the device) and on
    // a CPU device (which runs them one after another anyway); for a few tips on a GPU enough
    // that no invocation loops over more than 4 coarse tiles.
    const bool one = n > PerPixelMaxTips || s.Context->IsCpuDevice();
    const std::uint32_t coarse = reachMm < 0.0 ? 0 : s.CoarseTable.Within(reachMm);
    sizes[1] = { one ? 1u : std::max(1u, (coarse + 255) / 256), classes, n };
  }
  else
  {
    // Lanes first in the last dispatch over the order table: invocations per tile, workgroups
    // per pixel.
    laneSlots = perPixel ? laneGroups : lanes;
    sizes[1] = { groups(perPixel, laneSlots + (tiles > nearEntries ? tiles - nearEntries : 0)), classes, n };
  }
  s.LastTiles = tiles * classes;
  s.LastTilesInRange = orderCount * classes;
  s.PreparedQueryFor(q, n, perPixel, listing, nearEntries, laneSlots).Submit();
  s.LastTilesListed = static_cast<const std::uint32_t*>(s.HostState->Mapped())[7];
  this->ReadAnswers(tips, count, axes != nullptr, searchMm, q.Bins, binWidth, results);
}

void vtkZBufferVesselDistance::ReadAnswers(const std::array<double, 3>* tips, std::size_t count, bool axes,
  double searchMm, int bins, double binWidth, vp::ProximityResult* results) const
{
  Internals& s = *this->Impl;
  const std::uint32_t classes = s.Classes();
  const vp::DepthLayerGrid& g = s.Grid;
  const auto* hostState = static_cast<const std::uint32_t*>(s.HostState->Mapped());
  std::vector<InsideVote> votes; // the answers on surfaces that are not closed
  for (std::size_t i = 0; i < count; ++i)
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
      if (!(cellMm <= searchMm))
      {
        this->AnswerBeyondRange(c, tip, cs[1] != 0u, out);
        continue;
      }
      if (c < s.Last.size())
      {
        // That cell stays marked until the next rendering: no later answer is farther than it.
        Internals::LastAnswer& last = s.Last[c];
        last.Known = true;
        std::copy(tip, tip + 3, last.TipMm);
        last.CellMm = cellMm;
      }
      const double distance = ReportedDistanceMm(cs, cellMm, g.HalfDiagonalMm(), bins, binWidth);
      if (distance > this->RangeMm)
      {
        this->AnswerBeyondRange(c, tip, cs[1] != 0u, out);
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
        votes.push_back({ i, c, cellMm + g.HalfDiagonalMm() });
      }
      out.DistanceMm = distance;
      ClosestPointInChosenCell(g, tip, cs, out.ClosestPoint);
      out.TriangleId = -1;
    }
  }
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
  if (!s.Deep)
  {
    s.Deep = vtkSmartPointer<vtkExactVesselDistance>::New();
    for (const auto& [name, mesh] : this->Meshes)
    {
      s.Deep->AddVessel(name, mesh);
    }
    s.Deep->Build();
  }
  s.Deep->FindDepthBeyondRange(static_cast<int>(c), tip, out);
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
  os << indent << "DirectionalLanes: " << this->DirectionalLanes << (this->DirectionalLanes ? "" : " (by device)") << "\n";
  os << indent << "DeviceSelector: " << (this->DeviceSelector.empty() ? "(best)" : this->DeviceSelector) << "\n";
  const vp::DepthLayerGrid& g = this->Impl->Grid;
  os << indent << "Grid: " << g.Nx << " x " << g.Ny << " x " << g.Nz << " cells of " << g.PixelMm << " x "
     << g.PixelMm << " x " << g.SliceMm << " mm\n";
  os << indent << "Renders: " << this->Impl->Renders << " (last " << this->Impl->LastRenderMs << " ms)\n";
}
