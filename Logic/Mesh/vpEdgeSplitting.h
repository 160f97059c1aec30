#ifndef vpEdgeSplitting_h
#define vpEdgeSplitting_h

#include <array>
#include <cstdint>
#include <vector>

namespace vp
{
/// Splits every triangle with an edge longer than maxEdgeMm by repeated longest-edge bisection.
/// The midpoint of an edge is shared by the two triangles on it, so a watertight mesh stays
/// watertight. Returns the number of triangles added.
std::size_t SplitLongEdges(std::vector<std::array<double, 3>>& points,
  std::vector<std::array<std::int32_t, 3>>& triangles, double maxEdgeMm);
} // namespace vp

#endif
