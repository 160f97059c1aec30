// The whole-instrument distance: FCL (the module's path, plain and warm-started) and our own
// bounding-sphere search, each against brute force over every triangle pair, and against each
// other on real vessels with a real instrument.
#include "vpAnalyticShapes.h"
#include "vpRigidTransform.h"
#include "vpTestSupport.h"
#include "vpTriangleGeometry.h"
#include "vtkExactVesselDistance.h"
#include "vtkFclSurfaceDistance.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkVesselMeshReader.h"
#include "vpBlockDistanceField.h"
#include "vpCellDistanceField.h"
#include "vpSurfaceSamples.h"
#include "vpVesselSurface.h"
#include "vtkZBufferSurfaceDistance.h"
#include "vtkZBufferVesselDistance.h"
#include "vpVulkanTestSupport.h"

#include <gtest/gtest.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace
{
const double Origin[3] = { 0, 0, 0 };

vtkSmartPointer<vtkPolyData> ToolShaft()
{
  const double z[3] = { 0, 0, 1 };
  const double centre[3] = { 0, 0, -40 };
  return vp::MakeCappedCylinder(centre, z, 1.5, 80.0, 16); // tip face at z = 0
}

/// Every tool triangle against every vessel triangle: the reference for the whole-surface distance.
double BruteForceSurfaceDistance(vtkPolyData* tool, const std::array<double, 16>& m, vtkPolyData* vessel)
{
  auto corners = [](vtkPolyData* mesh, const std::array<double, 16>* place) {
    std::vector<std::array<double, 9>> out;
    auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        std::array<double, 9> t{};
        const vtkIdType corner[3] = { ids[0], ids[k], ids[k + 1] };
        for (int c = 0; c < 3; ++c)
        {
          double p[3];
          mesh->GetPoint(corner[c], p);
          for (int r = 0; r < 3; ++r)
          {
            t[3 * c + r] = place ? (*place)[4 * r] * p[0] + (*place)[4 * r + 1] * p[1] + (*place)[4 * r + 2] * p[2] + (*place)[4 * r + 3] : p[r];
          }
        }
        out.push_back(t);
      }
    }
    return out;
  };
  const auto a = corners(tool, &m);
  const auto b = corners(vessel, nullptr);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : a)
  {
    for (const auto& t : b)
    {
      double p[3], q[3];
      best = std::min(best, vp::ClosestPointsOfTriangles(&s[0], &s[3], &s[6], &t[0], &t[3], &t[6], p, q));
    }
  }
  return std::sqrt(best);
}


/// The shaft and a sphere of radius 10 at the origin, measured by every calculator: our bounding-
/// sphere search, FCL as it comes, and FCL warm-started from the previous pose's answer (the
/// module's path). Brute force, most of these tests' time under the sanitizers, runs once a pose.
class InstrumentDistance : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Engine->AddVessel("portal_vein", this->Vessel);
    this->Engine->Build();
    auto plain = vtkSmartPointer<vtkFclSurfaceDistance>::New();
    plain->WarmStartOff();
    this->Calculators = { vtkSmartPointer<vtkScalpelSurfaceDistance>::New(), plain, vtkSmartPointer<vtkFclSurfaceDistance>::New() };
    for (auto& c : this->Calculators)
    {
      c->SetVesselDistance(this->Engine);
      c->SetToolSurface(this->Tool);
    }
    this->Previous.resize(this->Calculators.size());
  }
  /// Calculator k's answer at pose m, started from its answer at the pose before.
  vp::SurfaceProximity At(std::size_t k, const std::array<double, 16>& m)
  {
    std::vector<vp::SurfaceProximity> result;
    this->Calculators[k]->ComputeSurfaceProximity(m, result, this->Previous[k].empty() ? nullptr : &this->Previous[k]);
    EXPECT_EQ(result.size(), 1u);
    this->Previous[k] = result;
    return result.at(0);
  }
  std::string Name(std::size_t k) const
  {
    return k == 0 ? "spheres" : k == 1 ? "plain FCL" : "warm FCL";
  }
  vtkSmartPointer<vtkPolyData> Vessel = vp::MakeSphere(Origin, 10.0, 24, 48);
  vtkSmartPointer<vtkPolyData> Tool = ToolShaft();
  vtkNew<vtkExactVesselDistance> Engine;
  std::vector<vtkSmartPointer<vtkScalpelSurfaceDistance>> Calculators;
  std::vector<std::vector<vp::SurfaceProximity>> Previous;
};
} // namespace

// Random poses, some crossing the sphere; with the warm start, each pose also starts from the
// answer for the one before (a jump, the worst case for a warm start: the bound it gives is loose).
TEST_F(InstrumentDistance, EqualsBruteForceAndSeesTheShaftBeforeTheTip)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<double> angle(0.0, 2 * M_PI), offset(-25.0, 25.0);
  int touching = 0;
  for (int i = 0; i < 40; ++i)
  {
    const double axis[3] = { offset(random), offset(random), offset(random) };
    const vp::Matrix4 rotation = vp::RotationAboutAxis({ axis[0], axis[1], axis[2] }, angle(random), { offset(random), offset(random), offset(random) });
    const double reference = BruteForceSurfaceDistance(this->Tool, rotation, this->Vessel);
    for (std::size_t k = 0; k < this->Calculators.size(); ++k)
    {
      const vp::SurfaceProximity result = this->At(k, rotation);
      if (reference > this->Engine->GetRangeMm())
      {
        EXPECT_FALSE(result.InRange) << this->Name(k);
        continue;
      }
      ASSERT_TRUE(result.InRange) << this->Name(k) << " pose " << i;
      EXPECT_NEAR(result.DistanceMm, reference, 1e-9) << this->Name(k) << " pose " << i;
      if (reference > 0.0)
      {
        EXPECT_NEAR(std::sqrt(vp::Distance2(result.PointOnToolMm, result.PointOnVesselMm)), result.DistanceMm, 1e-9);
      }
    }
    touching += reference == 0.0 ? 1 : 0;
  }
  EXPECT_GT(touching, 0) << "no pose crossed the vessel: the draw no longer tests the crossing case";

  // The shaft passes 2 mm beside the sphere (tool axis along +y at x = 13.5, tip at y = -40):
  // the tip is 32 mm away, the surface 2 mm (less the facets' chord error).
  const vp::Matrix4 beside{ 1, 0, 0, 13.5, 0, 0, -1, -40, 0, 1, 0, 0, 0, 0, 0, 1 };
  const double reference = BruteForceSurfaceDistance(this->Tool, beside, this->Vessel);
  EXPECT_NEAR(reference, 2.0, 0.1);
  for (std::size_t k = 0; k < this->Calculators.size(); ++k)
  {
    const vp::SurfaceProximity result = this->At(k, beside);
    ASSERT_TRUE(result.InRange) << this->Name(k);
    EXPECT_NEAR(result.DistanceMm, reference, 1e-9) << this->Name(k);
  }
}

// A tracked approach in 0.4 mm steps, from 12 mm away through the wall and out: the warm start
// (the previous closest pair) must never hide a nearer pair that appears as the tool turns.
TEST_F(InstrumentDistance, TrackedApproachEqualsBruteForceEveryFrame)
{
  int inside = 0;
  for (int i = 0; i <= 60; ++i)
  {
    // The tip comes in along -x while the tool turns a degree a frame about y.
    vp::Matrix4 m = vp::RotationAboutAxis({ 0, 1, 0.2 }, -M_PI / 2 + 1.0 * M_PI / 180.0 * i, { 0, 0, 0 });
    m[3] = 22.0 - 0.4 * i;
    m[7] = 3.0;
    const double reference = BruteForceSurfaceDistance(this->Tool, m, this->Vessel);
    for (std::size_t k = 0; k < this->Calculators.size(); ++k)
    {
      const vp::SurfaceProximity result = this->At(k, m);
      ASSERT_TRUE(result.InRange) << this->Name(k) << " frame " << i;
      ASSERT_NEAR(result.DistanceMm, reference, 1e-9) << this->Name(k) << " frame " << i;
    }
    inside += reference == 0.0 ? 1 : 0;
  }
  EXPECT_GT(inside, 10);
}

namespace
{
/// Random marked cells of two classes on a grid: the occupancy bits and the cells (class, x, y, z).
std::vector<std::uint32_t> RandomOccupancy(
  const vp::DepthLayerGrid& grid, int count, unsigned seed, std::vector<std::array<int, 4>>& marked)
{
  std::vector<std::uint32_t> occupancy(grid.Pixels() * grid.Words() * 2, 0u);
  std::mt19937 random(seed);
  for (int i = 0; i < count; ++i)
  {
    const std::array<int, 4> cell{ i % 2 == 0 ? 0 : (i < count / 2 ? 0 : 1), std::uniform_int_distribution<int>(0, grid.Nx - 1)(random),
      std::uniform_int_distribution<int>(0, grid.Ny - 1)(random), std::uniform_int_distribution<int>(0, grid.Nz - 1)(random) };
    marked.push_back(cell);
    const std::size_t column = static_cast<std::size_t>(cell[0]) * grid.Pixels() + static_cast<std::size_t>(cell[2]) * grid.Nx + cell[1];
    occupancy[column * grid.Words() + cell[3] / 32] |= 1u << (cell[3] % 32);
  }
  return occupancy;
}

/// For any surface with a point in every marked cell of class c and none elsewhere, the distance
/// from p lies between these: the nearest marked box, and the least over the boxes of the
/// farthest point of one.
void SurfaceDistanceLimits(const vp::DepthLayerGrid& grid, const std::vector<std::array<int, 4>>& marked, int c,
  const double p[3], double& nearest, double& farthest)
{
  nearest = farthest = std::numeric_limits<double>::infinity();
  for (const auto& m : marked)
  {
    if (m[0] != c)
    {
      continue;
    }
    double near2 = 0.0, far2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double lo = grid.OriginMm[k] + m[k + 1] * (k < 2 ? grid.PixelMm : grid.SliceMm);
      const double hi = lo + (k < 2 ? grid.PixelMm : grid.SliceMm);
      const double g = std::max({ 0.0, lo - p[k], p[k] - hi });
      const double f = std::max(std::abs(p[k] - lo), std::abs(p[k] - hi));
      near2 += g * g;
      far2 += f * f;
    }
    nearest = std::min(nearest, std::sqrt(near2));
    farthest = std::min(farthest, std::sqrt(far2));
  }
}

bool InGrid(const vp::DepthLayerGrid& grid, const double p[3])
{
  for (int k = 0; k < 3; ++k)
  {
    if (p[k] < grid.OriginMm[k] || p[k] > grid.OriginMm[k] + grid.SizeMm(k))
    {
      return false;
    }
  }
  return true;
}
} // namespace

// The block field's bounds, against the distance to every marked cell's box: the lower never
// above it (or the search would skip a nearer sample) and, for blocks of two cells, never more
// than two block diagonals below it within the grid (or it would prune nothing); the upper never
// below the farthest a surface through the marked cells can be. Points inside and outside; the
// bounds of every class at once (BoundsMm) equal each class's.
TEST(BlockDistanceField, BoundsTheDistanceToTheMarkedCells)
{
  vp::DepthLayerGrid grid;
  grid.OriginMm[0] = -3.0;
  grid.OriginMm[1] = 2.0;
  grid.OriginMm[2] = 1.0;
  grid.PixelMm = grid.SliceMm = 0.5;
  grid.Nx = 21;
  grid.Ny = 13;
  grid.Nz = 40;
  std::vector<std::array<int, 4>> marked;
  const std::vector<std::uint32_t> occupancy = RandomOccupancy(grid, 12, 7, marked);
  const vp::BlockDistanceField field(grid, 2, occupancy, 1.0);
  ASSERT_EQ(field.BlockCells(), 2);
  const double slack = 2.0 * std::sqrt(3.0) * 1.0;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(-8.0, 16.0), y(-3.0, 14.0), z(-4.0, 26.0);
  int inside = 0;
  for (int i = 0; i < 3000; ++i)
  {
    const double p[3] = { x(random), y(random), z(random) };
    double lower[2], upper[2];
    field.BoundsMm(p, lower, upper); // every class at once: the same bounds
    for (int c = 0; c < 2; ++c)
    {
      ASSERT_EQ(lower[c], field.LowerBoundMm(c, p));
      ASSERT_EQ(upper[c], field.UpperBoundMm(c, p));
      double nearest, farthest;
      SurfaceDistanceLimits(grid, marked, c, p, nearest, farthest);
      const double bound = field.LowerBoundMm(c, p);
      ASSERT_LE(bound, nearest + 1e-9) << "class " << c << " at " << p[0] << "," << p[1] << "," << p[2];
      ASSERT_GE(field.UpperBoundMm(c, p), farthest - 1e-9) << "class " << c << " at " << p[0] << "," << p[1] << "," << p[2];
      const bool inGrid = InGrid(grid, p);
      inside += inGrid ? 1 : 0;
      ASSERT_TRUE(!inGrid || bound >= nearest - slack - 1e-9) << "class " << c << " at " << p[0] << "," << p[1] << "," << p[2];
    }
  }
  EXPECT_GT(inside, 500);
}

// The cell field's two bounds hold for any surface through the marked cells, inside the grid,
// beyond the field's reach (there from the coarse blocks) and outside the grid; within the reach
// they are never wider than twice BoundMm(); the descent ends in a marked cell no farther than
// the upper bound. With fewer cells allowed, a field cell covers several of the layers' and the
// same holds with its larger bound.
TEST(CellDistanceField, BoundsTheDistanceToAnySurfaceThroughTheMarkedCells)
{
  vp::DepthLayerGrid grid;
  grid.OriginMm[0] = -3.0;
  grid.OriginMm[1] = 2.0;
  grid.OriginMm[2] = 1.0;
  grid.PixelMm = grid.SliceMm = 0.25;
  grid.Nx = 130; // 32.5 mm: some points lie beyond the reach of 79.5 cells (19.9 mm)
  grid.Ny = 27;
  grid.Nz = 70;
  std::vector<std::array<int, 4>> marked;
  const std::vector<std::uint32_t> occupancy = RandomOccupancy(grid, 10, 11, marked);
  for (const std::size_t maxCells : { std::size_t(1) << 26, std::size_t(20000) })
  {
    const vp::CellDistanceField field(grid, 2, occupancy, {}, {}, {}, maxCells, 1.0);
    const int k = field.LayerCellsPerCell();
    EXPECT_TRUE(maxCells > 20000 ? k == 1 : k > 1) << k;
    EXPECT_NEAR(field.FineReachMm(), 16.0 * k * grid.PixelMm, 1e-12);
    EXPECT_NEAR(field.ReachMm(), 79.5 * k * grid.PixelMm, 1e-12);
    const double h = k * grid.HalfDiagonalMm();
    EXPECT_NEAR(field.BoundMm(), 2.0 * h + k * grid.PixelMm / 16.0, 2e-3 * h + 3e-4);
    std::mt19937 random(13);
    std::uniform_real_distribution<double> x(-8.0, 35.0), y(-3.0, 14.0), z(-4.0, 26.0);
    int withinReach = 0, withinFarReach = 0, beyondReach = 0, descended = 0;
    for (int i = 0; i < 4000; ++i)
    {
      const double p[3] = { x(random), y(random), z(random) };
      for (int c = 0; c < 2; ++c)
      {
        double nearest, farthest, low, high;
        SurfaceDistanceLimits(grid, marked, c, p, nearest, farthest);
        field.Bounds(c, p, low, high);
        ASSERT_LE(low, nearest + 1e-9) << "k " << k << " class " << c << " at " << p[0] << "," << p[1] << "," << p[2];
        ASSERT_GE(high, farthest - 1e-9) << "k " << k << " class " << c << " at " << p[0] << "," << p[1] << "," << p[2];
        if (InGrid(grid, p) && high < field.FineReachMm())
        {
          ++withinReach;
          ASSERT_LE(high - low, 2.0 * field.BoundMm() + 1e-9) << "k " << k << " at " << p[0] << "," << p[1] << "," << p[2];
        }
        else if (InGrid(grid, p) && high < field.ReachMm())
        {
          ++withinFarReach; // levels half a cell apart
          ASSERT_LE(high - low, 2.0 * field.BoundMm() + k * grid.PixelMm * 3.0 / 8.0 + 1e-9);
        }
        beyondReach += nearest > field.ReachMm() + 2.0 * field.BoundMm() ? 1 : 0;
        double point[3];
        if (field.NearestMarkedPoint(c, p, point))
        {
          ++descended;
          const double d = std::sqrt((point[0] - p[0]) * (point[0] - p[0]) + (point[1] - p[1]) * (point[1] - p[1]) +
            (point[2] - p[2]) * (point[2] - p[2]));
          ASSERT_LE(d, high + 1e-9);
          double pointNearest, pointFarthest;
          SurfaceDistanceLimits(grid, marked, c, point, pointNearest, pointFarthest);
          ASSERT_LE(pointNearest, k * 2.0 * grid.HalfDiagonalMm() + 1e-9) << "the descent did not end at a marked cell";
        }
      }
    }
    EXPECT_GT(withinReach, 100) << "k " << k;
    EXPECT_GT(withinFarReach, 100) << "k " << k;
    if (k == 1)
    {
      EXPECT_GT(beyondReach, 20);
    }
    EXPECT_GT(descended, 500) << "k " << k;
  }
}

// The instrument's samples as the whole-instrument search walks them: every sample in exactly one
// leaf, each leaf one cube of the leaf edge, each node's points one run made of its children's
// runs in order, at least two children above a leaf, and every point of a node inside its sphere
// (a point outside would let the search set aside the nearest sample).
TEST(SurfaceSamples, ATreeOfSpheresHoldsEverySampleOnce)
{
  const vp::VesselSurface tool("shaft", ToolShaft());
  const double spacing = 0.2, leafMm = 0.5;
  const vp::SurfaceSamples s = vp::SurfaceSamples::Of(tool.PointArray(), tool.TriangleArray(), spacing, leafMm);
  ASSERT_GT(s.Points.size(), 1000u);
  ASSERT_GT(s.NumberOfLeaves, 100u);
  ASSERT_GT(s.Nodes.size(), s.NumberOfLeaves);
  const vp::SurfaceSamples::Node& root = s.Nodes[s.Root()];
  EXPECT_EQ(root.First, 0u);
  EXPECT_EQ(root.Count, s.Points.size());
  std::vector<int> leafSeen(s.NumberOfLeaves, 0);
  std::vector<std::uint32_t> stack{ s.Root() };
  std::size_t internal = 0;
  while (!stack.empty())
  {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const vp::SurfaceSamples::Node& node = s.Nodes[n];
    ASSERT_GT(node.Count, 0u);
    for (std::uint32_t i = node.First; i < node.First + node.Count; ++i)
    {
      const auto& p = s.Points[i];
      const double d = std::sqrt(std::pow(p[0] - node.CentreMm[0], 2) + std::pow(p[1] - node.CentreMm[1], 2) +
        std::pow(p[2] - node.CentreMm[2], 2));
      ASSERT_LE(d, node.RadiusMm) << "node " << n << ", point " << i;
    }
    if (node.ChildCount == 0)
    {
      ASSERT_LT(n, s.NumberOfLeaves);
      ++leafSeen[n];
      EXPECT_LE(node.RadiusMm, std::sqrt(3.0) / 2.0 * leafMm + 1e-6) << "leaf " << n;
      const auto& first = s.Points[node.First];
      for (std::uint32_t i = node.First; i < node.First + node.Count; ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          ASSERT_EQ(std::floor(s.Points[i][k] / leafMm), std::floor(first[k] / leafMm)) << "leaf " << n;
        }
      }
      continue;
    }
    ++internal;
    ASSERT_GE(node.ChildCount, 2u) << "node " << n;
    std::uint32_t next = node.First;
    for (std::uint32_t j = 0; j < node.ChildCount; ++j)
    {
      const std::uint32_t child = s.Children[node.FirstChild + j];
      ASSERT_LT(child, n) << "children are made before their parent";
      ASSERT_EQ(s.Nodes[child].First, next) << "node " << n << ", child " << j;
      next += s.Nodes[child].Count;
      stack.push_back(child);
    }
    ASSERT_EQ(next, node.First + node.Count) << "node " << n;
  }
  EXPECT_EQ(internal + s.NumberOfLeaves, s.Nodes.size()) << "every node is reached from the root";
  EXPECT_EQ(std::count(leafSeen.begin(), leafSeen.end(), 1), static_cast<std::ptrdiff_t>(s.NumberOfLeaves));
  // Every sample lies on the surface's triangles' vertices after splitting: the corners stay.
  for (const auto& corner : tool.PointArray())
  {
    const bool kept = std::any_of(s.Points.begin(), s.Points.end(), [&](const std::array<double, 3>& p) { return p == corner; });
    ASSERT_TRUE(kept);
  }
}

// The z-buffer's whole instrument: on random poses and a tracked approach, each answer never
// above brute force and within its own bound below it, that bound never above the stated one (the field's plus half the
// spacing) while the distance is within the field's reach, and the closest pair about as far
// apart as the answer says.
TEST_F(InstrumentDistance, ZBufferSurfaceIsWithinItsBoundOfBruteForce)
{
  VP_REQUIRE_VULKAN();
  vtkNew<vtkZBufferVesselDistance> layers;
  layers->SetRangeMm(this->Engine->GetRangeMm());
  layers->AddVessel("portal_vein", this->Vessel);
  vtkNew<vtkZBufferSurfaceDistance> zbuffer;
  zbuffer->SetZBuffer(layers);
  zbuffer->SetToolSurface(this->Tool);
  zbuffer->Build();
  EXPECT_GT(zbuffer->GetNumberOfSamples(), 1000);
  const double bound = zbuffer->GetErrorBoundMm();
  // Two cell diagonals, a quarter of a cell's edge, the default spacing (half a 0.4 mm cell).
  EXPECT_NEAR(bound, 4.0 * layers->GetGrid().HalfDiagonalMm() + 0.4 / 8.0 + 0.2, 4e-3);

  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(0.0, 2 * M_PI), offset(-20.0, 20.0);
  std::vector<vp::SurfaceProximity> previous, result;
  int near = 0, contacts = 0;
  for (int i = 0; i < 30; ++i)
  {
    vp::Matrix4 m;
    if (i < 15)
    {
      m = vp::RotationAboutAxis({ offset(random), offset(random), offset(random) }, angle(random),
        { offset(random), offset(random), offset(random) });
    }
    else
    {
      m = vp::RotationAboutAxis({ 0, 1, 0.2 }, -M_PI / 2 + 1.0 * M_PI / 180.0 * i, { 0, 0, 0 });
      m[3] = 22.0 - 0.8 * (i - 15);
      m[7] = 3.0;
    }
    const double reference = BruteForceSurfaceDistance(this->Tool, m, this->Vessel);
    zbuffer->ComputeSurfaceProximity(m, result, previous.empty() ? nullptr : &previous);
    previous = result;
    ASSERT_EQ(result.size(), 1u);
    if (reference > layers->GetRangeMm() + bound)
    {
      EXPECT_FALSE(result[0].InRange) << "pose " << i;
      continue;
    }
    if (reference < layers->GetRangeMm() - bound)
    {
      ASSERT_TRUE(result[0].InRange) << "pose " << i;
    }
    if (!result[0].InRange)
    {
      continue;
    }
    EXPECT_LE(result[0].DistanceMm, reference + 1e-9) << "pose " << i << ": never farther than the truth";
    EXPECT_LE(reference, result[0].DistanceMm + result[0].ErrorBoundMm) << "pose " << i;
    if (reference == 0.0)
    {
      ++contacts;
      EXPECT_EQ(result[0].DistanceMm, 0.0) << "pose " << i << ": contact reads 0";
    }
    const double* a = result[0].PointOnToolMm;
    const double* b = result[0].PointOnVesselMm;
    const double pair = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    if (reference < 4.5) // within the field's fine reach and padding (6.4 mm) by more than the widest interval
    {
      ++near;
      EXPECT_LE(result[0].ErrorBoundMm, bound + 1e-12) << "pose " << i;
      // The pair ends in a marked cell: within its diagonal of the surface.
      EXPECT_LE(pair, result[0].DistanceMm + result[0].ErrorBoundMm + 1e-9) << "pose " << i;
      EXPECT_GE(pair, reference - 2.0 * layers->GetErrorBoundMm()) << "pose " << i;
    }
  }
  EXPECT_GT(near, 8) << "too few poses near the vessel";
  EXPECT_GT(contacts, 0) << "no pose touched the vessel";
}

namespace
{
/// IRCADb's three vessel systems of a patient and a PLUS instrument tracked along 0.4 mm steps
/// between points a few millimetres off the vessels: FCL warm-started (the module's exact path),
/// FCL as it comes (no warm start) and our bounding-sphere search agree to 1e-6 mm on every pose
/// and class.
void CompareOnIrcadb(const std::string& patient, const std::string& instrument)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  const std::string data = vp::test::TestDataDir();
  if (extracted.empty() || data.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: FCL vs our whole-instrument search on "
                 << patient << " not tested";
  }
  const std::string dir = extracted + "/ircadb/" + patient + "/MESHES_VTK/";
  vtkNew<vtkExactVesselDistance> engine;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  for (const auto& entry : { std::make_pair("portal_vein", "portalvein.vtk"), std::make_pair("hepatic_vein", "venoussystem.vtk"),
         std::make_pair("hepatic_artery", "artery.vtk") })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(dir + entry.second);
    reader->Read();
    meshes.push_back(reader->GetOutput());
    engine->AddVessel(entry.first, reader->GetOutput());
  }
  engine->Build();
  vtkNew<vtkSTLReader> stl;
  stl->SetFileName((data + "/plusmodelcatalog/" + instrument).c_str());
  stl->Update();
  ASSERT_GT(stl->GetOutput()->GetNumberOfPolys(), 0);
  vtkNew<vtkFclSurfaceDistance> fcl;
  vtkNew<vtkScalpelSurfaceDistance> spheres;
  for (vtkScalpelSurfaceDistance* s : { static_cast<vtkScalpelSurfaceDistance*>(fcl), spheres.Get() })
  {
    s->SetVesselDistance(engine);
    s->SetToolSurface(stl->GetOutput());
  }
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  auto waypoint = [&]() {
    vtkPolyData* v = meshes[std::uniform_int_distribution<std::size_t>(0, meshes.size() - 1)(random)];
    double p[3];
    v->GetPoint(std::uniform_int_distribution<vtkIdType>(0, v->GetNumberOfPoints() - 1)(random), p);
    for (double& x : p)
    {
      x += 4.0 * normal(random);
    }
    return std::array<double, 3>{ p[0], p[1], p[2] };
  };
  std::vector<vp::SurfaceProximity> previous;
  std::array<double, 3> from = waypoint();
  int compared = 0, touching = 0;
  for (int leg = 0; leg < 5; ++leg)
  {
    const std::array<double, 3> to = waypoint();
    for (int k = 0; k <= 20; ++k)
    {
      const double t = k / 20.0;
      vp::Matrix4 m = vp::RotationAboutAxis({ 1.0, 0.5, 0.2 }, 0.03 * (leg * 21 + k), { 0, 0, 0 });
      for (int a = 0; a < 3; ++a)
      {
        m[4 * a + 3] = from[a] + t * (to[a] - from[a]);
      }
      std::vector<vp::SurfaceProximity> a, b, plain;
      fcl->ComputeSurfaceProximity(m, a, previous.empty() ? nullptr : &previous);
      fcl->ComputeSurfaceProximity(m, plain);
      spheres->ComputeSurfaceProximity(m, b);
      previous = a;
      ASSERT_EQ(a.size(), b.size());
      ASSERT_EQ(a.size(), plain.size());
      for (std::size_t c = 0; c < a.size(); ++c)
      {
        ASSERT_EQ(a[c].InRange, b[c].InRange) << patient << " leg " << leg << " step " << k << " class " << c;
        ASSERT_EQ(a[c].InRange, plain[c].InRange) << patient << " leg " << leg << " step " << k << " class " << c;
        if (a[c].InRange)
        {
          ASSERT_NEAR(a[c].DistanceMm, b[c].DistanceMm, 1e-6) << patient << " leg " << leg << " step " << k << " class " << c;
          ASSERT_NEAR(a[c].DistanceMm, plain[c].DistanceMm, 1e-6) << patient << " leg " << leg << " step " << k << " class " << c;
          ++compared;
          touching += a[c].DistanceMm == 0.0 ? 1 : 0;
        }
      }
    }
    from = to;
  }
  EXPECT_GT(compared, 200);
  EXPECT_GT(touching, 0) << "no pose touched a vessel: the crossing case went untested";
}
} // namespace

TEST(InstrumentDistanceOnIrcadb, FclEqualsOurSearchPatient1Scalpel)
{
  CompareOnIrcadb("3Dircadb1.1", "Scalpel.stl");
}

TEST(InstrumentDistanceOnIrcadb, FclEqualsOurSearchPatient4Cautery)
{
  CompareOnIrcadb("3Dircadb1.4", "Cautery.stl");
}

namespace
{
/// The z-buffer's whole instrument against FCL's exact one at 500 random poses (a PLUS instrument
/// turned at random, placed a few millimetres from a random vessel vertex): never farther than
/// exact, exact never beyond its bound, and that bound at most the stated one within 4.5 mm of a
/// vessel.
void CompareZBufferWithFcl(const std::string& label, const std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>>& vessels,
  const std::string& instrument)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: the z-buffer's whole instrument against FCL on " << label << " not tested";
  }
  vtkNew<vtkSTLReader> stl;
  stl->SetFileName((data + "/plusmodelcatalog/" + instrument).c_str());
  stl->Update();
  ASSERT_GT(stl->GetOutput()->GetNumberOfPolys(), 0);
  vtkNew<vtkExactVesselDistance> engine;
  vtkNew<vtkZBufferVesselDistance> layers;
  for (const auto& v : vessels)
  {
    engine->AddVessel(v.first, v.second);
    layers->AddVessel(v.first, v.second);
  }
  engine->Build();
  vtkNew<vtkFclSurfaceDistance> fcl;
  fcl->SetVesselDistance(engine);
  fcl->SetToolSurface(stl->GetOutput());
  vtkNew<vtkZBufferSurfaceDistance> zbuffer;
  zbuffer->SetZBuffer(layers);
  zbuffer->SetToolSurface(stl->GetOutput());
  zbuffer->Build();
  const double stated = zbuffer->GetErrorBoundMm();
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  int compared = 0, near = 0, touching = 0, disagreements = 0;
  for (int pose = 0; pose < 500; ++pose)
  {
    vtkPolyData* v = vessels[std::uniform_int_distribution<std::size_t>(0, vessels.size() - 1)(random)].second;
    double p[3];
    v->GetPoint(std::uniform_int_distribution<vtkIdType>(0, v->GetNumberOfPoints() - 1)(random), p);
    const vp::Matrix4 m = vp::RotationAboutAxis({ normal(random), normal(random), normal(random) + 1e-3 }, angle(random),
      { p[0] + 4.0 * normal(random), p[1] + 4.0 * normal(random), p[2] + 4.0 * normal(random) });
    std::vector<vp::SurfaceProximity> exact, z;
    fcl->ComputeSurfaceProximity(m, exact);
    zbuffer->ComputeSurfaceProximity(m, z);
    ASSERT_EQ(exact.size(), z.size());
    for (std::size_t c = 0; c < z.size(); ++c)
    {
      if (exact[c].InRange != z[c].InRange)
      {
        // Only at the edge of the range, where the z-buffer's bound leaves it open: never a class
        // within range that it calls out of range.
        ++disagreements;
        ASSERT_TRUE(z[c].InRange) << label << " pose " << pose << " class " << c << ": exact " << exact[c].DistanceMm;
        EXPECT_GE(z[c].DistanceMm + z[c].ErrorBoundMm, layers->GetRangeMm() - 1e-9) << label << " pose " << pose << " class " << c;
        continue;
      }
      if (!z[c].InRange)
      {
        continue;
      }
      ++compared;
      const double truth = exact[c].DistanceMm;
      ASSERT_LE(z[c].DistanceMm, truth + 1e-9) << label << " pose " << pose << " class " << c << ": farther than exact";
      ASSERT_LE(truth, z[c].DistanceMm + z[c].ErrorBoundMm + 1e-9) << label << " pose " << pose << " class " << c;
      touching += truth == 0.0 ? 1 : 0;
      if (truth < 4.5)
      {
        ++near;
        EXPECT_LE(z[c].ErrorBoundMm, stated + 1e-9) << label << " pose " << pose << " class " << c;
      }
    }
  }
  EXPECT_GT(compared, 1000) << label;
  EXPECT_GT(near, 100) << label;
  EXPECT_GT(touching, 10) << label;
  EXPECT_LT(disagreements, 100) << label;
}

std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> ReadIrcadbVessels(const std::string& patient)
{
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> vessels;
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    return vessels;
  }
  for (const auto& entry : { std::make_pair("portal_vein", "portalvein.vtk"), std::make_pair("hepatic_vein", "venoussystem.vtk"),
         std::make_pair("hepatic_artery", "artery.vtk") })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(extracted + "/ircadb/" + patient + "/MESHES_VTK/" + entry.second);
    reader->Read();
    vessels.emplace_back(entry.first, reader->GetOutput());
  }
  return vessels;
}
} // namespace

TEST(ZBufferInstrumentDistance, NeverFartherThanFclOnThePhantomScalpel)
{
  VP_REQUIRE_VULKAN();
  const std::string dir = vp::test::MakeTempDir("zbuffer-phantom");
  ASSERT_EQ(vp::test::RunTool(dir, "phantom -o " + dir).ExitCode, 0);
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> vessels;
  for (const char* name : { "portal_vein", "hepatic_artery", "hepatic_vein" })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(dir + "/" + name + ".stl");
    reader->Read();
    vessels.emplace_back(name, reader->GetOutput());
  }
  CompareZBufferWithFcl("phantom", vessels, "Scalpel.stl");
}

TEST(ZBufferInstrumentDistance, NeverFartherThanFclOnIrcadbPatient1Scalpel)
{
  VP_REQUIRE_VULKAN();
  const auto vessels = ReadIrcadbVessels("3Dircadb1.1");
  if (vessels.empty())
  {
    GTEST_SKIP() << "IRCADb archives not extracted: the z-buffer's whole instrument on patient 1 not tested";
  }
  CompareZBufferWithFcl("IRCADb patient 1", vessels, "Scalpel.stl");
}

TEST(ZBufferInstrumentDistance, NeverFartherThanFclOnIrcadbPatient4Cautery)
{
  VP_REQUIRE_VULKAN();
  const auto vessels = ReadIrcadbVessels("3Dircadb1.4");
  if (vessels.empty())
  {
    GTEST_SKIP() << "IRCADb archives not extracted: the z-buffer's whole instrument on patient 4 not tested";
  }
  CompareZBufferWithFcl("IRCADb patient 4", vessels, "Cautery.stl");
}
