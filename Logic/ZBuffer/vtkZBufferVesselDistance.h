#ifndef vtkZBufferVesselDistance_h
#define vtkZBufferVesselDistance_h

#include "vpDepthLayerGrid.h"
#include "vtkVesselDistanceEngine.h"

#include <cstdint>
#include <memory>
#include <string>

namespace vp
{
namespace zbuffer
{
struct AnswerCeiling;
}
}

/// The GPU method of Noborio et al., "Comparison of GPU-based and CPU-based Algorithms for
/// Determining the Minimum Distance between a CUSA Scalpel and Blood Vessels" (the paper below):
/// render the vessels into a z-buffer around the tip, then one GPU thread per pixel turns its
/// depths into a distance to the tip and a reduction keeps the minimum, so a query costs the
/// pixels within range, whatever the mesh size. Here on Vulkan (headless, any device; Mesa's
/// lavapipe on a machine without a GPU), made exact up to a stated bound.
///
/// The vessels are rasterised orthographically along +z into depth layers: per pixel, a column of
/// depth slices with one bit per slice for "the surface passes through this cell". The
/// rasteriser is conservative (each triangle is clipped against every pixel square it touches),
/// so a vessel thinner than a pixel is never lost. A compute pass then visits the pixels within
/// range of the tip, nearest first, one invocation per pixel, and keeps the nearest marked cell
/// per class. All classes are rasterised in one submission and queried in one dispatch.
///
/// LayerMode ExactIntervals (default) keeps every interval of every pixel: vessels one above
/// the other stay apart. PaperNearFar keeps only the nearest and farthest depth per pixel, a
/// cuboid column, as the paper does; it overstates proximity where vessels overlap along the view.
///
/// BoxMode FixedAroundVessels (default) renders the layers once around all vessels and reuses
/// them for every tip while the vessels do not change. MovingWithTip renders a box of
/// MovingBoxSizeMm around the tip, as the paper does, and renders again only when the range ball
/// around the tip leaves the current box.
///
/// Every answer carries GetErrorBoundMm() (vp::DepthLayerGrid::ErrorBoundMm): the reported
/// distance is within it of the exact distance, in either direction. The closest point is the
/// point of the nearest marked cell closest to the tip. Directional distance is the entry
/// distance of the first marked cell along the axis: never more than the exact value plus the
/// bound, but smaller where the axis passes within a cell of a vessel it does not hit. "Inside" is
/// decided at the pixel centre and may differ from the exact answer within about a cell of a surface.
///
/// Queries are serialised by a lock: one GPU submission at a time. A batch of tips goes in one
/// submission (ComputeProximityBatch), and the device, not the host, picks each answer.
class vtkZBufferVesselDistance : public vtkVesselDistanceEngine
{
public:
  static vtkZBufferVesselDistance* New();
  vtkTypeMacro(vtkZBufferVesselDistance, vtkVesselDistanceEngine);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LayerModes
  {
    ExactIntervals = 0,
    PaperNearFar = 1
  };
  enum BoxModes
  {
    FixedAroundVessels = 0,
    MovingWithTip = 1
  };

  /// ExactIntervals (default) or PaperNearFar.
  void SetLayerMode(int mode);
  int GetLayerMode() const { return this->LayerMode; }
  /// FixedAroundVessels (default) or MovingWithTip.
  void SetBoxMode(int mode);
  int GetBoxMode() const { return this->BoxMode; }

  /// Edge of a cell (pixel and slice), in mm. Default 0.4 mm: an error bound of 0.35 mm.
  static constexpr double DefaultCellSizeMm = 0.4;
  /// The error bound of layers of cells of cellMm (without the paper's distance bits).
  static double ErrorBoundForCellMm(double cellMm);
  void SetCellSizeMm(double cellMm);
  double GetCellSizeMm() const { return this->CellSizeMm; }
  /// Pixels across the longer side of the box in the view plane; overrides CellSizeMm when
  /// positive. Default 0 (use CellSizeMm).
  void SetResolutionPx(int pixels);
  int GetResolutionPx() const { return this->ResolutionPx; }
  /// Size of the moving box, in mm (x, y, z). Default: the paper's 106 x 106 x 213 mm. Each half
  /// must hold the range plus a cell.
  static constexpr double DefaultMovingBoxSizeMm[3] = { 106.0, 106.0, 213.0 };
  void SetMovingBoxSizeMm(double x, double y, double z);
  const double* GetMovingBoxSizeMm() const { return this->MovingBoxSizeMm; }
  /// The paper's distance bits: this many bins (a multiple of 16, at most 768) over 0 to
  /// RangeMm; the distance is then the midpoint of the first raised bin, and the bound grows by
  /// half a bin. Default 0 (off).
  void SetDistanceBins(int bins);
  int GetDistanceBins() const { return this->DistanceBins; }
  enum QueryPasses
  {
    QueryPassByDevice = 0,
    QueryPassPerTile = 1,
    QueryPassPerPixel = 2
  };
  /// How the query's pass visits the pixels near the tip: PerTile, one invocation walking the 64
  /// pixels of a tile (for CPU devices, where a workgroup with a barrier runs as coroutines), or
  /// PerPixel, one invocation per pixel (the paper's thread per pixel, for GPUs, where the
  /// per-tile walk is a chain of dependent reads). The answers are the same, bit for bit. Default
  /// QueryPassByDevice: on a GPU PerPixel for submissions of up to 8 tips and PerTile for larger
  /// ones (whose listed tiles fill the device anyway: 20,000 tips at 1.5M triangles per class
  /// on an H100, 5.6M tips/s of the device's time per tile, 4.5M per pixel), PerTile on a CPU
  /// device.
  void SetQueryPass(int pass);
  int GetQueryPass() const { return this->QueryPass; }
  enum TileListings
  {
    TileListingByDevice = 0,
    TileListingOff = 1,
    TileListingOn = 2
  };
  /// Whether a submission lists the tiles it has to visit before visiting them. Off: one dispatch
  /// over the order table (as far as the submission's highest ceiling) visits them, and every
  /// tile of it starts, if only to find that it has nothing to do. On: a workgroup per answer
  /// (a few for a single tip on a GPU) loops over the order table's entries within the answer's
  /// own ceiling and lists the tiles that have to be visited; a dispatch sized by the device
  /// then visits those alone, per pixel where the query pass would be. A batch's near tiles
  /// are visited first only without a list. The answers are the same, bit for bit. Default
  /// TileListingByDevice: on. A few tips' list is the host's (SetListingPass), which leaves them
  /// one dispatch of a few dozen workgroups where the order table started thousands; before it, a
  /// GPU listed no few tips' tiles (the device's listing was a dispatch more: 0.059 ms against
  /// 0.041 for a single tip on an H100).
  void SetTileListing(int listing);
  int GetTileListing() const { return this->TileListing; }
  enum ListingPasses
  {
    ListingPassByDevice = 0,
    ListingPassPerWorkgroup = 1,
    ListingPassPerInvocation = 2,
    ListingPassOnHost = 3
  };
  /// How a list is made (SetTileListing): PerWorkgroup, a workgroup per answer whose invocations
  /// test its coarse tiles side by side, each against the ceiling the answer started from; or
  /// PerInvocation, an invocation per answer walking its coarse tiles nearest first, each tile it
  /// may visit lowering the best before the next is tested, so that it stops sooner. The answers
  /// are the same, bit for bit. Or OnHost: the host walks each answer's coarse tiles as
  /// PerInvocation does (vp::HostTileListing, on the tile ranges copied once per rendering) and
  /// writes the list, lanes and all, so that one dispatch visits it: no listing dispatch, and
  /// no workgroup per tile of the order table; a submission whose list would not fit its slot
  /// (HostListItemsPerPoint items a point) is listed PerWorkgroup. Default ListingPassByDevice:
  /// OnHost for submissions of up to 8 tips (a single tip on lavapipe: see the bench's tile
  /// listing rows), PerInvocation for larger ones on a CPU device (a 20,000-tip batch on IRCADb
  /// patient 1 here: its listing 185 ms of device time against 373, the batch 453 ms against
  /// 635) and PerWorkgroup for larger ones on a GPU (where one thread's walk is a chain of
  /// dependent reads: to be measured there, bench's batch passes).
  void SetListingPass(int pass);
  int GetListingPass() const { return this->ListingPass; }
  /// Invocations that share the directional walk along the axis, each walking its share of the
  /// range (same answers for any number: every crossing is computed from its cell). Default 0:
  /// 64 on a GPU, where one walk of hundreds of cells in one thread was most of a tracked query's
  /// time, and 1 on a CPU device, where the lanes run one after another anyway.
  void SetDirectionalLanes(int lanes);
  int GetDirectionalLanes() const { return this->DirectionalLanes; }
  /// Whether each query starts from a ceiling on its answer (default on, with the fixed box): per
  /// tip and class, the least of an upper bound from the vessels' coarse blocks
  /// (vp::BlockDistanceField over the layers' occupancy, blocks of 4 cells and at least 1.6 mm,
  /// built once per rendering, at its second submission, so that a one-shot query does not wait
  /// for them) and the class's previous answer plus how far the tip moved since.
  /// The submission dispatches only the tiles within the highest ceiling of its answers (an
  /// indirect dispatch whose size the host writes; a class whose marked cells the blocks put
  /// beyond the search does not count), and each answer's tiles beyond its own ceiling are
  /// skipped from the start: a query's work follows the tip's distance, not the range, even on a GPU where all
  /// of a dispatch's tiles start at once. The answers are the same, bit for bit, on or off (no
  /// pixel that gives an answer lies beyond its ceiling); off is for tests and benchmarks.
  void SetQueryCeilings(bool on);
  bool GetQueryCeilings() const { return this->QueryCeilings; }
  /// Builds the ceilings' blocks for the current layers now (with the fixed box and ceilings
  /// on), where a query would at the rendering's second submission: for a tracker, so that no
  /// frame pays the tens to hundreds of milliseconds they take.
  void BuildQueryCeilings();
  /// BuildQueryCeilings().
  void PrepareForTracking() override { this->BuildQueryCeilings(); }
  /// The cell edge of the inside vote field (vp::InsideVoteField) each surface that is not
  /// closed gets (default 1 mm; 0: none). Where the centre ray's parity is no answer (an opening
  /// it passes through turns it), each answer in range takes the exact engine's vote of five rays
  /// (vp::InsideVote); the field answers most of them without a ray, the same vote, except in
  /// thin bands behind folds (micrometres behind most) where one ray counts the fold's two faces as one
  /// crossing and the rays disagree (the field there has the vote of either side). A batch's votes
  /// are most of its host work at 1.5M triangles per class. Set before Build().
  vtkSetMacro(VoteFieldCellMm, double);
  vtkGetMacro(VoteFieldCellMm, double);
  /// Submissions of a batch in flight at once: 1 or 2 (default). With two, the host writes the
  /// next submission's tips and ceilings and reads the previous one's answers (and votes on them)
  /// while the device works on the current one: on a GPU a batch should take about the longer of
  /// the device's and the host's work, not their sum (to be measured there). A submission's
  /// ceilings then start from the answers two submissions back, not one; the answers are the
  /// same, bit for bit, either way. On lavapipe, whose work runs on the host's cores, two gained
  /// 1-8 % at the median and 15-28 % at p95 (bench's batch_in_flight); one is for benchmarks
  /// and tests.
  void SetSubmissionsInFlight(int submissions);
  int GetSubmissionsInFlight() const { return this->SubmissionsInFlight; }
  enum BatchOrders
  {
    BatchOrderSpatial = 0,
    BatchOrderAsGiven = 1
  };
  /// The order in which a batch's tips go to the device. BatchOrderSpatial (default): along a
  /// Z-order curve through cubes a tile wide (vp::SpatialOrder), for batches of more than 8 tips,
  /// so that one submission's tips, and the device's neighbouring invocations, share the tiles
  /// they read; the results come back in the order given. BatchOrderAsGiven: as given. The
  /// answers are the same, bit for bit; what differs is the device's time (random tips, IRCADb
  /// patient 1, lavapipe: see bench's batch_order) and the host's sort (CallTimes::OrderMs). The
  /// answer a batch leaves for the next call's ceilings is the last one submitted. The whole
  /// instrument's search (ComputeProximityBatchWithin) keeps its order: its points come from an
  /// octree walk, in space order already, and sorting them again cost a frame of the penetration
  /// sweep some 15 us on lavapipe.
  void SetBatchOrder(int order);
  int GetBatchOrder() const { return this->BatchOrder; }
  /// Which Vulkan device (see vp::VulkanContext): empty (default) for the best one, an index, or
  /// part of a name.
  void SetDeviceSelector(const std::string& selector);
  const std::string& GetDeviceSelector() const { return this->DeviceSelector; }

  /// Renders the layers again now (after Build()). The engine renders by itself whenever the
  /// vessels or the box change; this is for benchmarks.
  void RenderLayers();

  /// The device in use; opens it when needed. Throws vp::DeviceError when there is none.
  std::string GetDeviceName();
  /// The bound on |reported - exact| of every distance, for the current settings (after Build()).
  double GetErrorBoundMm() const override;
  /// The box and cells in use (after Build(); for the moving box, the latest one).
  vp::DepthLayerGrid GetGrid() const;
  /// How many times the layers were rendered, and how long the last rendering took (ms).
  int GetNumberOfRenders() const;
  double GetLastRenderTimeMs() const;
  /// Triangles sent to the rasteriser after splitting the long ones (after Build()).
  std::size_t GetNumberOfRasterTriangles() const;

  /// One tip: a batch of one.
  void ComputeProximity(const double tip[3], const double* axis, vp::ProximityResult& result,
    const vp::ProximityResult* previous = nullptr) const override;
  /// Up to GetBatchCapacity() tips per GPU submission, nothing scanned on the host: the device picks
  /// each answer's closest cell, and the host reads 32 words per tip and class. The submission is
  /// recorded once per batch size and settings and then only resubmitted. With the moving box,
  /// tips are answered one at a time (each may need its own box).
  void ComputeProximityBatch(const Points& tips, const Points* axes, std::vector<vp::ProximityResult>& results) const override;
  /// The whole instrument's search: as ComputeProximityBatch without axes, but only surfaces
  /// within searchMm (at most the range) are found, and the distance bins are not used (each
  /// distance is the nearest marked cell's plus half a cell diagonal, within
  /// vp::DepthLayerGrid::ErrorBoundMm() of the truth). A shorter search visits fewer tiles: its
  /// cost follows the distance still to beat, not the range. Needs the fixed box.
  void ComputeProximityBatchWithin(const Points& points, double searchMm, std::vector<vp::ProximityResult>& results) const;
  /// The occupancy bits of the current layers, [class][pixel][word] (one bit per slice; see
  /// Shaders/DepthLayersCommon.glsl), copied to the host; empty before the first rendering.
  void CopyOccupancy(std::vector<std::uint32_t>& words) const;
  /// The crossing bits of the current layers (the pixel-centre ray's surface crossings, toggled
  /// per slice: their parity below a slice says inside), in the same layout; empty before the
  /// first rendering.
  void CopyCrossings(std::vector<std::uint32_t>& words) const;
  /// Where in its slice each crossing lies, in quarters: two planes in the crossings' layout, the
  /// quarter's high bit (halves) and its low bit (quarters), for a slice one crossing marks (with
  /// more, their parities). Empty before the first rendering.
  void CopyCrossingPlaces(std::vector<std::uint32_t>& halves, std::vector<std::uint32_t>& quarters) const;
  /// Tips per GPU submission (after a query): up to 4,096 on a GPU, where the tips of a batch
  /// run side by side, 256 on a CPU device, fewer when their records would pass 256 MB (a long
  /// range on small cells).
  std::size_t GetBatchCapacity() const;
  /// The device's own time for the latest query submission (all its dispatches, from the
  /// device's timestamps), in ms; negative when the device keeps no timestamps or before the
  /// first query. Beside the host's time, it tells what a query's round trip costs.
  double GetLastQueryDeviceMs() const;
  /// Where the latest call's time went (ComputeProximity, ComputeProximityBatch, ...), in ms:
  /// the device's own time summed over its submissions (negative without timestamps), the host's
  /// time submitting and waiting for them (device time included, except what the host spent on
  /// the other submission in flight), the host's inside votes on
  /// surfaces that are not closed (five rays a tip and class in range; the answers beyond the
  /// range, votes and all, count as read), the ceilings, the answers read, and the whole call
  /// (from the engine's lock; the results' set-up before it is the caller's).
  /// The device's time by stage, summed likewise: listing the tiles to visit (0 without a list),
  /// visiting them (the pixels' distances), and handing the answers to the host (the reduction);
  /// negative for a call of 8 points or fewer, which stamps no stages (a stamp between stages
  /// would cost a single tip a third of its time on lavapipe).
  struct CallTimes
  {
    double DeviceMs = 0.0;
    double DeviceListingMs = 0.0;
    double DeviceVisitingMs = 0.0;
    double DeviceReducingMs = 0.0;
    double SubmitWaitMs = 0.0;
    double VotesMs = 0.0;
    double CeilingsMs = 0.0; // the host's bounds per tip and class (SetQueryCeilings)
    double ReadMs = 0.0;     // the answers read into the results, votes excluded
    double OrderMs = 0.0;    // the tips put in space order and their results back (SetBatchOrder)
    double ListingMs = 0.0;  // the host's listing (ListingPassOnHost)
    double TotalMs = 0.0;
    std::size_t Submissions = 0;
    std::size_t Votes = 0;
    std::size_t TilesListed = 0; // by the device or the host, all submissions' tips and classes
  };
  CallTimes GetLastCallTimes() const;
  /// Tiles per tip within the latest submission's highest ceiling (summed over the classes: what
  /// it dispatched without a list), and the tiles of the order table within its search times the
  /// classes (what it dispatched without ceilings).
  std::size_t GetLastQueryTiles() const;
  std::size_t GetLastQueryTilesInRange() const;
  /// Tiles the latest submission listed (all its tips and classes; 0 when it listed none).
  std::size_t GetLastQueryTilesListed() const;
  /// Time to build the ceilings' blocks after the latest rendering (copying the occupancy to the
  /// host included), ms; 0 until they are built.
  double GetCeilingBuildTimeMs() const;
  const char* GetMethodName() const override { return "zbuffer"; }
  /// The device's name and "(Vulkan)".
  std::string GetDeviceDescription() override { return this->GetDeviceName() + " (Vulkan)"; }

protected:
  vtkZBufferVesselDistance();
  ~vtkZBufferVesselDistance() override;
  void BuildInternal() override;

private:
  vtkZBufferVesselDistance(const vtkZBufferVesselDistance&) = delete;
  void operator=(const vtkZBufferVesselDistance&) = delete;
  void Invalidate();
  /// The layers' bit planes (Shaders/DepthLayersCommon.glsl).
  enum class LayerPlane
  {
    Occupancy,
    Crossings,
    CrossingHalves,
    CrossingQuarters
  };
  /// A bit plane of the layers, copied to the host.
  void CopyLayer(LayerPlane plane, std::vector<std::uint32_t>& words) const;
  /// Width of one of the paper's distance bins; 0 when they are off.
  double BinWidthMm() const;
  /// Throws InputError unless each half of the moving box holds the range plus a cell.
  void CheckMovingBox(double cellMm) const;
  /// Every tip within searchMm; bins: whether the distance bins apply; spaceOrder: whether a
  /// batch may go in space order (SetBatchOrder).
  void AnswerAll(const Points& tips, const Points* axes, double searchMm, bool bins, bool spaceOrder,
    std::vector<vp::ProximityResult>& results) const;
  /// Writes each tip's ceilings for the next submission to ceilings (count x classes; lock held);
  /// returns how far from its tile the submission has to look, mm (the highest ceiling of a class
  /// not wholly beyond the search; below 0: nowhere).
  double WriteCeilings(const std::array<double, 3>* tips, std::size_t count, double searchMm,
    vp::zbuffer::AnswerCeiling* ceilings) const;
  /// Class c of a tip with no wall within the search: out of range, or inside however deep.
  void AnswerBeyondRange(std::uint32_t c, const double tip[3], bool centreRayInside, vp::ClassProximity& out) const;
  /// The exact engine of every class, made the first time a tip on a closed surface is deeper
  /// than the range (it measures the depth).
  void EnsureDeepEngine() const;
  /// A submission in flight and what reading its answers needs (vtkZBufferVesselDistanceInternals.h).
  struct Submission;
  /// Starts one submission for up to GetBatchCapacity() tips on the current layers, in one of
  /// the context's slots, without waiting for it (lock held, results begun).
  Submission StartBatch(const std::array<double, 3>* tips, std::size_t count, const std::array<double, 3>* axes,
    double searchMm, double binWidthMm, vp::ProximityResult* results, std::uint32_t slot) const;
  /// Waits for a submission and reads its answers from host-visible memory into its results,
  /// with the exact engine's inside vote on the surfaces that are not closed (lock held).
  void FinishBatch(const Submission& batch) const;
  /// A finished submission's answers into its results (lock held).
  void ReadAnswers(const Submission& batch) const;
  /// The tips in submissions of up to the batch capacity, up to SubmissionsInFlight at once.
  void SubmitAll(const std::array<double, 3>* tips, std::size_t count, const std::array<double, 3>* axes,
    double searchMm, double binWidth, vp::ProximityResult* results) const;

  /// The layers' grid around the vessels (fixed), or centred on their box until the first tip
  /// (moving); anchorMm: the centre of the vessels' box; cellMm: the cell edge chosen.
  vp::DepthLayerGrid PlaceGrid(double anchorMm[3], double& cellMm) const;

  int LayerMode = ExactIntervals;
  int BoxMode = FixedAroundVessels;
  double CellSizeMm = DefaultCellSizeMm;
  int ResolutionPx = 0;
  double MovingBoxSizeMm[3] = { DefaultMovingBoxSizeMm[0], DefaultMovingBoxSizeMm[1], DefaultMovingBoxSizeMm[2] };
  int DistanceBins = 0;
  int DirectionalLanes = 0;
  double VoteFieldCellMm = 1.0;
  int SubmissionsInFlight = 2;
  int BatchOrder = BatchOrderSpatial;
  int QueryPass = QueryPassByDevice;
  int TileListing = TileListingByDevice;
  int ListingPass = ListingPassByDevice;
  bool QueryCeilings = true;
  std::string DeviceSelector;

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
