#include "vtkFclSurfaceDistance.h"

#include "vpLibraryStateLock.h"

#include "vpInputError.h"
#include "vpMemory.h"
#include "vpVesselSurface.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/distance.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>

#include <cmath>
#include <iostream>
#include <mutex>
#include <sstream>
#include <limits>

#include <chrono>

vtkStandardNewMacro(vtkFclSurfaceDistance);

namespace
{
using Model = fcl::BVHModel<fcl::OBBRSSd>;
/// What FCL's tree takes per triangle, about: two OBBRSS nodes of 256 bytes, the indices, the
/// vertices, and our copies while it is built.
constexpr std::uint64_t BytesPerTriangle = 600;

/// FCL's tree over a prepared surface (triangulated, in the surface's own coordinates).
std::shared_ptr<Model> MakeModel(const vp::VesselSurface& surface)
{
  std::vector<fcl::Vector3d> points(surface.NumberOfPoints());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double* p = surface.Point(static_cast<std::int32_t>(i));
    points[i] = fcl::Vector3d(p[0], p[1], p[2]);
  }
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(surface.NumberOfTriangles());
  for (const auto& t : surface.TriangleArray())
  {
    triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2]));
  }
  auto model = std::make_shared<Model>();
  // FCL says a failure on std::cerr and goes on with a broken tree (a 10M-triangle vessel crashed
  // after "BVH Error! Out of memory"): its return codes decide, and its words stay off the terminal.
  // std::cerr is one for the process: trees built on several threads (a cohort's cases) take
  // their turns, or one would put back another's buffer, gone by then; ITK, which warns there,
  // takes the same lock.
  const std::lock_guard<std::mutex> lock(vp::LibraryStateLock());
  std::ostringstream said;
  std::streambuf* terminal = std::cerr.rdbuf(said.rdbuf());
  int status = model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  if (status == fcl::BVH_OK)
  {
    status = model->addSubModel(points, triangles);
  }
  if (status == fcl::BVH_OK)
  {
    status = model->endModel();
  }
  std::cerr.rdbuf(terminal);
  if (status != fcl::BVH_OK)
  {
    throw vp::InputError(surface.Name(), "FCL cannot build its tree of " + std::to_string(triangles.size()) + " triangles (" +
        (status == fcl::BVH_ERR_MODEL_OUT_OF_MEMORY ? std::string("out of memory") : "error " + std::to_string(status)) + ")");
  }
  return model;
}
} // namespace

struct vtkFclSurfaceDistance::Internals
{
  const vtkExactVesselDistance* VesselsBuiltFrom = nullptr;
  vtkMTimeType VesselsBuiltAt = 0;
  const vtkPolyData* ToolBuiltFrom = nullptr;
  vtkMTimeType ToolBuiltAt = 0;
  std::shared_ptr<Model> Tool;
  std::vector<std::shared_ptr<Model>> Vessels;
};

vtkFclSurfaceDistance::vtkFclSurfaceDistance()
  : Impl(std::make_unique<Internals>())
{
}
vtkFclSurfaceDistance::~vtkFclSurfaceDistance() = default;

long long vtkFclSurfaceDistance::GetNumberOfToolTriangles() const
{
  return this->Impl->Tool ? this->Impl->Tool->num_tris : 0;
}

void vtkFclSurfaceDistance::Build()
{
  if (!this->Vessels)
  {
    throw std::logic_error("vtkFclSurfaceDistance: set the vessel distance engine first");
  }
  std::lock_guard<std::mutex> lock(this->BuildLock);
  Internals& s = *this->Impl;
  this->Vessels->Build();
  const bool vesselsCurrent = s.VesselsBuiltFrom == this->Vessels && s.VesselsBuiltAt >= this->Vessels->GetMTime() &&
    static_cast<int>(s.Vessels.size()) == this->Vessels->GetNumberOfVessels();
  const bool toolCurrent =
    s.Tool && s.ToolBuiltFrom == this->ToolSurface && this->ToolSurface && s.ToolBuiltAt >= this->ToolSurface->GetMTime();
  if (vesselsCurrent && toolCurrent)
  {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  if (!this->ToolSurface || !this->ToolSurface->GetPoints() || this->ToolSurface->GetNumberOfPolys() == 0)
  {
    throw vp::InputError("scalpel model", "has no surface for the whole-instrument distance");
  }
  // Triangulated as the vessels are (fans of polygons), in model coordinates.
  s.Tool = MakeModel(vp::VesselSurface("scalpel model", this->ToolSurface));
  s.ToolBuiltFrom = this->ToolSurface;
  s.ToolBuiltAt = this->ToolSurface->GetMTime();
  if (vesselsCurrent)
  {
    this->BuildTimeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  s.Vessels.clear();
  for (int c = 0; c < this->Vessels->GetNumberOfVessels(); ++c)
  {
    const vp::VesselSurface& surface = this->Vessels->GetSurface(c);
    vp::CheckMemoryFor(BytesPerTriangle * surface.NumberOfTriangles(), surface.Name(),
      "FCL's tree of its " + std::to_string(surface.NumberOfTriangles()) + " triangles (the whole instrument's distance)");
    s.Vessels.push_back(MakeModel(surface));
  }
  s.VesselsBuiltFrom = this->Vessels;
  s.VesselsBuiltAt = this->Vessels->GetMTime();
  this->BuildTimeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

namespace
{
/// One class's closest pair within range, warm-started from the previous pose's pair (before,
/// may be null): FCL's traversal prunes from the minimum it holds. out is left out of range when
/// no pair lies within it.
void SearchClass(const Model* tool, const Model* vessel, const fcl::Transform3d& pose, const fcl::Transform3d& worldToTool,
  double range, const vp::SurfaceProximity* before, vp::SurfaceProximity& out)
{
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  // Nothing beyond the range is searched: the traversal prunes from its current minimum.
  fcl::DistanceResultd result(std::nextafter(range, std::numeric_limits<double>::max()));
  if (before && before->InRange && before->ToolTriangle >= 0 && before->ToolTriangle < tool->num_tris &&
    before->VesselTriangle >= 0 && before->VesselTriangle < vessel->num_tris)
  {
    // The previous closest pair at this pose, in the tool's frame as FCL's traversal measures.
    const fcl::Triangle& a = tool->tri_indices[before->ToolTriangle];
    const fcl::Triangle& b = vessel->tri_indices[before->VesselTriangle];
    fcl::Vector3d p, q;
    const double d = fcl::detail::TriangleDistance<double>::triDistance(tool->vertices[a[0]], tool->vertices[a[1]],
      tool->vertices[a[2]], worldToTool * vessel->vertices[b[0]], worldToTool * vessel->vertices[b[1]],
      worldToTool * vessel->vertices[b[2]], p, q);
    result.update(d, tool, vessel, static_cast<int>(before->ToolTriangle), static_cast<int>(before->VesselTriangle), p, q);
  }
  // The tool's pose goes in as a transform: the trees are never rebuilt.
  fcl::distance(tool, pose, vessel, fcl::Transform3d::Identity(), request, result);
  if (result.o1 != tool || result.o2 != vessel)
  {
    return; // no pair within range
  }
  // FCL gives an implementation-defined negative value for crossing meshes: touching is 0.
  const double d = std::max(0.0, result.min_distance);
  if (d <= range)
  {
    out.InRange = true;
    out.DistanceMm = d;
    out.ToolTriangle = result.b1;
    out.VesselTriangle = result.b2;
    for (int k = 0; k < 3; ++k)
    {
      out.PointOnToolMm[k] = result.nearest_points[0][k];
      out.PointOnVesselMm[k] = result.nearest_points[1][k];
    }
  }
}
} // namespace

void vtkFclSurfaceDistance::ComputeSurfaceProximity(
  const std::array<double, 16>& m, std::vector<vp::SurfaceProximity>& out, const std::vector<vp::SurfaceProximity>* previous) const
{
  const_cast<vtkFclSurfaceDistance*>(this)->Build();
  const Internals& s = *this->Impl;
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      pose.linear()(r, c) = m[4 * r + c];
    }
    pose.translation()(r) = m[4 * r + 3];
  }
  const fcl::Transform3d worldToTool = pose.inverse();
  const double range = this->SearchRangeMm();
  const bool warm = this->WarmStart && previous && previous->size() == s.Vessels.size();
  out.assign(s.Vessels.size(), vp::SurfaceProximity());
  // The classes are independent searches of shared, read-only trees: one thread each (in a
  // breach one class's search is long while the others are short).
  vtkSMPTools::For(0, static_cast<vtkIdType>(s.Vessels.size()), 1, [&](vtkIdType first, vtkIdType last) {
    for (vtkIdType c = first; c < last; ++c)
    {
      const auto i = static_cast<std::size_t>(c);
      SearchClass(s.Tool.get(), s.Vessels[i].get(), pose, worldToTool, range, warm ? &(*previous)[i] : nullptr, out[i]);
    }
  });
}

void vtkFclSurfaceDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WarmStart: " << (this->WarmStart ? "on" : "off") << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
}
