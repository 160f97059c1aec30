#ifndef vpVesselSurface_h
#define vpVesselSurface_h

#include "vpTriangleGeometry.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

class vtkPolyData;

namespace vp
{
/// What keeps a surface from being closed, counted over its undirected edges: an edge of one
/// triangle is a boundary (a hole's rim), of three or more non-manifold (a fin, a duplicated
/// sheet), of two wound the same way inconsistent (a piece turned inside out). Components are
/// the pieces joined through edges of exactly two triangles.
struct MeshDefects
{
  std::size_t BoundaryEdges = 0;
  std::size_t NonManifoldEdges = 0;
  std::size_t InconsistentEdges = 0;
  std::size_t Components = 0;
  bool Any() const { return BoundaryEdges + NonManifoldEdges + InconsistentEdges > 0; }
  /// "3 boundary edges, 1 non-manifold edge, 2 components", or "closed, 2 components".
  std::string Describe() const;
};

/// One vessel class's surface, prepared once for distance queries: indexed triangles in double
/// precision, and, for closed surfaces, what the sign test needs: outward face normals,
/// neighbour triangles across each edge and angle-weighted vertex pseudonormals.
///
/// "Closed" means every edge is shared by exactly two triangles that traverse it in opposite
/// directions (watertight, manifold, consistently wound). Each connected piece is turned to face
/// outward by the sign of its enclosed volume, so meshes that wind inward (IRCADb's, VMTK's) get
/// a correct inside test too. Open meshes answer "unknown" rather than guess.
class VesselSurface
{
public:
  /// Takes the triangles of mesh (other cells are ignored). Throws InputError(name, ...) when it
  /// has no triangles or non-finite points.
  VesselSurface(const std::string& name, vtkPolyData* mesh);

  const std::string& Name() const { return this->ClassName; }
  std::size_t NumberOfTriangles() const { return this->Triangles.size(); }
  std::size_t NumberOfPoints() const { return this->Points.size(); }
  bool IsClosed() const { return this->Closed; }
  /// The defects that keep it from being closed (none when closed).
  const MeshDefects& Defects() const { return this->DefectCounts; }
  /// The edges held by an odd number of triangles (point ids): a hole's rim, a fin's edge. Empty
  /// when closed. Where a ray sweeps over one, the parity of its crossings turns.
  const std::vector<std::array<std::int32_t, 2>>& OddEdges() const { return this->OddEdgeList; }
  const double* Point(std::int32_t id) const { return this->Points[id].data(); }
  const std::array<std::int32_t, 3>& Triangle(std::size_t t) const { return this->Triangles[t]; }
  const std::vector<std::array<double, 3>>& PointArray() const { return this->Points; }
  const std::vector<std::array<std::int32_t, 3>>& TriangleArray() const { return this->Triangles; }
  const double* Bounds() const { return this->BoundsMm.data(); }

  /// The unit outward normal of triangle t of a closed surface (null for an open one).
  const double* OutwardNormal(std::size_t t) const { return this->Closed ? this->FaceNormals[t].data() : nullptr; }

  /// Whether point p lies inside the closed surface, given its closest point on triangle t and
  /// the feature holding it. Empty for open surfaces; false on the surface itself
  /// (within 1e-9 mm, a picometre).
  std::optional<bool> IsInside(const double p[3], std::size_t t, const double closest[3],
    TriangleFeature feature) const;

private:
  std::string ClassName;
  std::vector<std::array<double, 3>> Points;
  std::vector<std::array<std::int32_t, 3>> Triangles;
  std::array<double, 6> BoundsMm{};
  bool Closed = false;
  MeshDefects DefectCounts;
  std::vector<std::array<std::int32_t, 2>> OddEdgeList;
  // Only filled for closed surfaces.
  std::vector<std::array<double, 3>> FaceNormals;     // unit, outward
  std::vector<std::array<std::int32_t, 3>> Neighbours; // across edge ab, bc, ca
  std::vector<std::array<double, 3>> VertexNormals;   // angle-weighted, outward

  void BuildTopology();
  /// Per triangle its unit normal, turned so that each closed piece (parent: the pieces) faces out.
  std::vector<std::array<double, 3>> OutwardFaceNormals(std::vector<std::int32_t>& parent) const;
  /// Per point the angle-weighted sum of its triangles' normals (the pseudonormal's direction).
  std::vector<std::array<double, 3>> AngleWeightedVertexNormals(const std::vector<std::array<double, 3>>& faceNormals) const;
};
} // namespace vp

#endif
