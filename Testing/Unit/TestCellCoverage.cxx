// The share of a lattice cell behind a wall taken as a plane (vp::CellShareInside, the closed
// form) and behind two (vp::CellShareInsideBoth): against slabs and corners whose volume is known,
// and against a dense count of the cube's points for planes in every direction.
#include "vpCellCoverage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
/// The share of the unit cube's points inside every wall, counted on a 96^3 grid: the reference.
double CountedShare(const vp::WallPlane* walls, int count)
{
  const int n = 96;
  long long in = 0;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int k = 0; k < n; ++k)
      {
        const double y[3] = { (i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5, (k + 0.5) / n - 0.5 };
        bool inside = true;
        for (int w = 0; w < count; ++w)
        {
          const double* m = walls[w].OutwardNormal;
          inside = inside && m[0] * y[0] + m[1] * y[1] + m[2] * y[2] < walls[w].OffsetMm;
        }
        in += inside ? 1 : 0;
      }
    }
  }
  return static_cast<double>(in) / (static_cast<double>(n) * n * n);
}

vp::WallPlane RandomWall(std::mt19937& random)
{
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(-0.9, 0.9);
  vp::WallPlane w;
  double length = 0.0;
  for (double& c : w.OutwardNormal)
  {
    c = normal(random);
    length += c * c;
  }
  for (double& c : w.OutwardNormal)
  {
    c /= std::sqrt(length);
  }
  w.OffsetMm = offset(random);
  return w;
}
} // namespace

TEST(CellCoverage, AWallSquareToAnAxisCutsASlab)
{
  for (double depth : { -0.6, -0.5, -0.3, 0.0, 0.2, 0.45, 0.7 })
  {
    const vp::WallPlane wall{ { 0, 1, 0 }, depth };
    // A cell of edge 2 mm: the share is the slab's thickness over the edge.
    EXPECT_NEAR(vp::CellShareInside({ { 0, 1, 0 }, 2.0 * depth }, 2.0), std::clamp(0.5 + depth, 0.0, 1.0), 1e-6) << depth;
    EXPECT_NEAR(vp::CubeFractionBelowPlane(wall.OutwardNormal, depth), std::clamp(0.5 + depth, 0.0, 1.0), 1e-6) << depth;
  }
}

TEST(CellCoverage, AWallAcrossACornerCutsATetrahedron)
{
  // n = (1,1,1)/sqrt3 and this offset put the plane at u + v + w = 3 - legs in the cube [0,1]^3:
  // beyond it, at the corner (1, 1, 1), a tetrahedron of three legs, volume legs^3 / 6.
  const double s = 1.0 / std::sqrt(3.0);
  for (double legs : { 0.1, 0.4, 0.9 })
  {
    const double offset = (1.5 - legs) * s; // the plane x + y + z = 1.5 - legs
    const double n[3] = { s, s, s };
    EXPECT_NEAR(vp::CubeFractionBelowPlane(n, offset), 1.0 - legs * legs * legs / 6.0, 1e-9) << legs;
  }
  // Through the centre, any direction halves the cube.
  const double tilted[3] = { 0.6, -0.48, 0.64 };
  EXPECT_NEAR(vp::CubeFractionBelowPlane(tilted, 0.0), 0.5, 1e-9);
}

TEST(CellCoverage, OneWallInAnyDirectionMatchesACount)
{
  std::mt19937 random(35);
  for (int trial = 0; trial < 40; ++trial)
  {
    const vp::WallPlane wall = RandomWall(random);
    EXPECT_NEAR(vp::CellShareInside(wall, 1.0), CountedShare(&wall, 1), 2e-3) << "trial " << trial;
  }
}

TEST(CellCoverage, TwoWallsShareOnlyWhatIsBehindBoth)
{
  // Opposite walls: a slab between them, or nothing where they coincide (a tip face on the wall).
  EXPECT_NEAR(vp::CellShareInsideBoth({ { 0, 0, 1 }, 0.2 }, { { 0, 0, -1 }, 0.1 }, 1.0), 0.3, 1e-9);
  EXPECT_NEAR(vp::CellShareInsideBoth({ { 0, 0, 1 }, 0.0 }, { { 0, 0, -1 }, 0.0 }, 1.0), 0.0, 1e-9);
  EXPECT_NEAR(vp::CellShareInsideBoth({ { 1, 0, 0 }, 0.0 }, { { 0, 1, 0 }, 0.0 }, 1.0), 0.25, 1e-9);
  std::mt19937 random(3535);
  for (int trial = 0; trial < 40; ++trial)
  {
    const vp::WallPlane walls[2] = { RandomWall(random), RandomWall(random) };
    // Exact along one axis, 8 x 8 columns across: within a column's share of each wall's trace.
    EXPECT_NEAR(vp::CellShareInsideBoth(walls[0], walls[1], 1.0), CountedShare(walls, 2), 0.03) << "trial " << trial;
  }
  // One wall twice is that wall.
  const vp::WallPlane once = RandomWall(random);
  EXPECT_NEAR(vp::CellShareInsideBoth(once, once, 1.0), vp::CellShareInside(once, 1.0), 0.02);
}
