#ifndef vpInsideVote_h
#define vpInsideVote_h

#include <algorithm>
#include <vector>

namespace vp
{
/// Inside or outside a surface that is not closed (holes, non-manifold edges, pieces wound the
/// wrong way, duplicated sheets: vp::MeshDefects), by the parity of its crossings along Rays
/// fixed rays from the point, crossings at the same distance along a ray counted once. Parity is
/// blind to winding; counting coincident crossings once makes it blind to a duplicated sheet (two
/// copies of a wall are one crossing, where counting both would turn the ray) and to a ray
/// through an edge or a vertex shared by several triangles; a small hole or a fin turns only the
/// rays that pass through it. The
/// engines count the crossings (Embree's rays in vtkExactVesselDistance, every triangle in
/// double in vtkBruteForceVesselDistance); the decision is made here, once.
struct InsideVote
{
  static constexpr int Rays = 5;
  /// Unit directions, none along an axis or a diagonal, so that a ray rarely runs along a
  /// mesh's edges or through its vertices.
  static constexpr double Directions[Rays][3] = {
    { 0.26726124, 0.53452248, 0.80178373 },
    { -0.70710678, 0.14142136, 0.69282032 },
    { 0.57735027, -0.61721340, -0.53452248 },
    { -0.30151134, -0.90453403, 0.30151134 },
    { 0.87287156, 0.21821789, -0.43643578 },
  };
  /// A point this close to the surface (mm) is on it, and outside, as VesselSurface::IsInside
  /// has it for a closed surface: touching is distance 0, not a breach.
  static constexpr double OnSurfaceMm = 1e-9;
  /// Crossings closer than this along a ray are one (mm): a duplicated wall's copies, the
  /// triangles meeting at an edge the ray passes through.
  static constexpr double CoincidentMm = 1e-3;
  /// The distinct crossings among the distances along one ray (sorted here).
  static int CountCrossings(std::vector<double>& distancesMm)
  {
    std::sort(distancesMm.begin(), distancesMm.end());
    int count = 0;
    for (std::size_t i = 0; i < distancesMm.size(); ++i)
    {
      count += i == 0 || distancesMm[i] - distancesMm[i - 1] > CoincidentMm ? 1 : 0;
    }
    return count;
  }
  /// Inside when most rays (3 of 5, the documented threshold) cross an odd number of times;
  /// uncertain when the rays disagree. The answer stays the majority's, so that the tips are
  /// classified right, and the danger level takes an uncertain answer as a breach
  /// (vp::ClassifyDanger): a breach is never hidden behind a defect.
  static bool Decide(const int crossings[Rays], bool& uncertain)
  {
    int inside = 0;
    for (int r = 0; r < Rays; ++r)
    {
      inside += crossings[r] % 2;
    }
    uncertain = inside != 0 && inside != Rays;
    return 2 * inside > Rays;
  }
};
} // namespace vp

#endif
