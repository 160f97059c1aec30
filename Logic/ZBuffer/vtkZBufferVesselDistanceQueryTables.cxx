// vtkZBufferVesselDistance, the query's tables: the tiles within the range in their nearest-first
// order (fine and coarse), the buffers sized for them, and the answers' ceilings from the coarse
// blocks of the current rendering.
#include "vtkZBufferVesselDistanceInternals.h"

#include <algorithm>
#include <chrono>
#include <cstring>

using namespace vp::zbuffer;
using vp::CoarseAcross;
using vp::NearestFirst;

void vtkZBufferVesselDistance::Internals::PrepareOrder(double rangeMm)
{
  if (this->OrderRangeMm == rangeMm)
  {
    return;
  }
  const vp::DepthLayerGrid& g = this->Grid;
  this->FineTable = NearestFirst(rangeMm, TilePx, g.PixelMm, std::max(g.TilesX(), g.TilesY()));
  this->CoarseTable = NearestFirst(
    rangeMm, TilePx * CoarseTiles, g.PixelMm, std::max(CoarseAcross(g.TilesX()), CoarseAcross(g.TilesY())));
  const std::vector<std::array<std::int32_t, 2>>& order = this->FineTable.Offsets;
  const int reach = this->FineTable.Reach;
  const int width = 2 * reach + 1;
  std::vector<std::uint32_t> entryOf(order.size());
  for (std::size_t e = 0; e < order.size(); ++e)
  {
    entryOf[static_cast<std::size_t>((order[e][1] + reach) * width + order[e][0] + reach)] = static_cast<std::uint32_t>(e);
  }
  this->HostListing.SetTables(this->FineTable, this->CoarseTable, entryOf);
  this->Context->WaitAll();
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
  // the host can write it. A slot each (vp::VulkanContext::Slots), for the submissions in flight.
  const VkDeviceSize slots = vp::VulkanContext::Slots;
  this->HostState = std::make_unique<vp::GpuBuffer>(*this->Context, stateBytes * slots, Placement::Host);
  this->Points = std::make_unique<vp::GpuBuffer>(
    *this->Context, sizeof(PointRecord) * this->Capacity * slots, Placement::HostToDevice);
  this->Ceilings = std::make_unique<vp::GpuBuffer>(
    *this->Context, sizeof(AnswerCeiling) * classes * this->Capacity * slots, Placement::HostToDevice);
  this->DispatchSizes = std::make_unique<vp::GpuBuffer>(
    *this->Context, 2 * sizeof(VkDispatchIndirectCommand) * slots, Placement::HostToDevice);
  if (!this->StampCopies)
  {
    const VkDeviceSize stampBytes = vp::VulkanContext::StampsPerSlot * sizeof(std::uint64_t) * slots;
    this->StampCopies = std::make_unique<vp::GpuBuffer>(*this->Context, stampBytes, Placement::Host);
    std::memset(this->StampCopies->Mapped(), 0, stampBytes);
  }
  // At most one listed tile per answer and entry: half the records' bytes.
  this->TileList = std::make_unique<vp::GpuBuffer>(*this->Context, recordBytesPerTip * this->Capacity / 2, Placement::Device);
  this->TileListSize = std::make_unique<vp::GpuBuffer>(*this->Context, 16, Placement::Device);
  this->HostTileList = std::make_unique<vp::GpuBuffer>(
    *this->Context, sizeof(HostListItem) * HostListItemsPerPoint * this->Capacity * slots, Placement::HostToDevice);
  for (vp::ComputeKernel* query : { this->Query.get(), this->QueryPerPixel.get() })
  {
    query->BindBuffers({ this->Occupancy->Handle(), this->Crossings->Handle(), this->DepthRanges->Handle(),
      this->TileRanges->Handle(), this->Order->Handle(), this->State->Handle(), this->Records->Handle(),
      this->Points->Handle(), this->Choices->Handle(), this->Ceilings->Handle(), this->TileList->Handle(),
      this->TileListSize->Handle(), this->CoarseOrder->Handle(), this->EntryIndex->Handle(),
      this->HostTileList->Handle() });
  }
  this->Reduce->BindBuffers({ this->State->Handle(), this->Records->Handle(), this->HostState->Handle(),
    this->Choices->Handle(), this->TileListSize->Handle() });
  // The state starts reset; every query leaves it so.
  const std::uint32_t answers = this->Capacity * classes;
  const ReduceParameters reset{ 0, answers, this->OrderCount, 0 };
  this->Context->Submit([&](VkCommandBuffer cmd) {
    this->Reduce->Record(cmd, &reset, (answers + 63) / 64);
    vp::ComputeKernel::Barrier(cmd);
  });
  this->OrderRangeMm = rangeMm;
}

const vp::BlockDistanceField* vtkZBufferVesselDistance::Internals::PrepareCeilings(bool now)
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
  this->CopyLayer(LayerPlane::Occupancy, occupancy);
  // Blocks of 4 cells, at least 1.6 mm: about a 64th of the cells (a few MB at 0.4 mm), and
  // the bound a few millimetres above the truth, which leaves a tip a few hundred tiles of
  // a 50 mm range's thousands.
  this->CeilingBlocks = std::make_unique<vp::BlockDistanceField>(
    this->Grid, static_cast<int>(this->Classes()), occupancy, std::max(1.6, 4.0 * this->Grid.PixelMm));
  this->CeilingBlocksRender = this->Renders;
  this->CeilingBuildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return this->CeilingBlocks.get();
}

const vp::HostTileListing& vtkZBufferVesselDistance::Internals::PrepareHostListing()
{
  if (this->HostListingRender != this->Renders)
  {
    std::vector<std::uint32_t> ranges;
    this->CopyBuffer(*this->TileRanges, ranges);
    this->HostListing.SetRanges(std::move(ranges), this->Grid.TilesX(), this->Grid.TilesY(),
      static_cast<int>(this->Classes()), this->Grid.PixelMm, this->Grid.SliceMm);
    this->HostListingRender = this->Renders;
  }
  return this->HostListing;
}

long long vtkZBufferVesselDistance::Internals::ListOnHost(
  const QueryParameters& q, const std::array<double, 3>* tips, std::size_t count, bool perPixel, std::uint32_t slot)
{
  const vp::HostTileListing& listing = this->PrepareHostListing();
  const std::uint32_t classes = this->Classes();
  const std::size_t first = this->FirstPointOf(slot);
  const AnswerCeiling* ceilings = this->HostCeilings.data();
  // Item 0 holds the count; the rest of the slot's items, the list (lanes first per answer).
  auto* items = static_cast<HostListItem*>(this->HostTileList->Mapped()) + first * HostListItemsPerPoint;
  const std::size_t room = HostListItemsPerPoint * this->Capacity - 1;
  const std::uint32_t laneItems =
    perPixel ? (static_cast<std::uint32_t>(q.DirectionalLanes) + 63) / 64 : static_cast<std::uint32_t>(q.DirectionalLanes);
  std::vector<std::uint32_t> entries;
  std::size_t used = 0;
  long long tiles = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    float tip[3];
    this->GridTip(tips[i].data(), tip);
    for (std::uint32_t c = 0; c < classes; ++c)
    {
      const std::uint32_t answer = static_cast<std::uint32_t>(i * classes + c);
      entries.clear();
      const AnswerCeiling& ceiling = ceilings[answer];
      listing.List(tip, static_cast<int>(c), ceiling.Mm, ceiling.Entries,
        static_cast<std::uint32_t>(q.CoarseCount), q.RangeMm, entries);
      if (used + laneItems + entries.size() > room)
      {
        return -1;
      }
      for (std::uint32_t lane = 0; lane < laneItems; ++lane)
      {
        items[1 + used++] = { answer, LaneItem + lane };
      }
      for (const std::uint32_t entry : entries)
      {
        items[1 + used++] = { answer, entry };
      }
      tiles += static_cast<long long>(entries.size());
    }
  }
  items[0] = { static_cast<std::uint32_t>(used), 0u };
  const std::uint32_t n = static_cast<std::uint32_t>(used);
  static_cast<VkDispatchIndirectCommand*>(this->DispatchSizes->Mapped())[2 * slot + 1] =
    VkDispatchIndirectCommand{ perPixel ? n : (n + 63) / 64, 1, 1 };
  return tiles;
}
