#ifndef vpSpatialOrder_h
#define vpSpatialOrder_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vp
{
/// The points' indices along a Z-order (Morton) curve through cubes of edgeMm from originMm, 1,024
/// cubes along each axis (points beyond them go to the nearest one), ties in their given order;
/// fewer than 2^32 points (an index is 32 bits).
/// A batch of random tips submitted in this order has neighbours next to each other: the device's
/// neighbouring invocations walk and read nearly the same tiles, where in the given order each
/// reads its own corner of the layers (lavapipe: a fifth less device time per batch; see
/// vtkZBufferVesselDistance::SetBatchOrder).
std::vector<std::uint32_t> SpatialOrder(
  const std::array<double, 3>* points, std::size_t count, const double originMm[3], double edgeMm);
} // namespace vp

#endif
