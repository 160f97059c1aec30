// vtkZBufferVesselDistance, rasterising: the vessels' triangles uploaded, the depth layers and their
// summaries created, and every class rendered into them (RasterizeLayers.comp, SummarizeColumns.comp,
// SummarizeTiles.comp).
#include "vtkZBufferVesselDistanceInternals.h"

#include "vpEdgeSplitting.h"
#include "vpInputError.h"

#include "RasterizeLayers_comp_spv.h"
#include "QueryProximityPerPixel_comp_spv.h"
#include "QueryProximity_comp_spv.h"
#include "ReduceProximity_comp_spv.h"
#include "SummarizeColumns_comp_spv.h"
#include "SummarizeTiles_comp_spv.h"

#include <chrono>
#include <cstring>

using namespace vp::zbuffer;
using vp::CoarseAcross;

void vtkZBufferVesselDistance::Internals::UploadGeometry(
  const std::vector<std::shared_ptr<const vp::VesselSurface>>& surfaces, double cellMm)
{
  vp::VulkanContext& context = *this->Context;
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  this->FirstTriangle.clear();
  this->TriangleCount.clear();
  for (const auto& surface : surfaces)
  {
    auto points = surface->PointArray();
    auto triangles = surface->TriangleArray();
    vp::SplitLongEdges(points, triangles, MaxEdgeCells * cellMm);
    const std::uint32_t base = static_cast<std::uint32_t>(positions.size() / 3);
    this->FirstTriangle.push_back(static_cast<std::uint32_t>(indices.size() / 3));
    this->TriangleCount.push_back(static_cast<std::uint32_t>(triangles.size()));
    for (const auto& p : points)
    {
      for (int k = 0; k < 3; ++k)
      {
        positions.push_back(static_cast<float>(p[k] - this->AnchorMm[k]));
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
  this->RasterTriangles = indices.size() / 3;
  if (positions.size() * 4 > context.Limits().maxStorageBufferRange ||
    indices.size() * 4 > context.Limits().maxStorageBufferRange)
  {
    throw vp::InputError("(vessels)", "too many triangles for one Vulkan buffer on this device");
  }
  using Placement = vp::GpuBuffer::Placement;
  this->Positions = std::make_unique<vp::GpuBuffer>(context, positions.size() * 4, Placement::Device);
  this->Positions->Upload(positions.data(), positions.size() * 4);
  this->Indices = std::make_unique<vp::GpuBuffer>(context, indices.size() * 4, Placement::Device);
  this->Indices->Upload(indices.data(), indices.size() * 4);
}

void vtkZBufferVesselDistance::Internals::CreateLayers(VkDeviceSize layerBytes)
{
  vp::VulkanContext& context = *this->Context;
  const std::uint32_t classes = this->Classes();
  using Placement = vp::GpuBuffer::Placement;
  const VkDeviceSize rangeBytes = 2ull * this->Grid.Pixels() * std::max(classes, 1u) * 4ull;
  // The tiles' ranges, then the coarse tiles'.
  const VkDeviceSize tileBytes = 2ull *
    static_cast<VkDeviceSize>(this->Grid.TilesX() * this->Grid.TilesY() + CoarseAcross(this->Grid.TilesX()) * CoarseAcross(this->Grid.TilesY())) *
    std::max(classes, 1u) * 4ull;
  this->Occupancy = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  this->Crossings = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  this->CrossingHalves = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  this->CrossingQuarters = std::make_unique<vp::GpuBuffer>(context, layerBytes, Placement::Device);
  this->DepthRanges = std::make_unique<vp::GpuBuffer>(context, rangeBytes, Placement::Device);
  this->TileRanges = std::make_unique<vp::GpuBuffer>(context, tileBytes, Placement::Device);

  this->Raster = std::make_unique<vp::ComputeKernel>(
    context, RasterizeLayers_comp, RasterizeLayers_comp_size, 6, static_cast<std::uint32_t>(sizeof(RasterParameters)));
  this->Raster->BindBuffers({ this->Positions->Handle(), this->Indices->Handle(), this->Occupancy->Handle(),
    this->Crossings->Handle(), this->CrossingHalves->Handle(), this->CrossingQuarters->Handle() });
  this->Columns = std::make_unique<vp::ComputeKernel>(
    context, SummarizeColumns_comp, SummarizeColumns_comp_size, 2, static_cast<std::uint32_t>(sizeof(ColumnParameters)));
  this->Columns->BindBuffers({ this->Occupancy->Handle(), this->DepthRanges->Handle() });
  this->Tiles = std::make_unique<vp::ComputeKernel>(
    context, SummarizeTiles_comp, SummarizeTiles_comp_size, 2, static_cast<std::uint32_t>(sizeof(TileParameters)));
  this->Tiles->BindBuffers({ this->DepthRanges->Handle(), this->TileRanges->Handle() });
  this->Query = std::make_unique<vp::ComputeKernel>(
    context, QueryProximity_comp, QueryProximity_comp_size, 15, static_cast<std::uint32_t>(sizeof(QueryParameters)));
  this->QueryPerPixel = std::make_unique<vp::ComputeKernel>(context, QueryProximityPerPixel_comp,
    QueryProximityPerPixel_comp_size, 15, static_cast<std::uint32_t>(sizeof(QueryParameters)));
  this->Reduce = std::make_unique<vp::ComputeKernel>(
    context, ReduceProximity_comp, ReduceProximity_comp_size, 5, static_cast<std::uint32_t>(sizeof(ReduceParameters)));
}

void vtkZBufferVesselDistance::Internals::Render()
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
  TileParameters tiles{ g.Nx, g.Ny, g.TilesX(), g.TilesY(), classes, rangeStride, TilePx, 0 };
  const std::uint32_t tileCount = static_cast<std::uint32_t>(g.TilesX() * g.TilesY()) * classes;
  TileParameters coarse{ g.Nx, g.Ny, CoarseAcross(g.TilesX()), CoarseAcross(g.TilesY()), classes, rangeStride,
    TilePx * CoarseTiles, 2 * tileCount };
  const std::uint32_t coarseCount = static_cast<std::uint32_t>(coarse.TilesX * coarse.TilesY) * classes;

  this->Context->Submit([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, this->Occupancy->Handle(), 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, this->Crossings->Handle(), 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, this->CrossingHalves->Handle(), 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, this->CrossingQuarters->Handle(), 0, VK_WHOLE_SIZE, 0u);
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

void vtkZBufferVesselDistance::Internals::CopyLayer(LayerPlane plane, std::vector<std::uint32_t>& words)
{
  words.clear();
  const vp::GpuBuffer* planes[] = { this->Occupancy.get(), this->Crossings.get(), this->CrossingHalves.get(),
    this->CrossingQuarters.get() };
  const vp::GpuBuffer* layer = planes[static_cast<int>(plane)];
  if (this->Rendered && layer)
  {
    this->CopyBuffer(*layer, words);
  }
}

void vtkZBufferVesselDistance::Internals::CopyBuffer(const vp::GpuBuffer& buffer, std::vector<std::uint32_t>& words)
{
  const VkDeviceSize bytes = buffer.Size();
  vp::GpuBuffer host(*this->Context, bytes, vp::GpuBuffer::Placement::Host);
  this->Context->Submit([&](VkCommandBuffer cmd) {
    VkBufferCopy region{ 0, 0, bytes };
    vkCmdCopyBuffer(cmd, buffer.Handle(), host.Handle(), 1, &region);
    vp::ComputeKernel::Barrier(cmd);
  });
  words.resize(static_cast<std::size_t>(bytes / 4));
  std::memcpy(words.data(), host.Mapped(), words.size() * 4);
}
