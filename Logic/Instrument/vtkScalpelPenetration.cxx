#include "vtkScalpelPenetration.h"

#include "vpCellCoverage.h"
#include "vpCellDistanceField.h"
#include "vpInputError.h"
#include "vpTriangleGeometry.h"
#include "vtkZBufferSurfaceDistance.h"

#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>

vtkStandardNewMacro(vtkScalpelPenetration);

namespace
{
/// Far enough for "find the nearest wall, wherever it is": the exact engine's search grows from
/// 1 mm and stops at the first wall, so the number only caps it.
constexpr double AnywhereMm = 1e6;

enum class Kind : std::uint8_t
{
  Full,  ///< every cell inside the instrument, none near its wall: children implied
  Mixed, ///< the wall passes through: children kept explicitly
  Cell   ///< one lattice cell, inside or near the instrument
};

struct Node
{
  double Centre[3] = { 0, 0, 0 }; ///< model coordinates
  int Level = 0;                  ///< the cube's edge is 2^Level cells
  Kind Type = Kind::Cell;
  bool InTool = false;   ///< Cell: its centre is inside the instrument
  bool NearTool = false; ///< Cell: its centre is within a half diagonal of the instrument's wall
  vp::WallPlane ToolWall; ///< Cell near the instrument's wall: that wall, as a plane
  int FirstChild = -1;   ///< Mixed: its children are Nodes[FirstChild, FirstChild + ChildCount)
  int ChildCount = 0;
  double ToolCells = 0.0; ///< cells' worth of the instrument in the cube: whole cells, and the shares of those its wall cuts
  long long CellsNearTool = 0;
};

/// A cube of the walk: an explicit node, or an implied child of a Full one.
struct Cube
{
  double Centre[3];
  int Level;
  const Node* Explicit; ///< null for an implied cube (all cells inside, none near the wall)
  double ToolCells() const { return this->Explicit ? this->Explicit->ToolCells : std::ldexp(1.0, 3 * this->Level); }
  long long CellsNearTool() const { return this->Explicit ? this->Explicit->CellsNearTool : 0; }
};
} // namespace

struct vtkScalpelPenetration::Lattice
{
  double CellMm = 0.0; // the penetration's CellSizeMm, set when the lattice is built
  bool Closed = false; ///< false: the instrument has no inside
  std::vector<Node> Nodes;
  int Root = -1;
  double SurfacePoint[3] = { 0, 0, 0 }; ///< a point of the instrument's wall (model)

  double HalfDiagonalMm(int level) const { return std::ldexp(this->CellMm, level) * std::sqrt(3.0) / 2.0; }

  /// How many children the cube has, explicit or implied.
  int ChildCount(const Cube& cube) const
  {
    return cube.Explicit && cube.Explicit->Type == Kind::Mixed ? cube.Explicit->ChildCount : 8;
  }

  /// The cube's children, explicit or implied, in octant order.
  int Children(const Cube& cube, Cube children[8]) const
  {
    if (cube.Explicit && cube.Explicit->Type == Kind::Mixed)
    {
      for (int k = 0; k < cube.Explicit->ChildCount; ++k)
      {
        const Node& n = this->Nodes[static_cast<std::size_t>(cube.Explicit->FirstChild + k)];
        children[k] = { { n.Centre[0], n.Centre[1], n.Centre[2] }, n.Level, &n };
      }
      return cube.Explicit->ChildCount;
    }
    const double offset = std::ldexp(this->CellMm, cube.Level - 2); // a quarter of the edge
    for (int k = 0; k < 8; ++k)
    {
      children[k] = { { cube.Centre[0] + ((k & 1) ? offset : -offset), cube.Centre[1] + ((k & 2) ? offset : -offset),
                        cube.Centre[2] + ((k & 4) ? offset : -offset) },
        cube.Level - 1, nullptr };
    }
    return 8;
  }

  /// Classifies the cube of the given centre and level against the instrument (class 0 of tool);
  /// returns the index of its node, or -1 when nothing of it is inside or near the instrument.
  int Build(const vtkExactVesselDistance* tool, const double centre[3], int level)
  {
    std::optional<bool> inside;
    vp::WallPlane wall;
    const double d = tool->NearestDistanceWithin(0, centre, AnywhereMm, &inside, nullptr, wall.OutwardNormal);
    const double r = this->HalfDiagonalMm(0);
    Node node;
    std::copy(centre, centre + 3, node.Centre);
    node.Level = level;
    if (level == 0)
    {
      node.Type = Kind::Cell;
      node.InTool = inside.value_or(false);
      node.NearTool = d <= r;
      if (!node.InTool && !node.NearTool)
      {
        return -1;
      }
      wall.OffsetMm = node.InTool ? d : -d;
      node.ToolWall = wall;
      node.ToolCells = node.NearTool ? vp::CellShareInside(wall, this->CellMm) : 1.0;
      node.CellsNearTool = node.NearTool ? 1 : 0;
    }
    else if (d > this->HalfDiagonalMm(level) + r)
    {
      if (!inside.value_or(false))
      {
        return -1; // wholly outside the instrument
      }
      node.Type = Kind::Full;
      node.ToolCells = std::ldexp(1.0, 3 * level);
    }
    else
    {
      node.Type = Kind::Mixed;
      std::vector<Node> kept;
      const double offset = std::ldexp(this->CellMm, level - 2);
      for (int k = 0; k < 8; ++k)
      {
        const double child[3] = { centre[0] + ((k & 1) ? offset : -offset), centre[1] + ((k & 2) ? offset : -offset),
          centre[2] + ((k & 4) ? offset : -offset) };
        const int index = this->Build(tool, child, level - 1);
        if (index >= 0)
        {
          kept.push_back(this->Nodes[static_cast<std::size_t>(index)]);
          this->Nodes.pop_back(); // re-appended below, next to its siblings
        }
      }
      if (kept.empty())
      {
        return -1;
      }
      node.FirstChild = static_cast<int>(this->Nodes.size());
      node.ChildCount = static_cast<int>(kept.size());
      for (const Node& k : kept)
      {
        node.ToolCells += k.ToolCells;
        node.CellsNearTool += k.CellsNearTool;
        this->Nodes.push_back(k);
      }
    }
    this->Nodes.push_back(node);
    return static_cast<int>(this->Nodes.size()) - 1;
  }
};

namespace
{
/// What the walk knows of the vessel wall at a point: its distance lies in [Low, High], and
/// Inside, when known, says on which side the point is.
struct Answer
{
  double Low = 0.0;
  double High = 0.0;
  std::optional<bool> Inside;
  /// The wall lies within the radius asked: Low and High are the query's own (for the exact
  /// engine, equal and exact). Otherwise only Low (the radius) is the query's.
  bool Near = false;
  /// Near, exact engine: the wall as a plane, in the instrument's (the lattice's) axes.
  bool HasWall = false;
  vp::WallPlane Wall;
};

/// One pose and one class: the walk of the instrument's octree in the world. The vessel wall's
/// distance comes from the exact engine, or, from the z-buffer's distance field, as an interval
/// [Low, High] with inside from its layers (right wherever the wall is farther than NearMm).
struct Walk
{
  const vtkExactVesselDistance* Vessels;
  const vp::CellDistanceField* Field;
  int Class;
  const std::array<double, 16>& M;
  double NearMm; ///< a cell nearer the wall than this is counted as uncertain
  double CellsInBoth = 0.0; ///< cells' worth of the instrument inside the vessel
  double CellsUncertain = 0.0; ///< cells' worth that may be counted wrongly
  double DepthMm = 0.0;
  long long Queries = 0;     ///< wall queries of the volume walk
  long long DeepQueries = 0; ///< wall queries of the deepest cell's search
  /// A bound on the depth of the cells the budget left unsearched (0: none left).
  double UnsearchedDepthMm = 0.0;
  bool Estimated = false; ///< cubes the wall crosses were estimated, not split

  void ToWorld(const double model[3], double w[3]) const
  {
    for (int r = 0; r < 3; ++r)
    {
      w[r] = this->M[4 * r] * model[0] + this->M[4 * r + 1] * model[1] + this->M[4 * r + 2] * model[2] + this->M[4 * r + 3];
    }
  }

  /// Whether the wall lies within radiusMm of the point, and if so where and on which side. The
  /// exact engine searches no farther (a bounded search is cheap however deep the point); the
  /// field answers everywhere at once.
  Answer Near(const double model[3], double radiusMm)
  {
    double w[3];
    this->ToWorld(model, w);
    ++this->Queries;
    Answer a;
    if (this->Field)
    {
      this->Field->Bounds(this->Class, w, a.Low, a.High);
      a.Inside = this->Field->Inside(this->Class, w);
      a.Near = a.Low <= radiusMm;
      return a;
    }
    std::array<double, 3> wall;
    double normal[3];
    const double d = this->Vessels->NearestDistanceWithin(this->Class, w, radiusMm, &a.Inside, wall.data(), normal);
    a.Near = std::isfinite(d);
    if (a.Near && a.Inside)
    {
      // Into the lattice's axes: the pose is rigid, its inverse rotation the transpose.
      a.HasWall = true;
      a.Wall.OffsetMm = *a.Inside ? d : -d;
      for (int c = 0; c < 3; ++c)
      {
        a.Wall.OutwardNormal[c] = this->M[c] * normal[0] + this->M[4 + c] * normal[1] + this->M[8 + c] * normal[2];
      }
    }
    a.Low = a.Near ? d : radiusMm;
    a.High = d;
    return a;
  }

  /// An upper bound on the wall's distance at a point known to be inside, within the engine's
  /// tolerance of the truth (exact: DeepSearchToleranceMm; field: its interval). The exact
  /// engine's wall point is kept for WallBoundMm.
  double DeepHigh(const double model[3], double knownWithinMm)
  {
    double w[3];
    this->ToWorld(model, w);
    ++this->DeepQueries;
    if (this->Field)
    {
      double low, high;
      this->Field->Bounds(this->Class, w, low, high);
      return high;
    }
    std::array<double, 3> wall;
    // The bound is the walk's own arithmetic: a hair wider, lest rounding leave the wall outside.
    double high = this->Vessels->DistanceUpperBoundWithin(
      this->Class, w, knownWithinMm * (1.0 + 1e-9) + 1e-9, vtkScalpelPenetration::DeepSearchToleranceMm, wall.data());
    if (!std::isfinite(high))
    {
      high = this->Vessels->DistanceUpperBoundWithin(
        this->Class, w, std::numeric_limits<double>::infinity(), vtkScalpelPenetration::DeepSearchToleranceMm, wall.data());
    }
    if (std::isfinite(high))
    {
      this->WallPoints.push_back(wall);
    }
    return high;
  }

  /// Points of the vessel wall the deep search found so far (world): the distance from any point
  /// to the wall is at most its distance to each, a bound for free that spares the queries it
  /// already rules out. Not the walk's near points: a large instrument across a wall finds
  /// thousands, and scanning them for every cube cost more than the queries they spared (the
  /// CUSA handpiece in a vessel of radius 42 mm: 3-7 ms of a frame against 0.1-1).
  std::vector<std::array<double, 3>> WallPoints{};
  double WallBoundMm(const double model[3]) const
  {
    double w[3];
    this->ToWorld(model, w);
    double best2 = std::numeric_limits<double>::infinity();
    for (const auto& p : this->WallPoints)
    {
      best2 = std::min(best2, vp::Distance2(w, p.data()));
    }
    return std::sqrt(best2);
  }

  /// The field's share of a cell inside (vp::CellDistanceField::InsideShare), as its column.
  double FieldShare(const double model[3], double halfMm) const
  {
    double w[3];
    this->ToWorld(model, w);
    return this->Field ? this->Field->InsideShare(this->Class, w, halfMm) : 0.0;
  }

  /// Whether a point is inside, wherever the wall (one unbounded search).
  bool InsideAnywhere(const double model[3])
  {
    const Answer a = this->Near(model, AnywhereMm);
    return a.Inside.value_or(false);
  }
};
} // namespace

vtkScalpelPenetration::vtkScalpelPenetration() = default;
vtkScalpelPenetration::~vtkScalpelPenetration() = default;

void vtkScalpelPenetration::SetVesselDistance(vtkExactVesselDistance* engine)
{
  if (this->Vessels != engine)
  {
    this->Vessels = engine;
    this->Modified();
  }
}

void vtkScalpelPenetration::SetZBufferSurface(vtkZBufferSurfaceDistance* surface)
{
  if (this->ZBufferSurface != surface)
  {
    this->ZBufferSurface = surface;
    this->Modified();
  }
}

void vtkScalpelPenetration::SetInstrumentDistance(vtkScalpelSurfaceDistance* surface)
{
  this->SetZBufferSurface(vtkZBufferSurfaceDistance::SafeDownCast(surface));
}

vtkZBufferSurfaceDistance* vtkScalpelPenetration::GetZBufferSurface() const
{
  return this->ZBufferSurface;
}

void vtkScalpelPenetration::SetToolSurface(vtkPolyData* model)
{
  std::lock_guard<std::mutex> lock(this->BuildLock);
  this->ToolSurface = model;
  this->Tool.reset();
  this->Modified();
}

void vtkScalpelPenetration::SetCellSizeMm(double cellMm)
{
  if (!(cellMm > 0.0) || !std::isfinite(cellMm))
  {
    throw vp::InputError("penetration cell size", "must be a positive number of mm, got " + vp::NumberText(cellMm));
  }
  std::lock_guard<std::mutex> lock(this->BuildLock);
  if (cellMm != this->CellSizeMm)
  {
    this->CellSizeMm = cellMm;
    this->Tool.reset();
    this->Modified();
  }
}

void vtkScalpelPenetration::SetQueryBudget(long long queries)
{
  if (queries < 0)
  {
    throw vp::InputError("penetration query budget", "must be 0 (no limit) or a positive count, got " + std::to_string(queries));
  }
  if (queries != this->QueryBudget)
  {
    this->QueryBudget = queries;
    this->Modified();
  }
}

void vtkScalpelPenetration::Build()
{
  std::lock_guard<std::mutex> lock(this->BuildLock);
  if (this->Tool)
  {
    return;
  }
  if (!this->ToolSurface || !this->ToolSurface->GetPoints() || this->ToolSurface->GetNumberOfPolys() == 0)
  {
    throw vp::InputError("scalpel model", "has no surface for the penetration volume");
  }
  const auto start = std::chrono::steady_clock::now();
  auto lattice = std::make_shared<Lattice>();
  lattice->CellMm = this->CellSizeMm;
  // The instrument's own distance and inside come from an exact engine over its surface.
  vtkNew<vtkExactVesselDistance> tool;
  tool->AddVessel("instrument", this->ToolSurface);
  tool->SetRangeMm(AnywhereMm);
  tool->Build();
  lattice->Closed = tool->GetSurface(0).IsClosed();
  this->ToolSurface->GetPoint(0, lattice->SurfacePoint);
  if (lattice->Closed)
  {
    const double* b = tool->GetSurface(0).Bounds();
    const double extent = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    int level = 0;
    while (std::ldexp(lattice->CellMm, level) < extent + lattice->CellMm)
    {
      ++level;
    }
    const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    lattice->Root = lattice->Build(tool, centre, level);
  }
  this->Tool = std::move(lattice);
  this->BuildTimeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool vtkScalpelPenetration::IsToolClosed() const
{
  return this->Tool && this->Tool->Closed;
}

bool vtkScalpelPenetration::GetToolVolumeMm3(double& volume, double& bound) const
{
  if (!this->Tool || !this->Tool->Closed || this->Tool->Root < 0)
  {
    return false;
  }
  const Node& root = this->Tool->Nodes[static_cast<std::size_t>(this->Tool->Root)];
  const double cell3 = std::pow(this->Tool->CellMm, 3);
  volume = cell3 * root.ToolCells;
  bound = cell3 * static_cast<double>(root.CellsNearTool);
  return true;
}

namespace
{
/// A cube wholly inside the vessel, waiting for the search of the deepest cell: no cell centre in
/// it lies farther from the wall than Key (for a cell, its centre's own distance).
struct Pending
{
  double Key;
  Cube Where;
  bool Queried; ///< Key comes from the cube's own centre, not yet only from its parent's
  std::size_t WallPointsSeen = 0; ///< Walk::WallPoints already in Key (unqueried)
  bool operator<(const Pending& other) const { return this->Key < other.Key; }
};
using PendingQueue = std::priority_queue<Pending>;

/// The key of a cube whose centre's distance is at most high: its cells reach a half diagonal
/// farther (a cell's key is its centre's own).
template <typename L>
double KeyOf(const L& lattice, double high, int level)
{
  return level == 0 ? high : high + lattice.HalfDiagonalMm(level);
}

/// A cube waiting for its wall query in the level-by-level walk, with what its parent knew.
struct Probe
{
  Cube Where;
  std::optional<bool> ParentInside;
  double ParentHigh;
  /// The parent's wall as a plane and its centre (the lattice's axes), when the exact engine
  /// gave one: beside the cube's own plane, how the wall bends between them.
  std::optional<vp::WallPlane> ParentWall;
  std::array<double, 3> ParentCentre{};
};

/// The wall's signed bend between two of its planes (1/mm, convex positive): the turn of the
/// normal along the step between their points nearest the two centres (each centre plus its
/// normal times its depth), the normal curvature in that step's direction. 0 when the points
/// coincide.
double BendPerMm(const vp::WallPlane& a, const double ca[3], const vp::WallPlane& b, const double cb[3])
{
  double turn = 0.0, step2 = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double dn = a.OutwardNormal[k] - b.OutwardNormal[k];
    const double dw = (ca[k] + a.OutwardNormal[k] * a.OffsetMm) - (cb[k] + b.OutwardNormal[k] * b.OffsetMm);
    turn += dn * dw;
    step2 += dw * dw;
  }
  return step2 > 1e-12 ? turn / step2 : 0.0;
}

/// A cube the vessel wall may cross, after its query: split, or estimated when the budget ends.
struct Straddler
{
  Probe From;
  Answer A;
  bool Inside;
  double High;
};

/// What one cube's query added to the walk: resolved independently, so that a level's cubes can
/// be queried on every core and added up in their order (the same answer however many cores).
struct Outcome
{
  double InBoth = 0.0;
  double Uncertain = 0.0;
  long long Queries = 0;
  std::optional<Pending> Deep;
  std::optional<Straddler> Crossed;
};

/// Resolves one cube of the walk: a cell is counted by its share in both solids; a cube the wall
/// does not reach is counted whole or not at all; a cube the wall may cross is returned to be
/// split (or estimated). Cubes wholly inside the vessel go to the deepest cell's search. walk is
/// only asked (its counters are the caller's scratch).
template <typename L>
Outcome Resolve(const L& lattice, Walk& walk, const Probe& probe)
{
  Outcome o;
  const long long before = walk.Queries;
  const Cube& cube = probe.Where;
  const double reach = cube.Level == 0 ? 0.0 : lattice.HalfDiagonalMm(cube.Level);
  const Answer a = walk.Near(cube.Centre, reach + walk.NearMm);
  const bool inside = a.Inside ? *a.Inside : probe.ParentInside ? *probe.ParentInside : walk.InsideAnywhere(cube.Centre);
  o.Queries = walk.Queries - before;
  // Where the wall is beyond the query's reach, the parent's centre bounds this one's distance.
  const double offset = lattice.HalfDiagonalMm(cube.Level);
  const bool queried = std::isfinite(a.High);
  const double high = queried ? a.High : probe.ParentHigh + offset;
  if (cube.Level == 0)
  {
    const bool nearTool = cube.Explicit ? cube.Explicit->NearTool : false;
    const bool nearVessel = a.Near;
    // The cell's share in both: whole where no wall crosses it, else its share behind each wall
    // (behind both where both cross it and both are known as planes).
    if (nearVessel && nearTool && a.HasWall)
    {
      o.InBoth = vp::CellShareInsideBoth(cube.Explicit->ToolWall, a.Wall, lattice.CellMm);
    }
    else
    {
      const double toolShare = cube.Explicit ? cube.Explicit->ToolCells : 1.0;
      const double vesselShare = !nearVessel ? (inside ? 1.0 : 0.0)
        : a.HasWall                          ? vp::CellShareInside(a.Wall, lattice.CellMm)
                                             : walk.FieldShare(cube.Centre, 0.5 * lattice.CellMm);
      o.InBoth = toolShare * vesselShare;
    }
    o.Uncertain = (nearTool || nearVessel) && (inside || nearVessel) ? 1.0 : 0.0;
    if (inside)
    {
      o.Deep = Pending{ high, cube, queried, 0 };
    }
    return o;
  }
  if (!a.Near)
  {
    // The vessel wall is farther than any of the cube's cells reaches: all inside, or all out.
    if (inside)
    {
      o.InBoth = cube.ToolCells();
      o.Uncertain = static_cast<double>(cube.CellsNearTool());
      o.Deep = Pending{ KeyOf(lattice, high, cube.Level), cube, queried, 0 };
    }
    return o;
  }
  o.Crossed = Straddler{ probe, a, inside, high };
  return o;
}

/// A cube the wall crosses, left unsplit when the budget ran out: its instrument cells counted by
/// the share of the cube behind the wall's plane at its centre (off by the wall's bend across it,
/// edge² / 8R for a vessel of radius R), every one of them uncertain. Its cells lie at most its
/// centre's depth plus its half diagonal deep (a centre outside: the half diagonal, the segment
/// to any cell inside crossing the wall), which bounds the depth left unsearched there.
template <typename L>
void Estimate(const L& lattice, Walk& walk, const Straddler& s)
{
  const Cube& cube = s.From.Where;
  const double edgeMm = std::ldexp(lattice.CellMm, cube.Level);
  double vesselShare = 0.0;
  if (s.A.HasWall)
  {
    // A wall that bends away from its plane (a vessel is convex across its axis) holds less of
    // the cube than the plane says: by its mean sag over the cube's face, H edge² / 12 for a
    // mean curvature H. The bend between this cube's plane and its parent's is the curvature in
    // one direction, the mean over the many cubes of a wall: the plane moved in by that sag.
    vp::WallPlane wall = s.A.Wall;
    if (s.From.ParentWall)
    {
      const double bend = BendPerMm(wall, cube.Centre, *s.From.ParentWall, s.From.ParentCentre.data());
      wall.OffsetMm -= std::clamp(bend * edgeMm * edgeMm / 12.0, -0.5 * edgeMm, 0.5 * edgeMm);
    }
    vesselShare = vp::CellShareInside(wall, edgeMm);
  }
  else
  {
    // The field's share is its column's through the point: a cube's is the mean of its eight
    // octants' columns, each a quarter edge off the centre (lookups cost next to nothing).
    const double q = 0.25 * edgeMm;
    for (int k = 0; k < 8; ++k)
    {
      const double octant[3] = { cube.Centre[0] + ((k & 1) ? q : -q), cube.Centre[1] + ((k & 2) ? q : -q),
        cube.Centre[2] + ((k & 4) ? q : -q) };
      vesselShare += walk.FieldShare(octant, q) / 8.0;
    }
  }
  walk.CellsInBoth += cube.ToolCells() * vesselShare;
  walk.CellsUncertain += cube.ToolCells();
  const double deepestMm = (s.Inside ? s.High : 0.0) + lattice.HalfDiagonalMm(cube.Level);
  walk.UnsearchedDepthMm = std::max(walk.UnsearchedDepthMm, deepestMm);
  walk.Estimated = true;
}

/// Queries a level's cubes, on every core when there are many, and adds their outcomes to the
/// walk in order; crossed receives the cubes the wall may cross (outcomes: scratch).
template <typename L>
void ResolveLevel(const L& lattice, Walk& walk, const std::vector<Probe>& level, PendingQueue& deepest,
  std::vector<Outcome>& outcomes, std::vector<Straddler>& crossed)
{
  outcomes.resize(level.size());
  auto resolve = [&](vtkIdType first, vtkIdType last) {
    Walk scratch = walk;
    for (vtkIdType i = first; i < last; ++i)
    {
      outcomes[static_cast<std::size_t>(i)] = Resolve(lattice, scratch, level[static_cast<std::size_t>(i)]);
    }
  };
  // A query is a microsecond or two: below some hundreds, a thread's start costs more than it saves.
  if (level.size() >= 256)
  {
    vtkSMPTools::For(0, static_cast<vtkIdType>(level.size()), 64, resolve);
  }
  else
  {
    resolve(0, static_cast<vtkIdType>(level.size()));
  }
  crossed.clear();
  for (Outcome& o : outcomes)
  {
    walk.CellsInBoth += o.InBoth;
    walk.CellsUncertain += o.Uncertain;
    walk.Queries += o.Queries;
    if (o.Deep)
    {
      deepest.push(*o.Deep);
    }
    if (o.Crossed)
    {
      crossed.push_back(*o.Crossed);
    }
  }
}

/// Of the crossed cubes, which to split when not all fit the budget: those the instrument's wall
/// also crosses first (a plane's share times the instrument's is wrong where both walls meet),
/// then those whose centre lies nearest the vessel wall (the plane halves them: the most to get
/// wrong). Stable, so that the same pose splits the same cubes.
inline std::vector<std::size_t> SplitOrder(const std::vector<Straddler>& crossed)
{
  std::vector<std::size_t> order(crossed.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  auto gap = [&](std::size_t i) { return std::isfinite(crossed[i].A.High) ? crossed[i].A.High : 0.0; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const bool ma = crossed[a].From.Where.CellsNearTool() > 0, mb = crossed[b].From.Where.CellsNearTool() > 0;
    return ma != mb ? ma : gap(a) < gap(b);
  });
  return order;
}

/// Counts the cells inside both solids, level by level from the root: each level's cubes are
/// queried (a query searches no farther than the cube's own reach, so its cost does not grow with
/// how deep it lies), and only the cubes the vessel wall may cross are split. Where the exact
/// engine finds no wall within a cube's reach, the cube lies on its parent's side (the segment
/// between their centres is shorter than the reach). When splitting all of a level's crossed
/// cubes would pass the budget, those that fit are split (SplitOrder) and the others estimated
/// (Estimate): the walk's cost stays bounded however large the overlap, and the uncertain volume
/// says what that cost.
template <typename L>
void Visit(const L& lattice, Walk& walk, const Probe& root, long long budget, PendingQueue& deepest)
{
  std::vector<Probe> level{ root }, next;
  std::vector<Outcome> outcomes;
  std::vector<Straddler> crossed;
  while (!level.empty())
  {
    ResolveLevel(lattice, walk, level, deepest, outcomes, crossed);
    long long left = budget > 0 ? budget - walk.Queries : std::numeric_limits<long long>::max();
    next.clear();
    for (std::size_t i : SplitOrder(crossed))
    {
      const Straddler& s = crossed[i];
      const int count = lattice.ChildCount(s.From.Where);
      if (count > left)
      {
        Estimate(lattice, walk, s);
        left = 0; // the rest too, in the same order: the budget is spent
        continue;
      }
      left -= count;
      Cube c[8];
      lattice.Children(s.From.Where, c);
      for (int k = 0; k < count; ++k)
      {
        next.push_back({ c[k], s.A.Inside ? s.A.Inside : std::optional<bool>(s.Inside), s.A.High,
          s.A.HasWall ? std::optional<vp::WallPlane>(s.A.Wall) : std::nullopt,
          { s.From.Where.Centre[0], s.From.Where.Centre[1], s.From.Where.Centre[2] } });
      }
    }
    std::swap(level, next);
  }
}

/// The deepest cell centre of the cubes wholly inside the vessel, best first: a cube is opened
/// only while its key beats the deepest found by more than the slack, and its children are
/// queried only when their parent's bound says they might. Keys never fall below the truth, so
/// no deeper cell is missed. Stops after budget deep queries (0: none); the best key left then
/// bounds every cell not searched (Walk::UnsearchedDepthMm).
template <typename L>
void FindDeepest(const L& lattice, Walk& walk, PendingQueue& queue, long long budget)
{
  const long long start = walk.DeepQueries;
  while (!queue.empty())
  {
    const Pending top = queue.top();
    if (top.Key <= walk.DepthMm + vtkScalpelPenetration::DepthSlackMm ||
      (budget > 0 && walk.DeepQueries - start >= budget))
    {
      walk.UnsearchedDepthMm = std::max(walk.UnsearchedDepthMm, top.Key);
      return;
    }
    queue.pop();
    if (!top.Queried)
    {
      if (walk.WallPoints.size() > top.WallPointsSeen)
      {
        const double key = KeyOf(lattice, walk.WallBoundMm(top.Where.Centre), top.Where.Level);
        if (key < top.Key)
        {
          queue.push({ key, top.Where, false, walk.WallPoints.size() });
          continue;
        }
      }
      const double centreBound = top.Where.Level == 0 ? top.Key : top.Key - lattice.HalfDiagonalMm(top.Where.Level);
      queue.push({ KeyOf(lattice, walk.DeepHigh(top.Where.Centre, centreBound), top.Where.Level), top.Where, true });
      continue;
    }
    if (top.Where.Level == 0)
    {
      walk.DepthMm = top.Key;
      continue;
    }
    const double high = top.Key - lattice.HalfDiagonalMm(top.Where.Level);
    Cube children[8];
    const int count = lattice.Children(top.Where, children);
    for (int k = 0; k < count; ++k)
    {
      const int level = children[k].Level;
      queue.push({ KeyOf(lattice, high + lattice.HalfDiagonalMm(level), level), children[k], false, 0 });
    }
  }
}
} // namespace

void vtkScalpelPenetration::ComputePenetration(const std::array<double, 16>& m,
  const std::vector<vp::SurfaceProximity>& surface, std::vector<vp::Penetration>& out) const
{
  if (!this->Vessels)
  {
    throw std::logic_error("vtkScalpelPenetration: set the vessel distance engine first");
  }
  const_cast<vtkScalpelPenetration*>(this)->Build();
  const int classes = this->Vessels->GetNumberOfVessels();
  // With the z-buffer, its field answers the walk (see SetZBufferSurface).
  const std::shared_ptr<const vp::CellDistanceField> field = this->ZBufferSurface ? this->ZBufferSurface->GetDistanceField() : nullptr;
  if (field && (!field->HasInside() || field->NumberOfClasses() != classes))
  {
    throw std::logic_error("vtkScalpelPenetration: the z-buffer's field does not match the vessel classes");
  }
  out.assign(static_cast<std::size_t>(classes), vp::Penetration());
  // The classes are independent walks over shared, read-only trees: one thread each where two or
  // more cross the instrument (the others cost a query at most, less than a thread's start).
  auto compute = [&](vtkIdType first, vtkIdType last) {
    for (vtkIdType c = first; c < last; ++c)
    {
      out[static_cast<std::size_t>(c)] = this->ComputeClass(static_cast<int>(c), m, surface, field.get());
    }
  };
  const auto crossing = std::count_if(surface.begin(), surface.end(),
    [](const vp::SurfaceProximity& s) { return s.InRange && s.DistanceMm <= 0.0; });
  if (crossing >= 2)
  {
    vtkSMPTools::For(0, classes, 1, compute);
  }
  else
  {
    compute(0, classes);
  }
}

vp::Penetration vtkScalpelPenetration::ComputeClass(int c, const std::array<double, 16>& m,
  const std::vector<vp::SurfaceProximity>& surface, const vp::CellDistanceField* field) const
{
  const Lattice& lattice = *this->Tool;
  vp::Penetration p;
  if (!lattice.Closed || !this->Vessels->GetSurface(c).IsClosed())
  {
    p.Known = false;
    return p;
  }
  if (lattice.Root < 0 || static_cast<std::size_t>(c) >= surface.size() || !surface[static_cast<std::size_t>(c)].InRange)
  {
    return p; // nothing within range: nothing overlaps
  }
  // A cell is near the wall while the wall may lie within the lattice's half diagonal of it, or,
  // from the z-buffer's field, within a layer cell's diagonal (where the layers' inside may be
  // wrong); the deepest cell's depth is then its upper bound, within the field's interval.
  const double nearMm = field ? std::max(lattice.HalfDiagonalMm(0), 2.0 * field->GetLayerGrid().ErrorBoundMm()) : lattice.HalfDiagonalMm(0);
  const double depthBoundMm = lattice.HalfDiagonalMm(0) + (field ? 2.0 * field->BoundMm() : DeepSearchToleranceMm);
  Walk walk{ field ? nullptr : this->Vessels.GetPointer(), field, c, m, nearMm };
  std::optional<bool> rootInside;
  if (surface[static_cast<std::size_t>(c)].DistanceMm > 0.0)
  {
    // The walls do not meet: the instrument is wholly inside the vessel, or wholly outside.
    if (!walk.InsideAnywhere(lattice.SurfacePoint))
    {
      return p;
    }
    rootInside = true;
  }
  const Node& root = lattice.Nodes[static_cast<std::size_t>(lattice.Root)];
  PendingQueue deepest;
  Visit(lattice, walk, Probe{ Cube{ { root.Centre[0], root.Centre[1], root.Centre[2] }, root.Level, &root }, rootInside,
                         std::numeric_limits<double>::infinity(), std::nullopt, {} },
    field ? static_cast<long long>(FieldBudgetFactor * static_cast<double>(this->QueryBudget)) : this->QueryBudget, deepest);
  // A deep query reads the many nearly equidistant triangles around a point deep inside (about
  // ten times a cell's near query here): the search gets an eighth of the budget (DeepShare).
  const long long deepBudget = this->QueryBudget > 0 ? std::max<long long>(16, this->QueryBudget / DeepShare) : 0;
  FindDeepest(lattice, walk, deepest, deepBudget);
  const double cell3 = std::pow(lattice.CellMm, 3);
  p.VolumeMm3 = cell3 * walk.CellsInBoth;
  p.VolumeBoundMm3 = cell3 * walk.CellsUncertain;
  // The depth never below the truth beyond its bound: where the search stopped short, the best
  // bound left over the cells not searched is the answer (an overstatement, as the contract
  // allows), and the bound grows by how far that lies above the deepest cell found.
  p.DepthMm = std::max(walk.DepthMm, walk.UnsearchedDepthMm);
  p.DepthBoundMm = walk.CellsInBoth + walk.CellsUncertain > 0 ? depthBoundMm + (p.DepthMm - walk.DepthMm) : 0.0;
  p.WallQueries = walk.Queries + walk.DeepQueries;
  p.BudgetReached = walk.Estimated || (deepBudget > 0 && walk.DeepQueries >= deepBudget);
  return p;
}

void vtkScalpelPenetration::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VesselDistance: " << (this->Vessels ? "set" : "(none)") << "\n";
  os << indent << "ZBufferSurface: " << (this->ZBufferSurface ? "set (the walk reads its field)" : "(none)") << "\n";
  os << indent << "CellSizeMm: " << this->CellSizeMm << "\n";
  os << indent << "QueryBudget: " << this->QueryBudget << "\n";
  os << indent << "LatticeNodes: " << (this->Tool ? this->Tool->Nodes.size() : 0) << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
}
