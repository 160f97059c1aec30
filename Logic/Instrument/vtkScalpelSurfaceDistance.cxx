#include "vtkScalpelSurfaceDistance.h"

#include "vpEdgeSplitting.h"
#include "vpInputError.h"
#include "vpTriangleGeometry.h"
#include "vtkExactVesselDistance.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>

vtkStandardNewMacro(vtkScalpelSurfaceDistance);

namespace
{
/// Triangles per leaf: small enough that a leaf near a vessel costs little, large enough that the
/// tree stays shallow (every visited node costs one point query).
constexpr std::size_t LeafTriangles = 8;
/// Longer tool edges are split first: instrument STLs carry shaft triangles 100 mm long, whose
/// bounding spheres would make every lower bound useless. Splitting changes no surface point.
constexpr double MaximumToolEdgeMm = 2.0;

struct Node
{
  double Centre[3] = { 0, 0, 0 }; ///< model coordinates
  double RadiusMm = 0;            ///< every point of the node's triangles lies within it
  int Children[2] = { -1, -1 };
  std::size_t Begin = 0, End = 0; ///< triangle range (leaves)
};
} // namespace

struct vtkScalpelSurfaceDistance::ToolTree
{
  std::vector<std::array<double, 3>> Points;
  std::vector<std::array<std::int32_t, 3>> Triangles; ///< reordered so each leaf's are contiguous
  std::vector<Node> Nodes;                         ///< Nodes[0] is the root

  int Build(std::size_t begin, std::size_t end)
  {
    Node node;
    double low[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
    double high[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (std::size_t t = begin; t < end; ++t)
    {
      for (std::int32_t id : this->Triangles[t])
      {
        for (int a = 0; a < 3; ++a)
        {
          low[a] = std::min(low[a], this->Points[id][a]);
          high[a] = std::max(high[a], this->Points[id][a]);
        }
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      node.Centre[a] = 0.5 * (low[a] + high[a]);
    }
    for (std::size_t t = begin; t < end; ++t)
    {
      for (std::int32_t id : this->Triangles[t])
      {
        node.RadiusMm = std::max(node.RadiusMm, std::sqrt(vp::Distance2(node.Centre, this->Points[id].data())));
      }
    }
    node.Begin = begin;
    node.End = end;
    const int index = static_cast<int>(this->Nodes.size());
    this->Nodes.push_back(node);
    if (end - begin <= LeafTriangles)
    {
      return index;
    }
    // Median split of the centroids along the box's longest side.
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (high[a] - low[a] > high[axis] - low[axis])
      {
        axis = a;
      }
    }
    const std::size_t middle = begin + (end - begin) / 2;
    auto centroid = [&](const std::array<std::int32_t, 3>& t) {
      return this->Points[t[0]][axis] + this->Points[t[1]][axis] + this->Points[t[2]][axis];
    };
    std::nth_element(this->Triangles.begin() + begin, this->Triangles.begin() + middle, this->Triangles.begin() + end,
      [&](const auto& a, const auto& b) { return centroid(a) < centroid(b); });
    const int left = this->Build(begin, middle);
    const int right = this->Build(middle, end);
    this->Nodes[index].Children[0] = left;
    this->Nodes[index].Children[1] = right;
    return index;
  }
};

vtkScalpelSurfaceDistance::vtkScalpelSurfaceDistance() = default;
vtkScalpelSurfaceDistance::~vtkScalpelSurfaceDistance() = default;

void vtkScalpelSurfaceDistance::SetVesselDistance(vtkExactVesselDistance* engine)
{
  if (this->Vessels != engine)
  {
    this->Vessels = engine;
    this->Modified();
  }
}

void vtkScalpelSurfaceDistance::SetToolSurface(vtkPolyData* model)
{
  this->ToolSurface = model;
  this->Tree.reset();
  this->Modified();
}

long long vtkScalpelSurfaceDistance::GetNumberOfToolTriangles() const
{
  return this->Tree ? static_cast<long long>(this->Tree->Triangles.size()) : 0;
}

void vtkScalpelSurfaceDistance::EnsureTree() const
{
  if (this->Tree)
  {
    return;
  }
  if (!this->ToolSurface || !this->ToolSurface->GetPoints() || this->ToolSurface->GetNumberOfPolys() == 0)
  {
    throw vp::InputError("scalpel model", "has no surface for the whole-instrument distance");
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(this->ToolSurface);
  triangles->PassLinesOff();
  triangles->PassVertsOff();
  triangles->Update();
  vtkPolyData* mesh = triangles->GetOutput();
  auto tree = std::make_shared<ToolTree>();
  tree->Points.resize(static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, tree->Points[static_cast<std::size_t>(i)].data());
  }
  const vtkIdType* ids = nullptr;
  vtkIdType n = 0;
  auto polys = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    polys->GetCurrentCell(n, ids);
    if (n == 3)
    {
      tree->Triangles.push_back(
        { static_cast<std::int32_t>(ids[0]), static_cast<std::int32_t>(ids[1]), static_cast<std::int32_t>(ids[2]) });
    }
  }
  if (tree->Triangles.empty())
  {
    throw vp::InputError("scalpel model", "has no triangles for the whole-instrument distance");
  }
  vp::SplitLongEdges(tree->Points, tree->Triangles, MaximumToolEdgeMm);
  tree->Build(0, tree->Triangles.size());
  this->Tree = std::move(tree);
}

void vtkScalpelSurfaceDistance::ComputeSurfaceProximity(
  const std::array<double, 16>& m, std::vector<vp::SurfaceProximity>& out, const std::vector<vp::SurfaceProximity>*) const
{
  if (!this->Vessels)
  {
    throw std::logic_error("vtkScalpelSurfaceDistance: set the vessel distance engine first");
  }
  this->EnsureTree();
  const ToolTree& tree = *this->Tree;
  auto place = [&m](const double p[3], double w[3]) {
    for (int r = 0; r < 3; ++r)
    {
      w[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
  };

  const int classes = this->Vessels->GetNumberOfVessels();
  const double range = this->SearchRangeMm();
  out.assign(static_cast<std::size_t>(classes), vp::SurfaceProximity());
  for (int c = 0; c < classes; ++c)
  {
    const vp::VesselSurface& vessel = this->Vessels->GetSurface(c);
    vp::SurfaceProximity& result = out[static_cast<std::size_t>(c)];
    double best = range; // nothing further counts
    // Best first: nodes by the lower bound of their distance, nearest first.
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
    auto push = [&](int index) {
      const Node& node = tree.Nodes[static_cast<std::size_t>(index)];
      double centre[3];
      place(node.Centre, centre);
      const double d = this->Vessels->NearestDistanceWithin(c, centre, best + node.RadiusMm);
      if (std::isfinite(d) && d - node.RadiusMm <= best)
      {
        open.emplace(d - node.RadiusMm, index);
      }
    };
    push(0);
    while (!open.empty())
    {
      const auto [lowerBound, index] = open.top();
      open.pop();
      if (lowerBound > best || (result.InRange && best == 0.0))
      {
        break; // nothing left can be nearer (and nothing is nearer than touching)
      }
      const Node& node = tree.Nodes[static_cast<std::size_t>(index)];
      if (node.Children[0] >= 0)
      {
        push(node.Children[0]);
        push(node.Children[1]);
        continue;
      }
      double centre[3];
      place(node.Centre, centre);
      // Only the leaves searched are placed in the world, not the whole tool every pose.
      std::array<std::array<double, 9>, LeafTriangles> corners;
      const std::size_t count = node.End - node.Begin;
      for (std::size_t t = 0; t < count; ++t)
      {
        for (int k = 0; k < 3; ++k)
        {
          place(tree.Points[static_cast<std::size_t>(tree.Triangles[node.Begin + t][k])].data(), &corners[t][3 * k]);
        }
      }
      this->Vessels->VisitTrianglesNear(c, centre, best + node.RadiusMm, [&](long long v) {
        const auto& vt = vessel.Triangle(static_cast<std::size_t>(v));
        const double* b0 = vessel.Point(vt[0]);
        const double* b1 = vessel.Point(vt[1]);
        const double* b2 = vessel.Point(vt[2]);
        // One point-triangle distance bounds the leaf's eight triangle pairs from below.
        double foot[3];
        vp::TriangleFeature feature;
        const double fromCentre = std::sqrt(vp::ClosestPointOnTriangle(centre, b0, b1, b2, foot, feature));
        if (fromCentre - node.RadiusMm > best)
        {
          return best + node.RadiusMm;
        }
        for (std::size_t t = 0; t < count; ++t)
        {
          double onTool[3], onVessel[3];
          const double d2 =
            vp::ClosestPointsOfTriangles(&corners[t][0], &corners[t][3], &corners[t][6], b0, b1, b2, onTool, onVessel);
          if (d2 <= best * best && (!result.InRange || d2 < result.DistanceMm * result.DistanceMm))
          {
            best = std::sqrt(d2);
            result.InRange = true;
            result.DistanceMm = best;
            std::copy(onTool, onTool + 3, result.PointOnToolMm);
            std::copy(onVessel, onVessel + 3, result.PointOnVesselMm);
          }
        }
        return best + node.RadiusMm;
      });
    }
  }
}

double vtkScalpelSurfaceDistance::SearchRangeMm() const
{
  return this->RangeMm > 0 ? std::min(this->RangeMm, this->Vessels->GetRangeMm()) : this->Vessels->GetRangeMm();
}

void vtkScalpelSurfaceDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VesselDistance: " << (this->Vessels ? "set" : "(none)") << "\n";
  os << indent << "RangeMm: " << this->RangeMm << (this->RangeMm > 0 ? "" : " (the vessel engine's)") << "\n";
  os << indent << "ToolTriangles: " << this->GetNumberOfToolTriangles() << "\n";
  os << indent << "ToolTreeNodes: " << (this->Tree ? this->Tree->Nodes.size() : 0) << "\n";
}
