// vtkZBufferVesselDistance, submitting: the device, the points written where the query reads
// them, the query's submission recorded once per batch size and parameters, and the host's votes
// for the classes whose surface is not closed.
#include "vtkZBufferVesselDistanceInternals.h"

#include "vpClock.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace vp::zbuffer;

vp::VulkanContext& vtkZBufferVesselDistance::Internals::Device(const std::string& selector)
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

void vtkZBufferVesselDistance::Internals::Release()
{
  if (this->Context)
  {
    this->Context->Drain(); // nothing in flight uses what is freed here (and, from the destructor, no throw)
  }
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
  this->CrossingHalves.reset();
  this->CrossingQuarters.reset();
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
  this->StampCopies.reset();
  this->DispatchSizes.reset();
  this->TileList.reset();
  this->TileListSize.reset();
  this->HostTileList.reset();
  this->HostListingRender = -1;
  this->CeilingBlocks.reset();
  this->CeilingBlocksRender = -1;
  this->CeilingBuildMs = 0.0;
  this->Last.clear();
  this->LastRender = -1;
  this->LastSlot = 0;
  this->Rendered = false;
  this->OrderRangeMm = -1.0;
  this->Capacity = 0;
}

void vtkZBufferVesselDistance::Internals::VoteInside(const std::vector<InsideVote>& votes, const std::array<double, 3>* tips, vp::ProximityResult* results)
{
  const double startMs = vp::NowMs();
  ForEachAnswer(votes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const InsideVote& v = votes[k];
      vp::ClassProximity& out = results[v.Tip].Classes[v.Class];
      out.Inside = this->Votes->VoteInside(this->ExactIndex[v.Class], tips[v.Tip].data(), v.DistanceMm, out.InsideUncertain);
    }
  });
  this->LastCall.VotesMs += vp::NowMs() - startMs;
  this->LastCall.Votes += votes.size();
}

void vtkZBufferVesselDistance::Internals::WritePoints(
  const std::array<double, 3>* tips, std::size_t count, const std::array<double, 3>* axes, std::uint32_t slot)
{
  auto* points = static_cast<PointRecord*>(this->Points->Mapped()) + this->FirstPointOf(slot);
  for (std::size_t i = 0; i < count; ++i)
  {
    PointRecord& p = points[i];
    p = PointRecord{};
    this->GridTip(tips[i].data(), p.Tip);
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

vp::PreparedCommands& vtkZBufferVesselDistance::Internals::PreparedQueryFor(const QueryParameters& q, std::uint32_t n,
  std::uint32_t slot, bool perPixel, int listing, bool listPerInvocation, bool hostList, bool stages,
  std::uint32_t nearEntries, std::uint32_t laneSlots)
{
  const std::uint32_t orderCount = static_cast<std::uint32_t>(q.OrderCount);
  auto prepared = std::find_if(this->Prepared.begin(), this->Prepared.end(), [&](const PreparedQuery& p) {
    return p.Points == n && p.Slot == slot && p.PerPixel == perPixel && p.Listing == listing &&
      p.ListPerInvocation == listPerInvocation && p.HostList == hostList && p.Stages == stages &&
      std::memcmp(&p.Parameters, &q, sizeof q) == 0;
  });
  if (prepared == this->Prepared.end())
  {
    if (this->Prepared.size() >= MaxPrepared)
    {
      this->Context->WaitAll(); // the other slot's commands may be in flight
      this->Prepared.clear();
    }
    const std::uint32_t answers = n * this->Classes();
    const ReduceParameters copy{ 1, answers, orderCount,
      static_cast<std::uint32_t>(this->FirstPointOf(slot) * this->Classes()) };
    const VkDeviceSize sizesAt = 2 * sizeof(VkDispatchIndirectCommand) * slot;
    PreparedQuery entry;
    entry.Points = n;
    entry.Slot = slot;
    entry.PerPixel = perPixel;
    entry.Listing = listing;
    entry.ListPerInvocation = listPerInvocation;
    entry.HostList = hostList;
    entry.Stages = stages;
    entry.Parameters = q;
    entry.Commands = std::make_unique<vp::PreparedCommands>(*this->Context, [&](VkCommandBuffer cmd) {
      auto stamp = [&](StampOf which) {
        if (stages || which == SubmissionStart || which == SubmissionEnd)
        {
          this->Context->Stamp(cmd, which, slot);
        }
      };
      this->Context->ResetStamps(cmd, slot);
      stamp(SubmissionStart);
      if (listing == 0 || hostList)
      {
        stamp(TilesListed); // none listed here: every stamp copied is written, or its copy would wait
      }
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
        visit(VisitOrderedTiles, perPixel, 0, nearEntries, 0, *this->DispatchSizes, sizesAt);
      }
      if (listing == 0)
      {
        visit(VisitOrderedTiles, perPixel, nearEntries, orderCount, laneSlots, *this->DispatchSizes, sizesAt + second);
      }
      else if (hostList)
      {
        // The host's list, lanes and tiles, in one dispatch it sized (ListOnHost).
        visit(VisitHostListedTiles, listing == 2, 0, 0, 0, *this->DispatchSizes, sizesAt + second);
      }
      else
      {
        // The listing: workgroups per answer (DispatchSizes' second), each looping over its
        // share of the answer's lanes and entries.
        visit(listPerInvocation ? SelectTilesPerAnswer : SelectTiles, false, nearEntries, orderCount, 0, *this->DispatchSizes,
          sizesAt + second);
        stamp(TilesListed);
        visit(VisitListedTiles, listing == 2, 0, 0, 0, *this->TileListSize, 4);
      }
      stamp(TilesVisited);
      this->Reduce->Record(cmd, &copy, (answers + 63) / 64); // into the host-visible answers, and resets
      // The stamp waits for the answers (bottom of the pipe); one barrier then makes the answers
      // and the stamps' copy visible to the host, and orders the next submission after this one.
      stamp(SubmissionEnd);
      this->Context->CopyStamps(cmd, slot, stages ? vp::VulkanContext::StampsPerSlot : SubmissionEnd + 1, this->StampCopies->Handle(),
        vp::VulkanContext::StampsPerSlot * sizeof(std::uint64_t) * slot);
      vp::ComputeKernel::Barrier(cmd);
    });
    this->Prepared.push_back(std::move(entry));
    prepared = this->Prepared.end() - 1;
  }
  return *prepared->Commands;
}

void vtkZBufferVesselDistance::Internals::BuildVotes(const std::vector<std::shared_ptr<const vp::VesselSurface>>& surfaces,
  const std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>>& meshes, double voteFieldCellMm, double rangeMm)
{
  this->Votes = nullptr;
  this->Deep = nullptr;
  this->ExactIndex.assign(surfaces.size(), -1);
  for (std::size_t c = 0; c < surfaces.size(); ++c)
  {
    if (!surfaces[c]->IsClosed())
    {
      if (!this->Votes)
      {
        this->Votes = vtkSmartPointer<vtkExactVesselDistance>::New();
        this->Votes->SetVoteFieldCellMm(voteFieldCellMm);
        this->Votes->SetRangeMm(rangeMm); // the field reaches the range beyond each vessel
      }
      this->ExactIndex[c] = this->Votes->GetNumberOfVessels();
      this->Votes->AddVessel(meshes[c].first, meshes[c].second);
    }
  }
  if (this->Votes)
  {
    this->Votes->Build();
  }
}
