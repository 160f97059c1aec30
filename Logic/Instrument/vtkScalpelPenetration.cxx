#include "vtkScalpelPenetration.h"

#include "vpCellDistanceField.h"
#include "vpInputError.h"
#include "vtkZBufferSurfaceDistance.h"

#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

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
  int FirstChild = -1;   ///< Mixed: its children are Nodes[FirstChild, FirstChild + ChildCount)
  int ChildCount = 0;
  long long CellsInTool = 0;
  long long CellsNearTool = 0;
};

/// A cube of the walk: an explicit node, or an implied child of a Full one.
struct Cube
{
  double Centre[3];
  int Level;
  const Node* Explicit; ///< null for an implied cube (all cells inside, none near the wall)
  long long CellsInTool() const { return this->Explicit ? this->Explicit->CellsInTool : 1LL << (3 * this->Level); }
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
    const double d = tool->NearestDistanceWithin(0, centre, AnywhereMm, &inside);
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
      node.CellsInTool = node.InTool ? 1 : 0;
      node.CellsNearTool = node.NearTool ? 1 : 0;
    }
    else if (d > this->HalfDiagonalMm(level) + r)
    {
      if (!inside.value_or(false))
      {
        return -1; // wholly outside the instrument
      }
      node.Type = Kind::Full;
      node.CellsInTool = 1LL << (3 * level);
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
        node.CellsInTool += k.CellsInTool;
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
  long long CellsInBoth = 0;
  long long CellsUncertain = 0;
  double DepthMm = 0.0;

  struct Answer
  {
    double Low;  ///< the wall is at least this far
    double High; ///< and at most this far
    bool Inside;
  };
  Answer Query(const double model[3]) const
  {
    double w[3];
    for (int r = 0; r < 3; ++r)
    {
      w[r] = this->M[4 * r] * model[0] + this->M[4 * r + 1] * model[1] + this->M[4 * r + 2] * model[2] + this->M[4 * r + 3];
    }
    if (this->Field)
    {
      Answer a;
      this->Field->Bounds(this->Class, w, a.Low, a.High);
      a.Inside = this->Field->Inside(this->Class, w);
      return a;
    }
    std::optional<bool> inside;
    const double d = this->Vessels->NearestDistanceWithin(this->Class, w, AnywhereMm, &inside);
    return { d, d, inside.value_or(false) };
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
  volume = cell3 * static_cast<double>(root.CellsInTool);
  bound = cell3 * static_cast<double>(root.CellsNearTool);
  return true;
}

namespace
{
/// The deepest cell of a cube known to lie wholly inside the vessel: children farthest from the
/// wall first, and none whose farthest cell cannot beat the depth found.
template <typename L>
void Deepest(const L& lattice, Walk& walk, const Cube& cube)
{
  Cube children[8];
  const int count = lattice.Children(cube, children);
  std::pair<double, int> order[8]; // the farthest the wall can be
  for (int k = 0; k < count; ++k)
  {
    order[k] = { walk.Query(children[k].Centre).High, k };
  }
  for (int k = 1; k < count; ++k) // at most eight: farthest from the wall first
  {
    for (int j = k; j > 0 && order[j - 1].first < order[j].first; --j)
    {
      std::swap(order[j - 1], order[j]);
    }
  }
  for (int k = 0; k < count; ++k)
  {
    const Cube& child = children[order[k].second];
    if (child.Level == 0)
    {
      walk.DepthMm = std::max(walk.DepthMm, order[k].first);
    }
    else if (order[k].first + lattice.HalfDiagonalMm(child.Level) > walk.DepthMm)
    {
      Deepest(lattice, walk, child);
    }
  }
}

template <typename L>
void Visit(const L& lattice, Walk& walk, const Cube& cube)
{
  const Walk::Answer a = walk.Query(cube.Centre);
  const double r = walk.NearMm;
  const double reach = lattice.HalfDiagonalMm(cube.Level);
  const bool inside = a.Inside;
  if (cube.Level == 0)
  {
    const bool inTool = cube.Explicit ? cube.Explicit->InTool : true;
    const bool nearTool = cube.Explicit ? cube.Explicit->NearTool : false;
    const bool nearVessel = a.Low <= r;
    walk.CellsInBoth += inTool && inside ? 1 : 0;
    walk.CellsUncertain += (nearTool || nearVessel) && (inside || nearVessel) ? 1 : 0;
    if (inside)
    {
      walk.DepthMm = std::max(walk.DepthMm, a.High);
    }
    return;
  }
  if (a.Low > reach + r)
  {
    // The vessel wall is farther than any of the cube's cells reaches: all inside, or all out.
    if (inside)
    {
      walk.CellsInBoth += cube.CellsInTool();
      walk.CellsUncertain += cube.CellsNearTool();
      if (a.High + reach > walk.DepthMm)
      {
        Deepest(lattice, walk, cube);
      }
    }
    return;
  }
  Cube children[8];
  const int count = lattice.Children(cube, children);
  for (int k = 0; k < count; ++k)
  {
    Visit(lattice, walk, children[k]);
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
  const Lattice& lattice = *this->Tool;
  const int classes = this->Vessels->GetNumberOfVessels();
  // With the z-buffer, its field answers the walk: a cell is near the wall while the wall may lie
  // within a layer cell's diagonal (where the layers' inside may be wrong) or within the
  // lattice's half diagonal, and the deepest cell's depth is its upper bound, within the field's
  // interval and the lattice's half diagonal of the truth.
  const std::shared_ptr<const vp::CellDistanceField> field = this->ZBufferSurface ? this->ZBufferSurface->GetDistanceField() : nullptr;
  if (field && (!field->HasInside() || field->NumberOfClasses() != classes))
  {
    throw std::logic_error("vtkScalpelPenetration: the z-buffer's field does not match the vessel classes");
  }
  const double nearMm = field ? std::max(lattice.HalfDiagonalMm(0), 2.0 * field->GetLayerGrid().ErrorBoundMm()) : lattice.HalfDiagonalMm(0);
  const double depthBoundMm = field ? lattice.HalfDiagonalMm(0) + 2.0 * field->BoundMm() : lattice.HalfDiagonalMm(0);
  out.assign(static_cast<std::size_t>(classes), vp::Penetration());
  const double cell3 = std::pow(lattice.CellMm, 3);
  for (int c = 0; c < classes; ++c)
  {
    vp::Penetration& p = out[static_cast<std::size_t>(c)];
    if (!lattice.Closed || !this->Vessels->GetSurface(c).IsClosed())
    {
      p.Known = false;
      continue;
    }
    if (lattice.Root < 0 || static_cast<std::size_t>(c) >= surface.size() || !surface[static_cast<std::size_t>(c)].InRange)
    {
      continue; // nothing within range: nothing overlaps
    }
    Walk walk{ field ? nullptr : this->Vessels.GetPointer(), field.get(), c, m, nearMm };
    if (surface[static_cast<std::size_t>(c)].DistanceMm > 0.0)
    {
      // The walls do not meet: the instrument is wholly inside the vessel, or wholly outside.
      if (!walk.Query(lattice.SurfacePoint).Inside)
      {
        continue;
      }
    }
    const Node& root = lattice.Nodes[static_cast<std::size_t>(lattice.Root)];
    Visit(lattice, walk, Cube{ { root.Centre[0], root.Centre[1], root.Centre[2] }, root.Level, &root });
    p.VolumeMm3 = cell3 * static_cast<double>(walk.CellsInBoth);
    p.VolumeBoundMm3 = cell3 * static_cast<double>(walk.CellsUncertain);
    p.DepthMm = walk.DepthMm;
    p.DepthBoundMm = walk.CellsInBoth + walk.CellsUncertain > 0 ? depthBoundMm : 0.0;
  }
}

void vtkScalpelPenetration::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VesselDistance: " << (this->Vessels ? "set" : "(none)") << "\n";
  os << indent << "ZBufferSurface: " << (this->ZBufferSurface ? "set (the walk reads its field)" : "(none)") << "\n";
  os << indent << "CellSizeMm: " << this->CellSizeMm << "\n";
  os << indent << "LatticeNodes: " << (this->Tool ? this->Tool->Nodes.size() : 0) << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
}
