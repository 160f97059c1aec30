#ifndef vpSurfaceSamples_h
#define vpSurfaceSamples_h

#include <array>
#include <cstdint>
#include <vector>

namespace vp
{
/// Points on a triangulated surface such that every point of the surface lies within SpacingMm
/// of one of them, held in a tree of spheres: an instrument as the z-buffer's whole-instrument
/// search sees it.
///
/// Made by splitting every edge longer than spacing x sqrt(3) (vp::SplitLongEdges, longest edge
/// first) and keeping the vertices: a triangle's every point lies within its longest edge over
/// sqrt(3) of a corner (the equilateral triangle's circumradius is the worst case). So the least
/// distance from the samples to a set is within SpacingMm above the least from the surface.
///
/// The tree: the leaves are the cubes of clusterMm the points fall in; a node above is a cube of
/// twice the edge of those below (an octree, the points in Morton order, so that every node's
/// points are one run of Points). A cube holding a single cube below is not a node of its own:
/// every node but a leaf has at least two children. Each node has a centre and a radius holding
/// all its points, so that a search can set aside a far part of the instrument (a handle 10 cm
/// from any vessel) with one bound, instead of one per leaf.
struct SurfaceSamples
{
  double SpacingMm = 0.0;
  std::vector<std::array<double, 3>> Points; ///< in Morton order of the leaves
  struct Node
  {
    std::array<double, 3> CentreMm{ { 0.0, 0.0, 0.0 } };
    double RadiusMm = 0.0;
    std::uint32_t First = 0; ///< its points: Points[First, First + Count)
    std::uint32_t Count = 0;
    std::uint32_t FirstChild = 0; ///< its children: Nodes[Children[FirstChild, FirstChild + ChildCount)]
    std::uint32_t ChildCount = 0; ///< 0 for a leaf
  };
  std::vector<Node> Nodes; ///< the leaves first, the root last
  std::vector<std::uint32_t> Children;
  std::size_t NumberOfLeaves = 0;

  std::uint32_t Root() const { return static_cast<std::uint32_t>(this->Nodes.size() - 1); }

  /// Samples the surface (model coordinates) at spacingMm, leaves of clusterMm.
  static SurfaceSamples Of(std::vector<std::array<double, 3>> points, std::vector<std::array<std::int32_t, 3>> triangles,
    double spacingMm, double clusterMm);
};
} // namespace vp

#endif
