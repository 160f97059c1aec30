#ifndef vtkZBufferVesselDistanceInternals_h
#define vtkZBufferVesselDistanceInternals_h

// vtkZBufferVesselDistance's device state and the steps on it, shared by the files that cut the
// engine along its seams: vtkZBufferVesselDistanceRasterizing.cxx (geometry, layers, rendering),
// vtkZBufferVesselDistanceQueryTables.cxx (the tile order and the ceilings),
// vtkZBufferVesselDistanceSubmission.cxx (the device, the points and the recorded query) and
// vtkZBufferVesselDistance.cxx (settings, building, answers). Private to Logic/ZBuffer.

#include "vtkZBufferVesselDistance.h"

#include "vpBlockDistanceField.h"
#include "vpComputeKernel.h"
#include "vpGpuBuffer.h"
#include "vpHostTileListing.h"
#include "vpPreparedCommands.h"
#include "vpTileOrder.h"
#include "vpVulkanContext.h"
#include "vpZBufferShaderLayout.h"
#include "vtkExactVesselDistance.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vp
{
namespace zbuffer
{
// Triangles are split until no edge is longer than this many cells, which bounds the pixels one
// rasteriser invocation visits (and so the longest invocation).
constexpr double MaxEdgeCells = 4.0;

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
// Tips per submission: as many as the records of a batch allow within RecordBudgetBytes, and at
// most these (a CPU device answers a batch's tips one after another: larger batches only cost
// memory there; a GPU answers them side by side, so larger batches spread a submission's fixed
// cost over more tips).
constexpr std::uint32_t CpuBatchCapacity = 256;
constexpr std::uint32_t GpuBatchCapacity = 4096;
constexpr VkDeviceSize RecordBudgetBytes = 256ull << 20;
// How far ahead of the tip whose ceilings it writes a batch asks for a later tip's blocks (their
// random places in some 10 MB of blocks each miss the cache).
constexpr std::size_t CeilingPrefetchTips = 8;

/// Answers from which a call's host work runs on every core: a task costs more than a few.
constexpr std::size_t ParallelAnswers = 64;

/// fn(begin, end) over [0, count): on every core for a batch (from ParallelAnswers), on this
/// thread for a few. A batch's host work per tip (its results, ceilings, answers read and votes)
/// was most of its time on a GPU: 20,000 tips at 1.5M triangles per class on an H100 took 82 ms,
/// 3.5 of them on the device.
template <typename Fn>
void ForEachAnswer(std::size_t count, const Fn& fn)
{
  if (count >= ParallelAnswers)
  {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&](vtkIdType begin, vtkIdType end) {
      fn(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    });
  }
  else
  {
    fn(0, count);
  }
}

/// As ForEachAnswer, fn(begin, end, local) with a Local of the thread's own (made from init),
/// then gather(local) on this thread for each thread's. For a few answers one Local on this
/// thread: a store per thread costs a single tip microseconds (5 of a lavapipe tip's 300).
template <typename Local, typename Fn, typename Gather>
void ForEachAnswerGathered(std::size_t count, const Local& init, const Fn& fn, const Gather& gather)
{
  if (count < ParallelAnswers)
  {
    Local one = init;
    fn(std::size_t{ 0 }, count, one);
    gather(one);
    return;
  }
  vtkSMPThreadLocal<Local> locals(init);
  ForEachAnswer(count, [&](std::size_t begin, std::size_t end) { fn(begin, end, locals.Local()); });
  for (Local& local : locals)
  {
    gather(local);
  }
}

/// An inside answer the exact engine's vote decides: on a surface that is not closed.
struct InsideVote
{
  std::size_t Tip;
  std::uint32_t Class;
  double DistanceMm;
};
} // namespace zbuffer
} // namespace vp

struct vtkZBufferVesselDistance::Submission
{
  const std::array<double, 3>* Tips = nullptr;
  std::size_t Count = 0;
  bool Axes = false;
  double SearchMm = 0.0;
  int Bins = 0;
  double BinWidthMm = 0.0;
  vp::ProximityResult* Results = nullptr;
  std::uint32_t Slot = 0;
  long long HostListed = -1; // the tiles the host listed; -1: none (the device listed, or no list)
};

struct vtkZBufferVesselDistance::Internals
{
  using InsideVote = vp::zbuffer::InsideVote;
  using QueryParameters = vp::zbuffer::QueryParameters;
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
  std::unique_ptr<vp::GpuBuffer> Occupancy, Crossings, CrossingHalves, CrossingQuarters, DepthRanges, TileRanges;

  // Query.
  double OrderRangeMm = -1.0;
  std::uint32_t OrderCount = 0;
  // The order table of tiles and that of coarse tiles, as uploaded (their gaps say which
  // entries a search needs).
  vp::TileOrder FineTable, CoarseTable;
  std::unique_ptr<vp::GpuBuffer> Order, State, Choices, Records, HostState, Points;
  // The coarse tiles' order table and each offset's entry in the order table (see CoarseOrder in
  // QueryProximityCommon.glsl).
  std::unique_ptr<vp::GpuBuffer> CoarseOrder, EntryIndex;
  // Per point and class the answer's ceiling (mm), and the sizes of the query's two dispatches
  // (VkDispatchIndirectCommand: the near tiles of a batch, then the lanes and the rest), written
  // by the host before every submission. These, the points and the host-visible answers hold
  // one submission per slot of the context (vp::VulkanContext::Slots), Capacity points each.
  std::unique_ptr<vp::GpuBuffer> Ceilings, DispatchSizes;
  // The tiles a submission lists, and the list's size with the workgroup counts of the
  // dispatch that visits them (written by the device; see TileList in the shaders).
  std::unique_ptr<vp::GpuBuffer> TileList, TileListSize;
  // A few tips' list made on the host (HostTileList in the shaders: HostListItemsPerPoint items
  // per point of a slot, written by the host), and the tile ranges it reads, copied from the
  // device once per rendering.
  std::unique_ptr<vp::GpuBuffer> HostTileList;
  std::vector<vp::zbuffer::AnswerCeiling> HostCeilings; // the ceilings as written, when the host lists
  vp::HostTileListing HostListing;
  int HostListingRender = -1;
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
  // The slot of the latest submission read (GetLastQueryDeviceMs), and each slot's timestamps as
  // its submission copies them (StampsPerSlot 64-bit ticks a slot: its start and end, then, for a
  // batch's submission, when its tiles were listed and visited).
  std::uint32_t LastSlot = 0;
  std::unique_ptr<vp::GpuBuffer> StampCopies;
  enum StampOf : std::uint32_t
  {
    SubmissionStart,
    SubmissionEnd,
    TilesListed,
    TilesVisited
  };
  // Whether the current call's submissions stamp their stages (a call of more than
  // PerPixelMaxTips points: every submission of a batch, its last and smallest too; a call reads
  // every submission it starts). A few tips' call does not: on lavapipe the two stamps between
  // its dispatches cost a single tip 0.1 of its 0.3 ms.
  bool StampStages = false;
  static bool StampsStages(std::size_t points) { return points > vp::zbuffer::PerPixelMaxTips; }
  // The device's time for slot `slot`'s latest submission between two of its stamps (negative
  // without timestamps).
  double DeviceMsOf(std::uint32_t slot, std::uint32_t from = SubmissionStart, std::uint32_t to = SubmissionEnd) const
  {
    if (!this->StampCopies)
    {
      return -1.0;
    }
    return this->Context->StampsMs(
      static_cast<const std::uint64_t*>(this->StampCopies->Mapped()) + vp::VulkanContext::StampsPerSlot * slot, from, to);
  }
  // The first point of a slot in the points, ceilings and answers.
  std::size_t FirstPointOf(std::uint32_t slot) const { return static_cast<std::size_t>(slot) * this->Capacity; }
  // A slot's answers as the device left them: StateStride words per point and class.
  const std::uint32_t* AnswersOf(std::uint32_t slot) const
  {
    return static_cast<const std::uint32_t*>(this->HostState->Mapped()) +
      this->FirstPointOf(slot) * this->Classes() * vp::zbuffer::StateStride;
  }
  int SubmissionsOnRender = 0;
  std::uint32_t LastTiles = 0, LastTilesInRange = 0, LastTilesListed = 0;
  vtkZBufferVesselDistance::CallTimes LastCall;
  /// One submission's device times (whole and by stage) added to a call's (which stay negative
  /// once one is unknown: the stages of a few tips' submission are).
  void AddDeviceMs(vtkZBufferVesselDistance::CallTimes& call, std::uint32_t slot) const
  {
    auto add = [](double& sum, double ms) { sum = sum < 0.0 || ms < 0.0 ? -1.0 : sum + ms; };
    const bool stages = this->StampStages;
    add(call.DeviceMs, this->DeviceMsOf(slot));
    add(call.DeviceListingMs, stages ? this->DeviceMsOf(slot, SubmissionStart, TilesListed) : -1.0);
    add(call.DeviceVisitingMs, stages ? this->DeviceMsOf(slot, TilesListed, TilesVisited) : -1.0);
    add(call.DeviceReducingMs, stages ? this->DeviceMsOf(slot, TilesVisited, SubmissionEnd) : -1.0);
  }
  // Tips per submission for the current order table (PrepareOrder).
  std::uint32_t Capacity = 0;

  std::unique_ptr<vp::ComputeKernel> Raster, Columns, Tiles, Query, QueryPerPixel, Reduce;
  // The query's submissions, each recorded once for one batch size and one set of parameters
  // (the whole instrument's search asks for a few ranges and sizes again and again).
  struct PreparedQuery
  {
    std::uint32_t Points = 0;
    std::uint32_t Slot = 0;
    bool PerPixel = false;
    int Listing = 0; // 0: no list; 1: listed tiles visited per tile; 2: per pixel
    bool HostList = false;          // listed by the host (else by the device)
    bool ListPerInvocation = false; // listed by an invocation per answer (else a workgroup)
    bool Stages = false;            // stamps between its stages
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

  // The classes whose surface is not closed, in an exact engine of their own for their votes
  // (with vote fields of voteFieldCellMm reaching rangeMm); and no deep engine until one is needed.
  void BuildVotes(const std::vector<std::shared_ptr<const vp::VesselSurface>>& surfaces,
    const std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>>& meshes, double voteFieldCellMm, double rangeMm);
  // The votes run on the host, five rays each: a batch's on all cores (Embree's queries are
  // thread-safe), so that a batch on a defective surface does not wait for them one by one.
  void VoteInside(const std::vector<InsideVote>& votes, const std::array<double, 3>* tips, vp::ProximityResult* results);

  vp::VulkanContext& Device(const std::string& selector);

  void Release();

  std::uint32_t Classes() const { return static_cast<std::uint32_t>(this->FirstTriangle.size()); }

  // One of the layers' bit planes, copied to the host (lock held).
  void CopyLayer(LayerPlane plane, std::vector<std::uint32_t>& words);
  // A device buffer's words, copied to the host.
  void CopyBuffer(const vp::GpuBuffer& buffer, std::vector<std::uint32_t>& words);

  // The ceilings' blocks for the current rendering, and no answer remembered from an older one.
  // None for a rendering's first submission: a one-shot query (`distance --tip`) does not wait
  // the tenths of a second they take on large layers.
  const vp::BlockDistanceField* PrepareCeilings(bool now = false);

  // A tip in grid units (pixels, pixels, slices) as the query reads it.
  void GridTip(const double tipMm[3], float grid[3]) const
  {
    const vp::DepthLayerGrid& g = this->Grid;
    grid[0] = static_cast<float>((tipMm[0] - g.OriginMm[0]) / g.PixelMm);
    grid[1] = static_cast<float>((tipMm[1] - g.OriginMm[1]) / g.PixelMm);
    grid[2] = static_cast<float>((tipMm[2] - g.OriginMm[2]) / g.SliceMm);
  }
  // Each tip in grid units and its unit axis (or zero), where the query in slot `slot` reads them.
  void WritePoints(const std::array<double, 3>* tips, std::size_t count, const std::array<double, 3>* axes, std::uint32_t slot);

  // The query's submission for these parameters, batch size and passes, recorded once: the two
  // dispatches over the order table (their sizes read from DispatchSizes when it runs), then the
  // answers. With a list (listing 1: visited per tile, 2: per pixel), the second dispatch lists
  // the tiles it would have visited (a workgroup, or with listPerInvocation an invocation, per
  // answer) and a third, sized by the device, visits them.
  // In slot `slot`: its points, ceilings, dispatch sizes, answers and timestamps.
  // With hostList the host has listed the tiles and lanes (HostTileList): one dispatch, sized
  // by the host, visits them.
  vp::PreparedCommands& PreparedQueryFor(const QueryParameters& q, std::uint32_t n, std::uint32_t slot, bool perPixel,
    int listing, bool listPerInvocation, bool hostList, bool stages, std::uint32_t nearEntries, std::uint32_t laneSlots);

  // The host's listing on the current rendering's tile ranges (copied once per rendering).
  const vp::HostTileListing& PrepareHostListing();
  // Lists the answers' tiles and lanes of `count` tips for slot `slot`, their ceilings in
  // HostCeilings: their items in HostTileList and the visiting dispatch's size in DispatchSizes'
  // second. The tiles listed, or -1 when they do not fit (the device lists them then).
  long long ListOnHost(
    const QueryParameters& q, const std::array<double, 3>* tips, std::size_t count, bool perPixel, std::uint32_t slot);

  // The vessels' triangles as the rasteriser reads them: long edges split so that one invocation
  // never walks many pixels; float positions relative to the anchor, so that rounding stays far
  // below a micrometre. Sets FirstTriangle, TriangleCount and RasterTriangles.
  void UploadGeometry(const std::vector<std::shared_ptr<const vp::VesselSurface>>& surfaces, double cellMm);
  // The layers and their summaries for Grid, and the kernels bound to them.
  void CreateLayers(VkDeviceSize layerBytes);

  // Rasterises every class into the layers, then summarises their columns and tiles.
  void Render();

  // The tiles within rangeMm of the tip's tile, nearest first: the query visits them in this
  // order so that the running best shrinks early and far tiles skip their work. The offsets
  // start at the grid's tile nearest the tip, so the table is never wider than the grid,
  // whatever the range (--range 1e9 asked for gigabytes before). Beside it the coarse tiles'
  // table, which the listing walks, and each offset's entry in the order table.
  void PrepareOrder(double rangeMm);
};

#endif
