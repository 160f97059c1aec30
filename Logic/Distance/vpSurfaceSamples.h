#ifndef vpSurfaceSamples_h
#define vpSurfaceSamples_h

#include <array>
#include <cstdint>
#include <vector>

namespace vp
{
/// Points on a triangulated surface such that every point of the surface lies within SpacingMm
/// of one of them, grouped into small clusters, each with a centre and a radius holding all its
/// points: an instrument as the z-buffer's whole-instrument search sees it.
///
/// Made by splitting every edge longer than spacing x sqrt(3) (vp::SplitLongEdges, longest edge
/// first) and keeping the vertices: a triangle's every point lies within its longest edge over
/// sqrt(3) of a corner (the equilateral triangle's circumradius is the worst case). So the least
/// distance from the samples to a set is within SpacingMm above the least from the surface.
struct SurfaceSamples
{
  double SpacingMm = 0.0;
  std::vector<std::array<double, 3>> Points; ///< ordered by cluster
  struct Cluster
  {
    std::array<double, 3> CentreMm;
    double RadiusMm = 0.0;
    std::uint32_t First = 0; ///< its points: Points[First, First + Count)
    std::uint32_t Count = 0;
  };
  std::vector<Cluster> Clusters;

  /// Samples the surface (model coordinates) at spacingMm; clusters are the points of one cube
  /// of clusterMm.
  static SurfaceSamples Of(std::vector<std::array<double, 3>> points, std::vector<std::array<std::int32_t, 3>> triangles,
    double spacingMm, double clusterMm);
};
} // namespace vp

#endif
