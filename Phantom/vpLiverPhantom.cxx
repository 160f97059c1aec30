#include "vpLiverPhantom.h"
#include "vpVec3.h"

#include "vpDicomLabelSeriesWriter.h"
#include "vpInputError.h"

#include <vtkImageData.h>
#include <vtkType.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace vp
{
namespace
{
using namespace vec3;

/// splitmix64: a few lines, fully specified, so every platform draws the same numbers (the
/// standard distributions are implementation-defined and would change the phantom).
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : State(seed)
  {
  }
  std::uint64_t Next()
  {
    std::uint64_t z = (this->State += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1), 53 random bits.
  double Uniform() { return static_cast<double>(this->Next() >> 11) * (1.0 / 9007199254740992.0); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * this->Uniform(); }

private:
  std::uint64_t State;
};

// ---------------------------------------------------------------------------------------------
// The parenchyma: a smooth union of ellipsoids (right lobe, medial part, left lobe, inferior
// right part) with a renal impression carved out of the visceral surface and a gentle
// low-frequency deformation. The field is roughly a signed distance in mm (negative inside);
// only its zero level set is the liver, the rest is used as a margin when placing vessels.

struct Ellipsoid
{
  Vec3 Centre;
  Vec3 SemiAxesMm;
};

/// Approximate signed distance to an ellipsoid (first-order: the implicit function over its
/// gradient), good to a few per cent near the surface, where it matters here.
double EllipsoidField(const Ellipsoid& e, const Vec3& p)
{
  const Vec3 q = { (p[0] - e.Centre[0]) / e.SemiAxesMm[0], (p[1] - e.Centre[1]) / e.SemiAxesMm[1],
    (p[2] - e.Centre[2]) / e.SemiAxesMm[2] };
  const Vec3 g = { q[0] / e.SemiAxesMm[0], q[1] / e.SemiAxesMm[1], q[2] / e.SemiAxesMm[2] };
  const double k0 = Norm(q), k1 = Norm(g);
  if (k1 < 1e-12)
  {
    return -std::min({ e.SemiAxesMm[0], e.SemiAxesMm[1], e.SemiAxesMm[2] }); // the centre
  }
  return k0 * (k0 - 1.0) / k1;
}

/// Polynomial smooth minimum: a fillet of about k mm where two fields meet.
double SmoothMin(double a, double b, double k)
{
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}
double SmoothMax(double a, double b, double k)
{
  return -SmoothMin(-a, -b, k);
}

const Ellipsoid RightLobe{ { -95, 18, 44 }, { 62, 70, 58 } };
const Ellipsoid MedialPart{ { -45, 10, 60 }, { 44, 60, 40 } };
const Ellipsoid LeftLobe{ { -4, -2, 70 }, { 34, 46, 21 } };
const Ellipsoid InferiorRight{ { -104, 6, 10 }, { 44, 50, 30 } };
const Ellipsoid RenalImpression{ { -112, 74, -28 }, { 40, 34, 44 } };
constexpr double BlendMm = 18.0;
constexpr double BumpMm = 2.0;

/// The deformation is a product of one sine per axis, so a grid can tabulate it per axis.
double BumpX(double x)
{
  return std::sin(0.045 * x + 0.3);
}
double BumpY(double y)
{
  return std::sin(0.050 * y + 1.1);
}
double BumpZ(double z)
{
  return std::sin(0.040 * z + 2.0);
}

double LiverFieldWithoutBumps(const Vec3& p)
{
  double f = SmoothMin(EllipsoidField(RightLobe, p), EllipsoidField(MedialPart, p), BlendMm);
  f = SmoothMin(f, EllipsoidField(LeftLobe, p), BlendMm);
  f = SmoothMin(f, EllipsoidField(InferiorRight, p), BlendMm);
  return SmoothMax(f, -EllipsoidField(RenalImpression, p), 0.5 * BlendMm);
}

double LiverField(const Vec3& p)
{
  return LiverFieldWithoutBumps(p) + BumpMm * BumpX(p[0]) * BumpY(p[1]) * BumpZ(p[2]);
}

// ---------------------------------------------------------------------------------------------
// Vessel trees.

enum VesselClass
{
  Portal = 0,
  Artery = 1,
  Hepatic = 2,
  NumberOfVesselClasses = 3
};
const char* const ClassNames[NumberOfVesselClasses] = { "portal_vein", "hepatic_artery", "hepatic_vein" };
const char* const FolderNames[NumberOfVesselClasses] = { "portalvein", "hepaticartery", "hepaticvein" };

/// 3 mm and 2 mm diameters: the finest vessels a 1 mm CT segmentation shows.
constexpr double VeinMinimumRadiusMm = 1.5;
constexpr double ArteryMinimumRadiusMm = 1.0;
/// The distances kept between surfaces while growing; the checks use the larger radius of each
/// piece, so the real gaps are at least these.
constexpr double ClassGapMm = LiverPhantom::MinimumGapMm + 0.3;
constexpr double SameClassGapMm = 1.0;
/// Where the artery runs beside the portal branch (surface to surface).
constexpr double ArteryOffsetGapMm = ClassGapMm + 0.5;
/// Branches stay this far inside the liver surface (veins; the artery keeps less).
constexpr double VeinLiverMarginMm = 2.0;
constexpr double ArteryLiverMarginMm = 1.0;
/// Branches of one tree leave each other at 35 degrees at least.
const double MaximumCosineAtJunction = std::cos(35.0 * Pi / 180.0);
/// Each piece tapers by this factor along a branch.
constexpr double TaperPerBranch = 0.96;

double ClosestSegmentSegmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2)
{
  // Ericson, Real-Time Collision Detection, 5.1.9.
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r);
  double s = 0, t = 0;
  if (a <= 1e-12 && e <= 1e-12)
  {
    return Norm(r);
  }
  if (a <= 1e-12)
  {
    t = std::clamp(f / e, 0.0, 1.0);
  }
  else
  {
    const double c = Dot(d1, r);
    if (e <= 1e-12)
    {
      s = std::clamp(-c / a, 0.0, 1.0);
    }
    else
    {
      const double b = Dot(d1, d2), denom = a * e - b * b;
      s = denom > 1e-12 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0)
      {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      }
      else if (t > 1)
      {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return Norm((p1 + s * d1) - (p2 + t * d2));
}

struct Piece
{
  VesselSegment Segment;
  int Class = 0;
  int Branch = 0;
  /// Bounding sphere, for a quick rejection before the exact segment distance.
  Vec3 MidMm{};
  double HalfLengthMm = 0;
  double MaxRadiusMm = 0;
};

Piece MakePiece(const Vec3& a, const Vec3& b, double ra, double rb, int cls, int branch)
{
  Piece p;
  p.Segment = { a, b, ra, rb };
  p.Class = cls;
  p.Branch = branch;
  p.MidMm = 0.5 * (a + b);
  p.HalfLengthMm = 0.5 * Norm(b - a);
  p.MaxRadiusMm = std::max(ra, rb);
  return p;
}

/// A planned branch: a polyline with a radius falling linearly along it.
struct BranchShape
{
  std::vector<Vec3> Points;
  double StartRadiusMm = 0;
  double EndRadiusMm = 0;
};

std::vector<Piece> PiecesOf(const BranchShape& shape, int cls, int branch)
{
  double total = 0;
  for (std::size_t i = 1; i < shape.Points.size(); ++i)
  {
    total += Norm(shape.Points[i] - shape.Points[i - 1]);
  }
  std::vector<Piece> pieces;
  double along = 0;
  for (std::size_t i = 1; i < shape.Points.size(); ++i)
  {
    const double length = Norm(shape.Points[i] - shape.Points[i - 1]);
    const double r0 = shape.StartRadiusMm + (shape.EndRadiusMm - shape.StartRadiusMm) * along / total;
    along += length;
    const double r1 = shape.StartRadiusMm + (shape.EndRadiusMm - shape.StartRadiusMm) * along / total;
    pieces.push_back(MakePiece(shape.Points[i - 1], shape.Points[i], r0, r1, cls, branch));
  }
  return pieces;
}

Vec3 EndHeading(const BranchShape& b)
{
  return Normalized(b.Points.back() - b.Points[b.Points.size() - 2]);
}

/// A bifurcation waiting to grow: one child of a branch end.
struct GrowthTip
{
  int Class = Portal;
  int ParentBranch = -1;
  Vec3 JunctionMm{};
  Vec3 ParentDirection{}; ///< unit, the parent's heading at the junction
  Vec3 Side{};            ///< unit, perpendicular to ParentDirection: the bifurcation plane
  double TurnRad = 0;     ///< signed angle from ParentDirection towards Side
  double RadiusMm = 0;
  double ParentRadiusMm = 0; ///< end radius of the parent branch
  /// The artery beside the parent portal branch (-1: none): this child's artery starts at its end.
  int ParentCompanion = -1;
  std::uint64_t Order = 0;
};

/// An artery branch running beside a portal branch.
struct Companion
{
  int Branch = -1;
  Vec3 EndMm{};
  Vec3 OffsetDirection{}; ///< unit, from the portal axis to the artery axis
  double EndRadiusMm = 0;
};

/// Grows the three trees together, so that each keeps clear of the others: every branch is
/// tried in a fixed sequence of shapes and the first that fits is kept.
class TreeGrower
{
public:
  explicit TreeGrower(std::uint64_t seed)
    : Rng(seed)
  {
  }

  /// Places a branch without checks (the hand-made trunks); returns its branch id.
  int PlaceFixed(const BranchShape& shape, int cls, int parentBranch = -1)
  {
    const int branch = this->NewBranch(parentBranch);
    const std::vector<Piece> pieces = PiecesOf(shape, cls, branch);
    this->Placed.insert(this->Placed.end(), pieces.begin(), pieces.end());
    return branch;
  }

  /// Queues the children of a branch that ends at junction, heading along direction with end
  /// radius r: Murray's law r^3 = r1^3 + r2^3 with a random split, and the angles that minimise
  /// the work of the bifurcation (cos t1 = (r^4 + r1^4 - r2^4) / (2 r^2 r1^2)), in a random plane.
  void Bifurcate(int cls, int branch, const Vec3& junction, const Vec3& direction, double radius, int companion)
  {
    const double minimum = cls == Artery ? ArteryMinimumRadiusMm : VeinMinimumRadiusMm;
    const double split = this->Rng.Uniform(0.3, 0.7);
    const double r1 = radius * std::cbrt(split), r2 = radius * std::cbrt(1.0 - split);
    const double r02 = radius * radius;
    auto angle = [&](double ra, double rb)
    {
      const double c = (r02 * r02 + ra * ra * ra * ra - rb * rb * rb * rb) / (2 * r02 * ra * ra);
      return std::acos(std::clamp(c, -1.0, 1.0));
    };
    const Vec3 side = Rotate(PerpendicularTo(direction, { 0, 0, 1 }), direction, this->Rng.Uniform(0, 2 * Pi));
    const double radii[2] = { r1, r2 };
    const double turns[2] = { angle(r1, r2), -angle(r2, r1) };
    for (int c = 0; c < 2; ++c)
    {
      if (radii[c] < minimum)
      {
        continue;
      }
      GrowthTip tip;
      tip.Class = cls;
      tip.ParentBranch = branch;
      tip.JunctionMm = junction;
      tip.ParentDirection = direction;
      tip.Side = side;
      tip.TurnRad = turns[c];
      tip.RadiusMm = radii[c];
      tip.ParentRadiusMm = radius;
      tip.ParentCompanion = companion;
      tip.Order = this->NextOrder++;
      this->Tips.push_back(tip);
    }
  }

  /// Grows every waiting tip, largest first (the big vessels claim their space before the small
  /// ones; ties in the order queued).
  void Grow()
  {
    while (!this->Tips.empty())
    {
      auto best = std::max_element(this->Tips.begin(), this->Tips.end(),
        [](const GrowthTip& a, const GrowthTip& b)
        { return a.RadiusMm < b.RadiusMm || (a.RadiusMm == b.RadiusMm && a.Order > b.Order); });
      const GrowthTip tip = *best;
      this->Tips.erase(best);
      this->GrowTip(tip);
    }
  }

  /// Starts the artery beside a hand-made portal branch (the trunk); returns the companion id.
  int AddCompanionFixed(const BranchShape& portal, const Vec3& offsetDirection, double arteryRadiusMm)
  {
    const double offset = portal.StartRadiusMm + arteryRadiusMm + ArteryOffsetGapMm;
    BranchShape artery;
    for (const Vec3& p : portal.Points)
    {
      artery.Points.push_back(p + offset * offsetDirection);
    }
    artery.StartRadiusMm = arteryRadiusMm;
    artery.EndRadiusMm = arteryRadiusMm * TaperPerBranch;
    const int branch = this->PlaceFixed(artery, Artery);
    this->Companions.push_back({ branch, artery.Points.back(), offsetDirection, artery.EndRadiusMm });
    return static_cast<int>(this->Companions.size() - 1);
  }

  /// Grows the artery beside a portal branch whose parent has one, from the parent artery's end
  /// to beside the branch's points, on the side nearest the parent's that fits; returns the new
  /// companion (-1 when the artery ends here: too thin, or no room).
  int GrowCompanion(int parentCompanion, const BranchShape& portal, double portalParentRadiusMm)
  {
    if (parentCompanion < 0)
    {
      return -1;
    }
    const Companion parent = this->Companions[static_cast<std::size_t>(parentCompanion)];
    // The artery divides as the vein does: the same share of the flow, Murray's law for both.
    const double share = std::pow(portal.StartRadiusMm / portalParentRadiusMm, 3.0);
    const double radius = parent.EndRadiusMm * std::cbrt(std::min(share, 1.0));
    if (radius < ArteryMinimumRadiusMm)
    {
      return -1;
    }
    const Vec3 axis = Normalized(portal.Points.back() - portal.Points.front());
    const Vec3 base = PerpendicularTo(axis, parent.OffsetDirection);
    const double offset = std::max(portal.StartRadiusMm, portal.EndRadiusMm) + radius + ArteryOffsetGapMm;
    static const double turnsDeg[] = { 0, 30, -30, 60, -60, 90, -90, 120, -120, 150, -150, 180 };
    for (double turnDeg : turnsDeg)
    {
      const Vec3 n = Rotate(base, axis, turnDeg * Pi / 180.0);
      BranchShape artery;
      artery.Points.push_back(parent.EndMm);
      for (std::size_t i = 1; i < portal.Points.size(); ++i)
      {
        artery.Points.push_back(portal.Points[i] + offset * n);
      }
      artery.StartRadiusMm = radius;
      artery.EndRadiusMm = radius * TaperPerBranch;
      const int branch = static_cast<int>(this->BranchParent.size());
      const std::vector<Piece> pieces = PiecesOf(artery, Artery, branch);
      if (this->Fits(pieces, parent.EndMm, parent.Branch, ArteryLiverMarginMm))
      {
        this->NewBranch(parent.Branch);
        this->Placed.insert(this->Placed.end(), pieces.begin(), pieces.end());
        this->Companions.push_back({ branch, artery.Points.back(), n, artery.EndRadiusMm });
        return static_cast<int>(this->Companions.size() - 1);
      }
    }
    return -1;
  }

  std::vector<VesselSegment> SegmentsOf(int cls) const
  {
    std::vector<VesselSegment> segments;
    for (const Piece& p : this->Placed)
    {
      if (p.Class == cls)
      {
        segments.push_back(p.Segment);
      }
    }
    return segments;
  }

private:
  int NewBranch(int parentBranch)
  {
    this->BranchParent.push_back(parentBranch);
    return static_cast<int>(this->BranchParent.size() - 1);
  }

  /// True when the pieces of a new branch stay inside the liver and keep their gaps to
  /// everything placed. Its parent and grandparent are exempt (the child leaves them at their
  /// end, at less than a right angle, and a short parent keeps it near the grandparent's end);
  /// its siblings must part from it at an angle.
  bool Fits(const std::vector<Piece>& pieces, const Vec3& junction, int parentBranch, double liverMarginMm) const
  {
    const Vec3 heading = Normalized(pieces.back().Segment.EndMm - junction);
    const int grandparentBranch = parentBranch < 0 ? -1 : this->BranchParent[static_cast<std::size_t>(parentBranch)];
    for (const Piece& c : pieces)
    {
      const double length = 2 * c.HalfLengthMm;
      const int samples = std::max(2, static_cast<int>(std::ceil(length / 1.5)) + 1);
      for (int s = 0; s < samples; ++s)
      {
        const double t = static_cast<double>(s) / (samples - 1);
        const Vec3 p = c.Segment.StartMm + t * (c.Segment.EndMm - c.Segment.StartMm);
        const double r = c.Segment.StartRadiusMm + t * (c.Segment.EndRadiusMm - c.Segment.StartRadiusMm);
        if (LiverField(p) > -(r + liverMarginMm))
        {
          return false;
        }
      }
    }
    for (const Piece& e : this->Placed)
    {
      const bool sameClass = e.Class == pieces.front().Class;
      if (sameClass && e.Branch >= 0 && (e.Branch == parentBranch || e.Branch == grandparentBranch))
      {
        continue;
      }
      if (sameClass && parentBranch >= 0 && this->BranchParent[static_cast<std::size_t>(e.Branch)] == parentBranch)
      {
        // A sibling: it starts where the new branch does, so only the angle between them counts.
        if (Dot(Normalized(e.Segment.EndMm - junction), heading) > MaximumCosineAtJunction)
        {
          return false;
        }
        continue;
      }
      for (const Piece& c : pieces)
      {
        const double needed = c.MaxRadiusMm + e.MaxRadiusMm + (sameClass ? SameClassGapMm : ClassGapMm);
        if (Norm(c.MidMm - e.MidMm) - c.HalfLengthMm - e.HalfLengthMm >= needed)
        {
          continue;
        }
        if (ClosestSegmentSegmentDistance(c.Segment.StartMm, c.Segment.EndMm, e.Segment.StartMm, e.Segment.EndMm) <
          needed)
        {
          return false;
        }
      }
    }
    return true;
  }

  void GrowTip(const GrowthTip& tip)
  {
    // The planned plane first, then planes turned about the parent's axis; each at full length,
    // then shorter (branches near the surface end early).
    static const double planeTurnsDeg[] = { 0, 40, -40, 80, -80, 120, -120, 160, -160 };
    static const double lengthFactors[] = { 1.0, 0.7, 0.5, 0.35 };
    const double baseLength = std::min(tip.RadiusMm * this->Rng.Uniform(3.5, 6.0), 30.0);
    for (double lengthFactor : lengthFactors)
    {
      for (double planeTurnDeg : planeTurnsDeg)
      {
        const Vec3 side = Rotate(tip.Side, tip.ParentDirection, planeTurnDeg * Pi / 180.0);
        const Vec3 u = std::cos(tip.TurnRad) * tip.ParentDirection + std::sin(tip.TurnRad) * side;
        const double length = baseLength * lengthFactor;
        // A gently bent branch: the middle points leave the straight line by a few per cent.
        const Vec3 bend = Rotate(PerpendicularTo(u, side), u, this->Rng.Uniform(0, 2 * Pi));
        const double bendMm = length * this->Rng.Uniform(0.0, 0.06);
        BranchShape shape;
        shape.Points = { tip.JunctionMm, tip.JunctionMm + (0.45 * length) * u + bendMm * bend,
          tip.JunctionMm + (0.75 * length) * u + (0.8 * bendMm) * bend, tip.JunctionMm + length * u };
        shape.StartRadiusMm = tip.RadiusMm;
        shape.EndRadiusMm = tip.RadiusMm * TaperPerBranch;
        const int branch = static_cast<int>(this->BranchParent.size());
        const std::vector<Piece> pieces = PiecesOf(shape, tip.Class, branch);
        if (!this->Fits(pieces, tip.JunctionMm, tip.ParentBranch, VeinLiverMarginMm))
        {
          continue;
        }
        this->NewBranch(tip.ParentBranch);
        this->Placed.insert(this->Placed.end(), pieces.begin(), pieces.end());
        const int companion =
          tip.Class == Portal ? this->GrowCompanion(tip.ParentCompanion, shape, tip.ParentRadiusMm) : -1;
        this->Bifurcate(tip.Class, branch, shape.Points.back(), EndHeading(shape), shape.EndRadiusMm, companion);
        return;
      }
    }
  }

  Random Rng;
  std::vector<Piece> Placed;
  std::vector<GrowthTip> Tips;
  std::vector<Companion> Companions;
  std::vector<int> BranchParent; ///< per branch id, its parent's id (-1: a root)
  std::uint64_t NextOrder = 0;
};
} // namespace
} // namespace vp

namespace vp
{
namespace
{
/// The voxel grid: axis-aligned in LPS (axial slices, as CT), voxel centres at Origin + index *
/// VoxelMm.
struct PhantomGrid
{
  Vec3 OriginMm{};
  int Dimensions[3] = { 0, 0, 0 };
  double VoxelMm = 1.0;

  std::size_t Size() const
  {
    return static_cast<std::size_t>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  Vec3 Centre(int i, int j, int k) const
  {
    return { this->OriginMm[0] + i * this->VoxelMm, this->OriginMm[1] + j * this->VoxelMm,
      this->OriginMm[2] + k * this->VoxelMm };
  }
};

/// The liver's bounding box, from a 2 mm scan of the field, plus the margin; the origin falls on
/// a multiple of the voxel size so that grids of one voxel size share their voxel centres.
PhantomGrid LiverGrid(const LiverPhantomOptions& options)
{
  constexpr double StepMm = 2.0;
  const Vec3 searchLo = { -180, -80, -50 }, searchHi = { 50, 110, 130 };
  Vec3 lo = searchHi, hi = searchLo;
  for (double z = searchLo[2]; z <= searchHi[2]; z += StepMm)
  {
    for (double y = searchLo[1]; y <= searchHi[1]; y += StepMm)
    {
      for (double x = searchLo[0]; x <= searchHi[0]; x += StepMm)
      {
        const Vec3 p = { x, y, z };
        if (LiverField(p) <= 0)
        {
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
          }
        }
      }
    }
  }
  PhantomGrid grid;
  grid.VoxelMm = options.VoxelMm;
  for (int a = 0; a < 3; ++a)
  {
    const double from = lo[a] - StepMm - options.MarginMm, to = hi[a] + StepMm + options.MarginMm;
    grid.OriginMm[a] = std::floor(from / options.VoxelMm) * options.VoxelMm;
    grid.Dimensions[a] = static_cast<int>(std::ceil((to - grid.OriginMm[a]) / options.VoxelMm)) + 1;
  }
  return grid;
}

std::vector<std::uint8_t> RasteriseLiver(const PhantomGrid& grid)
{
  std::vector<std::uint8_t> mask(grid.Size(), 0);
  const int nx = grid.Dimensions[0], ny = grid.Dimensions[1], nz = grid.Dimensions[2];
  std::vector<double> bx(static_cast<std::size_t>(nx)), by(static_cast<std::size_t>(ny)),
    bz(static_cast<std::size_t>(nz));
  for (int i = 0; i < nx; ++i)
  {
    bx[static_cast<std::size_t>(i)] = BumpX(grid.Centre(i, 0, 0)[0]);
  }
  for (int j = 0; j < ny; ++j)
  {
    by[static_cast<std::size_t>(j)] = BumpY(grid.Centre(0, j, 0)[1]);
  }
  for (int k = 0; k < nz; ++k)
  {
    bz[static_cast<std::size_t>(k)] = BumpZ(grid.Centre(0, 0, k)[2]);
  }
  std::size_t index = 0;
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i, ++index)
      {
        // Same operations, in the same order, as LiverField: the mask is the field's zero set.
        const double bump = BumpMm * bx[static_cast<std::size_t>(i)] * by[static_cast<std::size_t>(j)] *
          bz[static_cast<std::size_t>(k)];
        mask[index] = LiverFieldWithoutBumps(grid.Centre(i, j, k)) + bump <= 0 ? 1 : 0;
      }
    }
  }
  return mask;
}

/// Marks the voxels whose centre lies inside the cone-capsule, looking only at its bounding box.
void RasteriseSegment(const PhantomGrid& grid, const VesselSegment& s, std::vector<std::uint8_t>& mask)
{
  int from[3], to[3];
  const double reach = std::max(s.StartRadiusMm, s.EndRadiusMm);
  for (int a = 0; a < 3; ++a)
  {
    const double lo = std::min(s.StartMm[a], s.EndMm[a]) - reach, hi = std::max(s.StartMm[a], s.EndMm[a]) + reach;
    from[a] = std::max(0, static_cast<int>(std::ceil((lo - grid.OriginMm[a]) / grid.VoxelMm)));
    to[a] = std::min(grid.Dimensions[a] - 1, static_cast<int>(std::floor((hi - grid.OriginMm[a]) / grid.VoxelMm)));
  }
  const std::size_t nx = static_cast<std::size_t>(grid.Dimensions[0]), ny = static_cast<std::size_t>(grid.Dimensions[1]);
  for (int k = from[2]; k <= to[2]; ++k)
  {
    for (int j = from[1]; j <= to[1]; ++j)
    {
      for (int i = from[0]; i <= to[0]; ++i)
      {
        if (SegmentSignedDistanceMm(s, grid.Centre(i, j, k)) <= 0)
        {
          mask[(static_cast<std::size_t>(k) * ny + static_cast<std::size_t>(j)) * nx + static_cast<std::size_t>(i)] = 1;
        }
      }
    }
  }
}

LabelGrid MaskGrid(const PhantomGrid& grid, const std::vector<std::uint8_t>& mask)
{
  LabelGrid label;
  label.Labels = vtkSmartPointer<vtkImageData>::New();
  label.Labels->SetDimensions(grid.Dimensions[0], grid.Dimensions[1], grid.Dimensions[2]);
  label.Labels->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  std::memcpy(label.Labels->GetScalarPointer(), mask.data(), mask.size());
  label.IjkToLps = { grid.VoxelMm, 0, 0, grid.OriginMm[0], 0, grid.VoxelMm, 0, grid.OriginMm[1], 0, 0, grid.VoxelMm,
    grid.OriginMm[2], 0, 0, 0, 1 };
  return label;
}

BranchShape Shape(std::vector<Vec3> points, double startRadiusMm, double endRadiusMm)
{
  BranchShape shape;
  shape.Points = std::move(points);
  shape.StartRadiusMm = startRadiusMm;
  shape.EndRadiusMm = endRadiusMm;
  return shape;
}

/// The hand-made part of the trees (trunks and first branches, where anatomy is most constant),
/// then the grown rest.
std::map<std::string, std::vector<VesselSegment>> MakeVesselTrees(std::uint64_t seed)
{
  TreeGrower grower(seed);

  // Hepatic veins: the vena cava in its groove on the posterior surface, right of the midline,
  // running through the whole grid (the scan's field of view cuts it, as in real data); the
  // three trunks join it near the top.
  const int venaCava =
    grower.PlaceFixed(Shape({ { -27, 62, -60 }, { -29, 59, 45 }, { -33, 54, 150 } }, 11.0, 11.0), Hepatic);
  const Vec3 confluence = { -32, 55, 94 };
  const BranchShape hepaticTrunks[3] = { Shape({ confluence, { -58, 44, 84 }, { -84, 32, 74 } }, 5.0, 4.8),
    Shape({ confluence, { -42, 34, 84 }, { -52, 14, 74 } }, 4.7, 4.5),
    Shape({ confluence, { -14, 42, 88 }, { 0, 26, 80 } }, 4.5, 4.3) };
  int hepaticBranches[3];
  for (int t = 0; t < 3; ++t)
  {
    hepaticBranches[t] = grower.PlaceFixed(hepaticTrunks[t], Hepatic, venaCava);
  }

  // Portal vein: from below the hilum (outside the liver, medial and posterior) up to its
  // bifurcation; the right branch takes the larger share of the flow.
  const BranchShape portalTrunk = Shape({ { -20, 32, -14 }, { -40, 27, 8 }, { -58, 22, 26 } }, 6.25, 6.1);
  const int trunkBranch = grower.PlaceFixed(portalTrunk, Portal);
  const double rightShare = 0.55;
  const double rightRadius = portalTrunk.EndRadiusMm * std::cbrt(rightShare);
  const double leftRadius = portalTrunk.EndRadiusMm * std::cbrt(1 - rightShare);
  const BranchShape rightPortal =
    Shape({ portalTrunk.Points.back(), { -76, 25, 32 }, { -92, 28, 38 } }, rightRadius, rightRadius * TaperPerBranch);
  const BranchShape leftPortal =
    Shape({ portalTrunk.Points.back(), { -40, 10, 42 }, { -22, 2, 52 } }, leftRadius, leftRadius * TaperPerBranch);
  const int rightBranch = grower.PlaceFixed(rightPortal, Portal, trunkBranch);
  const int leftBranch = grower.PlaceFixed(leftPortal, Portal, trunkBranch);

  // Hepatic artery: in front of the portal trunk, as the proper hepatic artery runs in the
  // hepatoduodenal ligament, on the side normal to the portal bifurcation so that neither portal
  // branch crosses it; then beside the portal branches.
  const Vec3 trunkAxis = Normalized(portalTrunk.Points.back() - portalTrunk.Points.front());
  const Vec3 bifurcationNormal = Cross(rightPortal.Points[1] - rightPortal.Points[0], leftPortal.Points[1] - leftPortal.Points[0]);
  const Vec3 anterior = Dot(bifurcationNormal, { 0, -1, 0 }) > 0 ? bifurcationNormal : -1.0 * bifurcationNormal;
  const int arteryTrunk = grower.AddCompanionFixed(portalTrunk, PerpendicularTo(trunkAxis, anterior), 2.25);
  const int arteryRight = grower.GrowCompanion(arteryTrunk, rightPortal, portalTrunk.EndRadiusMm);
  const int arteryLeft = grower.GrowCompanion(arteryTrunk, leftPortal, portalTrunk.EndRadiusMm);

  grower.Bifurcate(
    Portal, rightBranch, rightPortal.Points.back(), EndHeading(rightPortal), rightPortal.EndRadiusMm, arteryRight);
  grower.Bifurcate(
    Portal, leftBranch, leftPortal.Points.back(), EndHeading(leftPortal), leftPortal.EndRadiusMm, arteryLeft);
  for (int t = 0; t < 3; ++t)
  {
    const BranchShape& trunk = hepaticTrunks[t];
    grower.Bifurcate(Hepatic, hepaticBranches[t], trunk.Points.back(), EndHeading(trunk), trunk.EndRadiusMm, -1);
  }
  grower.Grow();

  std::map<std::string, std::vector<VesselSegment>> trees;
  for (int c = 0; c < NumberOfVesselClasses; ++c)
  {
    trees[ClassNames[c]] = grower.SegmentsOf(c);
  }
  return trees;
}
} // namespace

const PhantomStructure* LiverPhantom::FindClass(const std::string& className) const
{
  for (const PhantomStructure& s : this->Structures)
  {
    if (s.ClassName == className)
    {
      return &s;
    }
  }
  return nullptr;
}

double SegmentSignedDistanceMm(const VesselSegment& s, const std::array<double, 3>& p)
{
  const Vec3 d = s.EndMm - s.StartMm;
  const double lengthSquared = Dot(d, d);
  const double t = lengthSquared > 0 ? std::clamp(Dot(p - s.StartMm, d) / lengthSquared, 0.0, 1.0) : 0.0;
  const double radius = s.StartRadiusMm + t * (s.EndRadiusMm - s.StartRadiusMm);
  return Norm(p - (s.StartMm + t * d)) - radius;
}

double TreeSignedDistanceMm(const std::vector<VesselSegment>& tree, const std::array<double, 3>& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (const VesselSegment& s : tree)
  {
    best = std::min(best, SegmentSignedDistanceMm(s, p));
  }
  return best;
}

LiverPhantom MakeLiverPhantom(const LiverPhantomOptions& options)
{
  if (!(options.VoxelMm >= 0.25 && options.VoxelMm <= 4.0) || !(options.MarginMm >= 0 && options.MarginMm <= 50))
  {
    throw InputError("liver phantom", "voxel size must be 0.25-4 mm and the margin 0-50 mm (got " +
        NumberText(options.VoxelMm) + " and " + NumberText(options.MarginMm) + ")");
  }
  LiverPhantom phantom;
  phantom.Centrelines = MakeVesselTrees(options.Seed);
  const PhantomGrid grid = LiverGrid(options);
  phantom.Structures.push_back({ "liver", "liver", MaskGrid(grid, RasteriseLiver(grid)) });
  for (int c = 0; c < NumberOfVesselClasses; ++c)
  {
    std::vector<std::uint8_t> mask(grid.Size(), 0);
    for (const VesselSegment& s : phantom.Centrelines[ClassNames[c]])
    {
      RasteriseSegment(grid, s, mask);
    }
    phantom.Structures.push_back({ FolderNames[c], ClassNames[c], MaskGrid(grid, mask) });
  }
  return phantom;
}

void WriteLiverPhantomDicom(const LiverPhantom& phantom, const std::string& folder)
{
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
  {
    throw InputError(folder, "cannot create folder: " + ec.message());
  }
  const ImageIdentity identity = DicomLabelSeriesWriter::NewIdentity("");
  for (const PhantomStructure& s : phantom.Structures)
  {
    // Foreground 255, as most of 3D-IRCADb's masks have it.
    LabelGrid written;
    written.IjkToLps = s.Mask.IjkToLps;
    written.Identity = identity; // one patient: every series in one study and frame of reference
    written.Identity.PatientName = "VesselProximity^" + s.Name;
    written.Labels = vtkSmartPointer<vtkImageData>::New();
    written.Labels->SetDimensions(s.Mask.Labels->GetDimensions());
    written.Labels->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    const auto* in = static_cast<const std::uint8_t*>(s.Mask.Labels->GetScalarPointer());
    auto* out = static_cast<std::uint8_t*>(written.Labels->GetScalarPointer());
    const std::size_t n = static_cast<std::size_t>(s.Mask.Labels->GetNumberOfPoints());
    for (std::size_t i = 0; i < n; ++i)
    {
      out[i] = in[i] ? 255 : 0;
    }
    DicomLabelSeriesWriter::Write(written, folder + "/" + s.Name, s.Name);
  }
}
} // namespace vp
