// The demo's built-in data: the procedural liver phantom (its grid, vessel trees and DICOM
// series), the default CUSA handpiece and the scalpel path designed through the phantom.
#include "vpCusaHandpiece.h"
#include "vpDemoTrajectory.h"
#include "vpDicomLabelSeriesReader.h"
#include "vpInputError.h"
#include "vpLiverPhantom.h"
#include "vpModelTestSupport.h"
#include "vpScalpelLoader.h"
#include "vpScalpelTipFinder.h"
#include "vpTestSupport.h"
#include "vpVesselLabelTable.h"

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#ifndef VP_SOURCE_DIR
#error "VP_SOURCE_DIR must name the source tree (for Resources/)"
#endif

namespace
{
using Point = std::array<double, 3>;

const char* const VesselClassNames[] = { "portal_vein", "hepatic_artery", "hepatic_vein" };

/// One phantom for the whole file: it takes a fraction of a second, but many tests read it.
const vp::LiverPhantom& Phantom()
{
  static const vp::LiverPhantom phantom = vp::MakeLiverPhantom();
  return phantom;
}

const vp::DemoTrajectory& Trajectory()
{
  static const vp::DemoTrajectory trajectory = vp::DesignDemoTrajectory(Phantom());
  return trajectory;
}

const std::uint8_t* Voxels(const vp::LabelGrid& grid)
{
  return static_cast<const std::uint8_t*>(grid.Labels->GetScalarPointer());
}

long long CountVoxels(const vp::LabelGrid& grid)
{
  const std::uint8_t* v = Voxels(grid);
  return std::count_if(v, v + grid.Labels->GetNumberOfPoints(), [](std::uint8_t x) { return x != 0; });
}

/// Number of 26-connected components of the non-zero voxels.
int Components26(const vp::LabelGrid& grid)
{
  int d[3];
  grid.Labels->GetDimensions(d);
  const std::uint8_t* v = Voxels(grid);
  const std::size_t n = static_cast<std::size_t>(d[0]) * d[1] * d[2];
  std::vector<bool> seen(n, false);
  int components = 0;
  std::vector<std::size_t> stack;
  for (std::size_t s = 0; s < n; ++s)
  {
    if (!v[s] || seen[s])
    {
      continue;
    }
    ++components;
    seen[s] = true;
    stack.push_back(s);
    while (!stack.empty())
    {
      const std::size_t at = stack.back();
      stack.pop_back();
      const int i = static_cast<int>(at % d[0]), j = static_cast<int>((at / d[0]) % d[1]),
                k = static_cast<int>(at / (static_cast<std::size_t>(d[0]) * d[1]));
      for (int dk = -1; dk <= 1; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di)
          {
            const int a = i + di, b = j + dj, c = k + dk;
            if (a < 0 || b < 0 || c < 0 || a >= d[0] || b >= d[1] || c >= d[2])
              continue;
            const std::size_t w = (static_cast<std::size_t>(c) * d[1] + b) * d[0] + a;
            if (v[w] && !seen[w])
            {
              seen[w] = true;
              stack.push_back(w);
            }
          }
    }
  }
  return components;
}

Point Lerp(const Point& a, const Point& b, double t)
{
  return { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]) };
}

/// Radius of the largest ball about p (LPS) holding only voxels of the mask: the distance to the
/// nearest voxel centre outside it (so between the true radius and about a voxel more).
double InscribedRadiusMm(const vp::LabelGrid& grid, const Point& p, double searchMm)
{
  int d[3];
  grid.Labels->GetDimensions(d);
  const auto& m = grid.IjkToLps; // axis-aligned: diagonal steps
  const std::uint8_t* v = Voxels(grid);
  double best = std::numeric_limits<double>::infinity();
  int from[3], to[3];
  for (int a = 0; a < 3; ++a)
  {
    const double step = m[static_cast<std::size_t>(5 * a)], origin = m[static_cast<std::size_t>(4 * a + 3)];
    from[a] = std::max(0, static_cast<int>(std::floor((p[static_cast<std::size_t>(a)] - searchMm - origin) / step)));
    to[a] = std::min(d[a] - 1, static_cast<int>(std::ceil((p[static_cast<std::size_t>(a)] + searchMm - origin) / step)));
  }
  for (int k = from[2]; k <= to[2]; ++k)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int i = from[0]; i <= to[0]; ++i)
      {
        if (v[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i])
          continue;
        const double x = m[0] * i + m[3] - p[0], y = m[5] * j + m[7] - p[1], z = m[10] * k + m[11] - p[2];
        best = std::min(best, std::sqrt(x * x + y * y + z * z));
      }
  return best;
}

const vp::PhantomStructure& StructureOfClass(const std::string& className)
{
  const vp::PhantomStructure* s = Phantom().FindClass(className);
  if (!s)
  {
    throw std::runtime_error("no structure of class " + className);
  }
  return *s;
}

Point TipOf(const vp::TrackedPose& pose)
{
  return { pose.ModelToWorld[3], pose.ModelToWorld[7], pose.ModelToWorld[11] };
}

double Distance(const Point& a, const Point& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
} // namespace

// ------------------------------------------------------------------------------------------------
// The phantom

// A liver-sized grid of 1 mm voxels, axial and axis-aligned in LPS, in the patient's right upper
// abdomen, small enough for the demo (about 4 M voxels, under the 5 M budget).
TEST(LiverPhantom, GridIsLiverSizedAndAxisAligned)
{
  const vp::LiverPhantom& phantom = Phantom();
  ASSERT_EQ(phantom.Structures.size(), 4u);
  int d[3];
  phantom.Structures[0].Mask.Labels->GetDimensions(d);
  EXPECT_EQ(d[0], 199);
  EXPECT_EQ(d[1], 149);
  EXPECT_EQ(d[2], 135);
  EXPECT_LT(static_cast<double>(d[0]) * d[1] * d[2], 5.0e6);
  const auto& m = phantom.Structures[0].Mask.IjkToLps;
  const std::array<double, 16> expected = { 1, 0, 0, -162, 0, 1, 0, -56, 0, 0, 1, -26, 0, 0, 0, 1 };
  for (std::size_t i = 0; i < 16; ++i)
  {
    EXPECT_DOUBLE_EQ(m[i], expected[i]) << "IjkToLps[" << i << "]";
  }
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_DOUBLE_EQ(phantom.Structures[0].Mask.SpacingMm(a), 1.0);
  }
  const double centreX = m[3] + 0.5 * (d[0] - 1);
  EXPECT_LT(centreX, -40.0) << "the liver lies on the patient's right (negative x in LPS)";
  for (const vp::PhantomStructure& s : phantom.Structures)
  {
    int ds[3];
    s.Mask.Labels->GetDimensions(ds);
    EXPECT_TRUE(ds[0] == d[0] && ds[1] == d[1] && ds[2] == d[2]) << s.Name;
    EXPECT_EQ(s.Mask.IjkToLps, m) << s.Name;
    EXPECT_EQ(s.Mask.Labels->GetScalarType(), VTK_UNSIGNED_CHAR) << s.Name;
  }
}

// Names as the label table knows them (IRCADb-style folder names) and the classes it gives them.
TEST(LiverPhantom, StructuresAreNamedForTheLabelTable)
{
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  const std::vector<std::pair<std::string, std::string>> expected = { { "liver", "liver" },
    { "portalvein", "portal_vein" }, { "hepaticartery", "hepatic_artery" }, { "hepaticvein", "hepatic_vein" } };
  ASSERT_EQ(Phantom().Structures.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    EXPECT_EQ(Phantom().Structures[i].Name, expected[i].first);
    EXPECT_EQ(Phantom().Structures[i].ClassName, expected[i].second);
    EXPECT_EQ(table.ClassOfName(expected[i].first), expected[i].second);
  }
}

// The voxel counts are the phantom's fingerprint: the generator draws its own random numbers, so
// every platform must produce exactly these. A liver of about 1.5 litres (an adult's).
TEST(LiverPhantom, VoxelCountsAreReproducible)
{
  const std::map<std::string, long long> expected = { { "liver", 1481777 }, { "portal_vein", 21634 },
    { "hepatic_artery", 2135 }, { "hepatic_vein", 72094 } };
  for (const auto& [className, voxels] : expected)
  {
    EXPECT_EQ(CountVoxels(StructureOfClass(className).Mask), voxels) << className;
  }
  // A second run gives the same trees.
  const vp::LiverPhantom again = vp::MakeLiverPhantom();
  for (const char* c : VesselClassNames)
  {
    const auto& a = Phantom().Centrelines.at(c);
    const auto& b = again.Centrelines.at(c);
    ASSERT_EQ(a.size(), b.size()) << c;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      EXPECT_EQ(a[i].StartMm, b[i].StartMm);
      EXPECT_EQ(a[i].EndMm, b[i].EndMm);
      EXPECT_EQ(a[i].StartRadiusMm, b[i].StartRadiusMm);
    }
  }
}

// Every structure is one piece: each vessel system a single tree.
TEST(LiverPhantom, EachStructureIsOneConnectedComponent)
{
  for (const vp::PhantomStructure& s : Phantom().Structures)
  {
    EXPECT_GT(CountVoxels(s.Mask), 0) << s.Name;
    EXPECT_EQ(Components26(s.Mask), 1) << s.Name;
  }
}

// Vessels of different systems never share or touch a voxel (not even diagonally): their
// surfaces stay apart, as the distance engines must tell one system from another.
TEST(LiverPhantom, VesselSystemsDoNotTouch)
{
  const vp::LabelGrid& grid = Phantom().Structures[0].Mask;
  int d[3];
  grid.Labels->GetDimensions(d);
  const std::size_t n = static_cast<std::size_t>(d[0]) * d[1] * d[2];
  std::vector<std::uint8_t> label(n, 0);
  for (int c = 0; c < 3; ++c)
  {
    const std::uint8_t* v = Voxels(StructureOfClass(VesselClassNames[c]).Mask);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (v[i])
      {
        ASSERT_EQ(label[i], 0) << "voxel " << i << " in two vessel systems";
        label[i] = static_cast<std::uint8_t>(c + 1);
      }
    }
  }
  long long touching = 0;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        const std::uint8_t here = label[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i];
        if (!here)
          continue;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
            {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a >= d[0] || b >= d[1] || c >= d[2])
                continue;
              const std::uint8_t there = label[(static_cast<std::size_t>(c) * d[1] + b) * d[0] + a];
              touching += there && there != here ? 1 : 0;
            }
      }
  EXPECT_EQ(touching, 0);
}

// The analytic trees keep MinimumGapMm between the surfaces of different systems everywhere,
// and the veins sit in the liver.
TEST(LiverPhantom, AnalyticTreesKeepTheirGapAndLieInTheLiver)
{
  const auto& trees = Phantom().Centrelines;
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      if (a == b)
        continue;
      double gap = std::numeric_limits<double>::infinity();
      for (const vp::VesselSegment& s : trees.at(VesselClassNames[a]))
      {
        for (int t = 0; t <= 20; ++t)
        {
          const double u = t / 20.0;
          const double r = s.StartRadiusMm + u * (s.EndRadiusMm - s.StartRadiusMm);
          gap = std::min(gap, vp::TreeSignedDistanceMm(trees.at(VesselClassNames[b]), Lerp(s.StartMm, s.EndMm, u)) - r);
        }
      }
      EXPECT_GE(gap, vp::LiverPhantom::MinimumGapMm) << VesselClassNames[a] << " to " << VesselClassNames[b];
    }
  }
  // The portal trunk, the artery beside it and the vena cava reach out of the liver, as they do;
  // the branches grown from them (all below 8.4 mm, apart from the artery's trunk) stay inside.
  const vp::LabelGrid& liver = StructureOfClass("liver").Mask;
  int d[3];
  liver.Labels->GetDimensions(d);
  const auto& m = liver.IjkToLps;
  auto inLiver = [&](const Point& p)
  {
    const int i = static_cast<int>(std::lround((p[0] - m[3]) / m[0]));
    const int j = static_cast<int>(std::lround((p[1] - m[7]) / m[5]));
    const int k = static_cast<int>(std::lround((p[2] - m[11]) / m[10]));
    return i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2] &&
      Voxels(liver)[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i] != 0;
  };
  for (const char* c : VesselClassNames)
  {
    const auto& tree = trees.at(c);
    int checked = 0, outside = 0;
    for (std::size_t s = std::string(c) == "hepatic_artery" ? 2 : 0; s < tree.size(); ++s)
    {
      if (tree[s].StartRadiusMm >= 4.2)
        continue;
      for (int t = 0; t <= 10; ++t)
      {
        ++checked;
        outside += inLiver(Lerp(tree[s].StartMm, tree[s].EndMm, t / 10.0)) ? 0 : 1;
      }
    }
    EXPECT_GT(checked, 100) << c;
    EXPECT_EQ(outside, 0) << c;
  }
}

// Calibres as designed: portal trunk 12.5 mm, right and left branches 9-10 mm (Murray's law),
// hepatic trunks 9-10 mm at the confluence beside a 22 mm vena cava, artery 4.5 mm; down to 3 mm
// for the veins and 2 mm for the artery.
TEST(LiverPhantom, VesselCalibresAreAsDesigned)
{
  const auto& trees = Phantom().Centrelines;
  struct Range
  {
    const char* Class;
    double LargestDiameterMm, SmallestDiameterMm;
  };
  for (const Range& r : { Range{ "portal_vein", 12.5, 3.0 }, Range{ "hepatic_artery", 4.5, 2.0 },
         Range{ "hepatic_vein", 22.0, 3.0 } })
  {
    double largest = 0, smallest = std::numeric_limits<double>::infinity();
    for (const vp::VesselSegment& s : trees.at(r.Class))
    {
      largest = std::max({ largest, s.StartRadiusMm, s.EndRadiusMm });
      smallest = std::min({ smallest, s.StartRadiusMm, s.EndRadiusMm });
    }
    EXPECT_NEAR(2 * largest, r.LargestDiameterMm, 0.01) << r.Class;
    EXPECT_NEAR(2 * smallest, r.SmallestDiameterMm, 0.2) << r.Class;
    EXPECT_GT(trees.at(r.Class).size(), std::string(r.Class) == "hepatic_artery" ? 15u : 100u) << r.Class;
  }
  // The three hepatic trunks leave the vena cava (the tree's 22 mm segments) at 9-10 mm.
  const auto& hepatic = trees.at("hepatic_vein");
  std::vector<vp::VesselSegment> cava;
  std::copy_if(hepatic.begin(), hepatic.end(), std::back_inserter(cava),
    [](const vp::VesselSegment& s) { return s.StartRadiusMm >= 10.0; });
  EXPECT_EQ(cava.size(), 2u);
  int trunks = 0;
  for (const vp::VesselSegment& s : hepatic)
  {
    if (s.StartRadiusMm < 10.0 && vp::TreeSignedDistanceMm(cava, s.StartMm) < -5.0)
    {
      ++trunks;
      EXPECT_GE(2 * s.StartRadiusMm, 9.0);
      EXPECT_LE(2 * s.StartRadiusMm, 10.0);
    }
  }
  EXPECT_EQ(trunks, 3);
  // Murray's law at the portal bifurcation: r^3 = r1^3 + r2^3.
  const auto& portal = trees.at("portal_vein");
  const vp::VesselSegment& trunkEnd = portal[1];
  double sumOfCubes = 0;
  for (const vp::VesselSegment& s : portal)
  {
    if (s.StartMm == trunkEnd.EndMm)
    {
      sumOfCubes += std::pow(s.StartRadiusMm, 3);
    }
  }
  EXPECT_NEAR(sumOfCubes, std::pow(trunkEnd.EndRadiusMm, 3), 1e-6);
}

// The voxels hold the designed calibre: the largest ball about the trunks' centrelines fits their
// radius to within a voxel.
TEST(LiverPhantom, InscribedRadiusMatchesTheTrunks)
{
  for (const char* c : VesselClassNames)
  {
    const vp::VesselSegment& trunk = Phantom().Centrelines.at(c).front();
    const Point mid = Lerp(trunk.StartMm, trunk.EndMm, 0.5);
    const double designed = 0.5 * (trunk.StartRadiusMm + trunk.EndRadiusMm);
    const double measured = InscribedRadiusMm(StructureOfClass(c).Mask, mid, designed + 3);
    EXPECT_NEAR(measured, designed, 1.0) << c << " at " << mid[0] << "," << mid[1] << "," << mid[2];
  }
}

// Other voxel sizes sample the same anatomy: the centrelines do not depend on the grid.
TEST(LiverPhantom, VoxelSizeChangesOnlyTheSampling)
{
  vp::LiverPhantomOptions options;
  options.VoxelMm = 2.0;
  const vp::LiverPhantom coarse = vp::MakeLiverPhantom(options);
  int d[3];
  coarse.Structures[0].Mask.Labels->GetDimensions(d);
  EXPECT_NEAR(d[0], 100, 2);
  EXPECT_NEAR(d[1], 75, 2);
  EXPECT_NEAR(d[2], 68, 2);
  EXPECT_DOUBLE_EQ(coarse.Structures[0].Mask.SpacingMm(0), 2.0);
  EXPECT_NEAR(CountVoxels(coarse.Structures[0].Mask) * 8.0, 1481777.0, 0.02 * 1481777.0);
  for (const char* c : VesselClassNames)
  {
    ASSERT_EQ(coarse.Centrelines.at(c).size(), Phantom().Centrelines.at(c).size()) << c;
    EXPECT_EQ(coarse.Centrelines.at(c).back().EndMm, Phantom().Centrelines.at(c).back().EndMm) << c;
  }
  options.VoxelMm = 0.0;
  EXPECT_THROW(vp::MakeLiverPhantom(options), vp::InputError);
}

// The DICOM series read back as the same masks, in the same place, with the names the label
// table maps to the classes (IRCADb's MASKS_DICOM layout: one folder per structure).
TEST(LiverPhantom, DicomSeriesRoundTrip)
{
  const std::string folder = vp::test::MakeTempDir("liverphantom") + "/masks";
  vp::WriteLiverPhantomDicom(Phantom(), folder);
  for (const vp::PhantomStructure& s : Phantom().Structures)
  {
    EXPECT_TRUE(std::filesystem::exists(folder + "/" + s.Name + "/image_0")) << s.Name;
  }
  const vp::LabelStructures read =
    vp::DicomLabelSeriesReader::ReadFolder(folder, [](const std::string&) { return true; });
  ASSERT_EQ(read.size(), Phantom().Structures.size());
  const vp::VesselLabelTable table = vp::VesselLabelTable::Default();
  for (const vp::LabelStructure& r : read)
  {
    const auto original = std::find_if(Phantom().Structures.begin(), Phantom().Structures.end(),
      [&](const vp::PhantomStructure& s) { return s.Name == r.Name; });
    ASSERT_NE(original, Phantom().Structures.end()) << r.Name;
    EXPECT_EQ(table.ClassOf(r), original->ClassName);
    int a[3], b[3];
    r.Grid.Labels->GetDimensions(a);
    original->Mask.Labels->GetDimensions(b);
    ASSERT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) << r.Name;
    for (std::size_t i = 0; i < 16; ++i)
    {
      EXPECT_NEAR(r.Grid.IjkToLps[i], original->Mask.IjkToLps[i], 1e-6) << r.Name << " IjkToLps[" << i << "]";
    }
    long long differing = 0;
    for (vtkIdType i = 0; i < r.Grid.Labels->GetNumberOfPoints(); ++i)
    {
      differing += (r.Grid.Labels->GetPointData()->GetScalars()->GetTuple1(i) != 0) != (Voxels(original->Mask)[i] != 0);
    }
    EXPECT_EQ(differing, 0) << r.Name;
  }
  EXPECT_THROW(vp::WriteLiverPhantomDicom(Phantom(), "/proc/no-such-place/masks"), vp::InputError);
}

// ------------------------------------------------------------------------------------------------
// The CUSA handpiece

TEST(CusaHandpiece, IsAClosedOutwardSurfaceWithItsTipAtTheOrigin)
{
  vtkSmartPointer<vtkPolyData> cusa = vp::MakeCusaHandpiece();
  EXPECT_EQ(vp::test::OpenEdges(cusa), 0);
  EXPECT_LT(cusa->GetNumberOfPolys(), 3000);
  EXPECT_GT(cusa->GetNumberOfPolys(), 500);
  // Positive: the triangles face out. About a 19 mm x 117 mm body, the taper and the tube.
  const double volume = vp::test::SignedVolume(cusa);
  EXPECT_GT(volume, 34000.0);
  EXPECT_LT(volume, 37000.0);
  double bounds[6];
  cusa->GetBounds(bounds);
  using D = vp::CusaHandpieceDimensions;
  EXPECT_NEAR(bounds[0], -D::BodyRadiusMm, 1e-9);
  EXPECT_NEAR(bounds[1], D::BodyRadiusMm, 1e-9);
  EXPECT_NEAR(bounds[5], 0.0, 1e-12) << "nothing beyond the tip";
  EXPECT_NEAR(bounds[4], -175.0, 1e-9);
  // The tip face's centre is exactly the origin; the tip tube is 2.8 mm across up to the taper.
  bool origin = false;
  double tubeRadius = 0;
  for (vtkIdType i = 0; i < cusa->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cusa->GetPoint(i, p);
    origin = origin || (p[0] == 0 && p[1] == 0 && p[2] == 0);
    if (p[2] < -1.0 && p[2] >= -D::TipLengthMm)
    {
      tubeRadius = std::max(tubeRadius, std::hypot(p[0], p[1]));
    }
  }
  EXPECT_TRUE(origin);
  EXPECT_NEAR(2 * tubeRadius, 2.8, 1e-9);
  EXPECT_DOUBLE_EQ(D::TotalLengthMm, 175.0);
  EXPECT_GE(D::BodyLengthMm, 110.0);
  EXPECT_LE(D::BodyLengthMm, 120.0);
  // The automatic tip finder agrees: narrow end at the origin, axis +z.
  const vp::ScalpelTipEstimate e = vp::FindScalpelTip(cusa, "CUSA");
  EXPECT_FALSE(e.Ambiguous);
  EXPECT_LT(Distance(e.TipMm, { 0, 0, 0 }), 0.5) << e.Description;
  EXPECT_GT(e.Axis[2], 0.999) << e.Description;
  EXPECT_NEAR(e.LengthMm, 175.0, 0.5);
}

// The resource files are the generator's output, byte for byte, with the PLUS-style tip file.
TEST(CusaHandpiece, ResourceIsTheGeneratorOutput)
{
  const std::string resource = std::string(VP_SOURCE_DIR) + "/Resources/CusaHandpiece.stl";
  const std::string dir = vp::test::MakeTempDir("cusa");
  const std::string generated = vp::test::WriteMeshFile(dir, "CusaHandpiece.stl", vp::MakeCusaHandpiece());
  const std::string expected = vp::test::Slurp(generated);
  ASSERT_GT(expected.size(), 84u);
  EXPECT_EQ(expected.substr(0, 9), "SPACE=LPS");
  EXPECT_TRUE(vp::test::Slurp(resource) == expected)
    << resource << " differs from MakeCusaHandpiece(); regenerate it with vtkVesselMeshWriter";

  vtkSmartPointer<vtkScalpelModel> scalpel = vp::LoadScalpel(resource, {});
  double tip[3], axis[3];
  scalpel->GetTipMm(tip);
  scalpel->GetAxis(axis);
  EXPECT_EQ(tip[0], 0.0);
  EXPECT_EQ(tip[1], 0.0);
  EXPECT_EQ(tip[2], 0.0);
  EXPECT_NEAR(axis[2], 1.0, 1e-12);
  EXPECT_NE(scalpel->GetTipSource().find("CusaHandpiece.json"), std::string::npos) << scalpel->GetTipSource();
}

// ------------------------------------------------------------------------------------------------
// The demo trajectory

// 50 Hz for 15-25 s, one fixed orientation from anterior-superior (no flips), surgeon's speeds.
TEST(DemoTrajectory, PosesAreSmoothAndTipLeading)
{
  const std::vector<vp::TrackedPose>& poses = Trajectory().Poses;
  ASSERT_GT(poses.size(), 2u);
  EXPECT_EQ(poses.front().TimeS, 0.0);
  EXPECT_GE(poses.back().TimeS, 15.0);
  EXPECT_LE(poses.back().TimeS, 25.0);
  EXPECT_EQ(poses.size(), vp::MakeDemoTrajectory(Phantom()).size());
  const auto& axis = Trajectory().AxisDirection;
  EXPECT_GT(axis[1], 0.2) << "moves posterior: comes from anterior";
  EXPECT_LT(axis[2], -0.2) << "moves inferior: comes from superior";
  double fastest = 0;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const auto& m = poses[i].ModelToWorld;
    // Proper rotation whose +z column is the fixed axis; last row 0 0 0 1.
    for (int r = 0; r < 3; ++r)
    {
      EXPECT_NEAR(m[static_cast<std::size_t>(4 * r + 2)], axis[static_cast<std::size_t>(r)], 1e-12);
    }
    const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
      m[2] * (m[4] * m[9] - m[5] * m[8]);
    EXPECT_NEAR(det, 1.0, 1e-9);
    EXPECT_EQ(m[12], 0.0);
    EXPECT_EQ(m[15], 1.0);
    if (i > 0)
    {
      const double dt = poses[i].TimeS - poses[i - 1].TimeS;
      ASSERT_NEAR(dt, 0.02, 1e-9);
      fastest = std::max(fastest, Distance(TipOf(poses[i]), TipOf(poses[i - 1])) / dt);
    }
  }
  EXPECT_LE(fastest, 15.0);
  EXPECT_GE(fastest, 5.0);
}

// The levels of the nearest vessel (analytic), frame by frame, follow the design; the breach is
// 1 mm into a medium portal branch, the pass 3-4 mm from a hepatic vein, the artery stays far.
TEST(DemoTrajectory, VisitsTheDesignedLevelsAtTheDesignedDistances)
{
  const vp::LiverPhantom& phantom = Phantom();
  std::vector<vp::DangerLevel> levels;
  double portal = std::numeric_limits<double>::infinity(), hepatic = portal, artery = portal;
  for (const vp::TrackedPose& pose : Trajectory().Poses)
  {
    const Point tip = TipOf(pose);
    const vp::DangerLevel level = vp::AnalyticProximityAt(phantom, tip).Level;
    if (levels.empty() || levels.back() != level)
    {
      levels.push_back(level);
    }
    portal = std::min(portal, vp::TreeSignedDistanceMm(phantom.Centrelines.at("portal_vein"), tip));
    hepatic = std::min(hepatic, vp::TreeSignedDistanceMm(phantom.Centrelines.at("hepatic_vein"), tip));
    artery = std::min(artery, vp::TreeSignedDistanceMm(phantom.Centrelines.at("hepatic_artery"), tip));
  }
  using L = vp::DangerLevel;
  const std::vector<L> expected = { L::Safe, L::Caution, L::Warning, L::Danger, L::Breach, L::Danger, L::Warning,
    L::Caution, L::Safe, L::Caution, L::Warning, L::Caution, L::Safe };
  EXPECT_EQ(levels, expected);
  EXPECT_EQ(vp::DemoTrajectoryLevelSequence(), expected);
  EXPECT_NEAR(portal, -1.0, 0.01);
  EXPECT_GE(hepatic, 3.0);
  EXPECT_LE(hepatic, 4.0);
  EXPECT_NEAR(hepatic, 3.5, 0.05);
  EXPECT_GT(artery, 10.0);
  EXPECT_GE(2 * Trajectory().TargetRadiusMm, 4.6);
  EXPECT_LE(2 * Trajectory().TargetRadiusMm, 7.2);
}

// The key points: where and when, and at least 0.7 mm from every threshold, so that surfaces
// built from the voxels (about half a voxel off) keep the same levels there.
TEST(DemoTrajectory, KeyPointsKeepMarginsFromTheThresholds)
{
  const auto& keys = Trajectory().KeyPoints;
  ASSERT_EQ(keys.size(), 5u);
  const std::vector<std::string> names = { "start", "breach", "withdrawn", "hepatic pass", "end" };
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    EXPECT_EQ(keys[i].Name, names[i]);
    if (i > 0)
    {
      EXPECT_GT(keys[i].TimeS, keys[i - 1].TimeS);
    }
    for (double threshold : { 0.0, 2.0, 5.0, 10.0 })
    {
      EXPECT_GE(std::abs(keys[i].DistanceMm - threshold), 0.7) << keys[i].Name;
    }
    const vp::AnalyticProximity there = vp::AnalyticProximityAt(Phantom(), keys[i].TipMm);
    EXPECT_EQ(there.NearestClass, keys[i].ClassName);
    EXPECT_DOUBLE_EQ(there.NearestMm, keys[i].DistanceMm);
    EXPECT_EQ(there.Level, keys[i].Level);
  }
  EXPECT_GT(keys[0].DistanceMm, 15.0);
  EXPECT_EQ(keys[1].ClassName, "portal_vein");
  EXPECT_NEAR(keys[1].DistanceMm, -1.0, 1e-6);
  EXPECT_EQ(keys[1].Level, vp::DangerLevel::Breach);
  EXPECT_EQ(keys[2].Level, vp::DangerLevel::Safe);
  EXPECT_EQ(keys[3].ClassName, "hepatic_vein");
  EXPECT_NEAR(keys[3].DistanceMm, 3.5, 1e-6);
  EXPECT_EQ(keys[3].Level, vp::DangerLevel::Warning);
  EXPECT_GT(keys[4].DistanceMm, 12.0);
  // The poses pass through the key points at their times (the breach is held for a moment).
  for (const vp::DemoKeyPoint& k : keys)
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (const vp::TrackedPose& pose : Trajectory().Poses)
    {
      if (std::abs(pose.TimeS - k.TimeS) <= 0.011)
      {
        nearest = std::min(nearest, Distance(TipOf(pose), k.TipMm));
      }
    }
    EXPECT_LT(nearest, 0.15) << k.Name;
  }
}
