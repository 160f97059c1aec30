#include "vtkExactVesselDistance.h"

#include "vpInputError.h"
#include "vpInsideVote.h"
#include "vpInsideVoteField.h"

#include <vtkObjectFactory.h>

#include <embree3/rtcore.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkExactVesselDistance);

vtkSmartPointer<vtkExactVesselDistance> vtkExactVesselDistance::ServingBeside(vtkVesselDistanceEngine* engine, bool needed)
{
  vtkSmartPointer<vtkExactVesselDistance> exact = vtkExactVesselDistance::SafeDownCast(engine);
  if (!exact && needed)
  {
    exact = vtkSmartPointer<vtkExactVesselDistance>::New();
    exact->SetRangeMm(engine->GetRangeMm());
  }
  return exact;
}

namespace
{
struct DeviceDeleter
{
  void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter
{
  void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

/// Collects every triangle a ray crosses: an intersection context whose filter records the hit
/// and rejects it, so that the traversal goes on to the next.
struct CrossingContext
{
  RTCIntersectContext Context; // first: Embree hands this pointer back to the filter
  std::vector<double>* Crossed; // distances along the ray, in the tree's float units (mm)
};

void CollectCrossing(const RTCFilterFunctionNArguments* args)
{
  auto* context = reinterpret_cast<CrossingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
  {
    if (args->valid[i] != 0)
    {
      context->Crossed->push_back(RTCRayN_tfar(args->ray, args->N, i));
      args->valid[i] = 0;
    }
  }
}

/// The inside vote field's reach beyond the vessel's box (mm), and its size (cells, a byte each:
/// 16 MB a class at most; IRCADb patient 1's vessels with a 50 mm reach fill it at 1.0-1.05 mm).
constexpr double MaxVoteFieldPadMm = 50.0;
constexpr std::size_t MaxVoteFieldCells = std::size_t(1) << 24;

/// First search radius; grown until the best triangle found lies within it (or the range is hit).
constexpr double InitialSearchRadiusMm = 1.0;

/// One class's tree. Vertices are stored relative to Origin to keep float rounding small.
struct ClassTree
{
  ScenePtr Scene;
  double Origin[3] = { 0, 0, 0 };
  /// How far the float tree may be from the double surface, plus the query point's rounding.
  double SlackMm = 0;
  /// An open surface's votes where no ray is needed (null: every vote casts its rays).
  std::unique_ptr<vp::InsideVoteField> VoteField;
};

struct QueryState
{
  const vp::VesselSurface* Surface;
  double Point[3];
  double Best2;
  long long Triangle;
  double Closest[3];
  vp::TriangleFeature Feature;
  double SlackMm;
  /// Nodes farther than the best so far less this are not searched: 0 for the nearest triangle,
  /// more for a distance known to that tolerance (a point deep inside, where many triangles are
  /// nearly equidistant and an exact search reads them all).
  double ToleranceMm = 0.0;
};

/// A ray from origin along direction up to tfar, in the tree's coordinates, with no hit yet.
RTCRayHit MakeRay(const ClassTree& tree, const double origin[3], const double direction[3], float tfar)
{
  RTCRayHit hit{};
  hit.ray.org_x = static_cast<float>(origin[0] - tree.Origin[0]);
  hit.ray.org_y = static_cast<float>(origin[1] - tree.Origin[1]);
  hit.ray.org_z = static_cast<float>(origin[2] - tree.Origin[2]);
  hit.ray.dir_x = static_cast<float>(direction[0]);
  hit.ray.dir_y = static_cast<float>(direction[1]);
  hit.ray.dir_z = static_cast<float>(direction[2]);
  hit.ray.tnear = 0.0f;
  hit.ray.tfar = tfar;
  hit.ray.mask = 0xFFFFFFFFu;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return hit;
}

/// Whether p is inside a surface that is not closed (vp::InsideVote), its crossings counted by
/// Embree.
bool VoteInsideRays(const ClassTree& tree, const double p[3], bool& uncertain)
{
  std::vector<double> crossed;
  int crossings[vp::InsideVote::Rays];
  for (int r = 0; r < vp::InsideVote::Rays; ++r)
  {
    const double* direction = vp::InsideVote::Directions[r];
    CrossingContext context;
    rtcInitIntersectContext(&context.Context);
    context.Context.filter = &CollectCrossing;
    context.Crossed = &crossed;
    crossed.clear();
    RTCRayHit hit = MakeRay(tree, p, direction, std::numeric_limits<float>::infinity());
    rtcIntersect1(tree.Scene.get(), &context.Context, &hit);
    // A triangle the tree holds in two leaves, reported twice, is one crossing too.
    crossings[r] = vp::InsideVote::CountCrossings(crossed);
  }
  return vp::InsideVote::Decide(crossings, uncertain);
}

/// The vote from the tree's field where it holds p's, from the rays elsewhere. On the surface
/// itself (distanceMm within a picometre) p is outside, as for a closed surface.
bool VoteInsideTree(const ClassTree& tree, const double p[3], double distanceMm, bool& uncertain)
{
  uncertain = false;
  if (distanceMm <= vp::InsideVote::OnSurfaceMm)
  {
    return false;
  }
  bool inside = false;
  if (tree.VoteField && tree.VoteField->Lookup(p, inside, uncertain))
  {
    return inside;
  }
  return VoteInsideRays(tree, p, uncertain);
}

/// Narrows Embree's search sphere to radiusMm (plus the tree's float slack), never widening it:
/// a candidate found just outside the sphere must not grow the search. Returns whether it shrank.
bool ShrinkQueryRadius(RTCPointQueryFunctionArguments* args, double radiusMm, double slackMm)
{
  const float shrunk = static_cast<float>(radiusMm + slackMm);
  if (shrunk >= args->query->radius)
  {
    return false;
  }
  args->query->radius = shrunk;
  return true;
}

bool VisitTriangle(RTCPointQueryFunctionArguments* args)
{
  auto* state = static_cast<QueryState*>(args->userPtr);
  const auto& tri = state->Surface->Triangle(args->primID);
  const double* a = state->Surface->Point(tri[0]);
  const double* b = state->Surface->Point(tri[1]);
  const double* c = state->Surface->Point(tri[2]);
  // The triangle's plane is no farther than the triangle: where the plane cannot beat the best,
  // the triangle cannot either. Deep inside a vessel that is most of the triangles the tree
  // shows; near a wall, few, and the test costs a tenth more than it saves (bench, random tips),
  // so only the deep searches make it. A triangle within the tolerance is still taken: it
  // narrows the search more.
  if (state->ToleranceMm > 0.0 && std::isfinite(state->Best2))
  {
    double ab[3], ac[3], ap[3], n[3];
    vp::Sub3(b, a, ab);
    vp::Sub3(c, a, ac);
    vp::Sub3(state->Point, a, ap);
    vp::Cross3(ab, ac, n);
    const double along = vp::Dot3(n, ap);
    if (along * along >= state->Best2 * vp::Dot3(n, n))
    {
      return false;
    }
  }
  double q[3];
  vp::TriangleFeature feature;
  const double d2 = vp::ClosestPointOnTriangle(state->Point, a, b, c, q, feature);
  if (d2 >= state->Best2)
  {
    return false;
  }
  state->Best2 = d2;
  state->Triangle = args->primID;
  state->Closest[0] = q[0];
  state->Closest[1] = q[1];
  state->Closest[2] = q[2];
  state->Feature = feature;
  return ShrinkQueryRadius(args, std::max(0.0, std::sqrt(d2) - state->ToleranceMm), state->SlackMm);
}

struct VisitorState
{
  const vtkExactVesselDistance::TriangleVisitor* Visit;
  double SlackMm;
};

bool VisitForCaller(RTCPointQueryFunctionArguments* args)
{
  auto* state = static_cast<VisitorState*>(args->userPtr);
  return ShrinkQueryRadius(args, (*state->Visit)(args->primID), state->SlackMm);
}

/// One Embree point query of a class tree: the sphere of radiusMm about centre (world mm).
void RunPointQuery(const ClassTree& tree, const double centre[3], double radiusMm, RTCPointQueryFunction visit, void* user)
{
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  RTC_ALIGN(16) RTCPointQuery query;
  query.x = static_cast<float>(centre[0] - tree.Origin[0]);
  query.y = static_cast<float>(centre[1] - tree.Origin[1]);
  query.z = static_cast<float>(centre[2] - tree.Origin[2]);
  query.time = 0.0f;
  query.radius = static_cast<float>(radiusMm + tree.SlackMm);
  rtcPointQuery(tree.Scene.get(), &query, &context, visit, user);
}

/// The triangle of the class nearest to point within radiusMm (Triangle -1 when none). Spheres
/// grow from 1 mm: a small sphere touches few tree nodes, and Embree's traversal is not nearest
/// first. Embree also shows triangles just outside a sphere (their leaf's box reaches in), so
/// the best found is the nearest only once it lies within the sphere searched; until then the
/// next sphere is the smaller of twice the last and the best.
QueryState FindNearestTriangle(const ClassTree& tree, const vp::VesselSurface& surface, const double point[3],
  double radiusMm, double toleranceMm = 0.0, double startMm = InitialSearchRadiusMm)
{
  QueryState state{ &surface, { point[0], point[1], point[2] }, std::numeric_limits<double>::infinity(), -1, { 0, 0, 0 },
    vp::TriangleFeature::Face, tree.SlackMm, toleranceMm };
  for (double r = std::min(radiusMm, startMm);;)
  {
    RunPointQuery(tree, point, r, &VisitTriangle, &state);
    const double best = std::sqrt(state.Best2);
    if (best <= r || r >= radiusMm)
    {
      return state;
    }
    r = std::min({ radiusMm, 2.0 * r, best });
  }
}

/// The answer, in range, from a nearest-triangle search's state: distance, point, and inside
/// (exact on a closed surface, voted on an open one when vote).
void FillAnswer(const ClassTree& tree, const vp::VesselSurface& surface, bool vote, const double tip[3],
  const QueryState& state, vp::ClassProximity& out)
{
  out.InRange = true;
  out.DistanceMm = std::sqrt(state.Best2);
  out.TriangleId = state.Triangle;
  std::copy(state.Closest, state.Closest + 3, out.ClosestPoint);
  if (surface.IsClosed())
  {
    out.Inside = surface.IsInside(tip, static_cast<std::size_t>(state.Triangle), state.Closest, state.Feature);
  }
  else if (vote)
  {
    out.Inside = VoteInsideTree(tree, tip, out.DistanceMm, out.InsideUncertain);
  }
}

void OnEmbreeError(void* userPtr, RTCError code, const char* message)
{
  auto* last = static_cast<std::string*>(userPtr);
  *last = "Embree error " + std::to_string(static_cast<int>(code)) + (message ? std::string(": ") + message : "");
}
} // namespace

struct vtkExactVesselDistance::Internals
{
  std::string LastError;
  DevicePtr Device;
  std::vector<ClassTree> Trees;
};

vtkExactVesselDistance::vtkExactVesselDistance()
  : Impl(new Internals)
{
}

vtkExactVesselDistance::~vtkExactVesselDistance()
{
  // Scenes hold references to the device: release them first.
  this->Impl->Trees.clear();
}

void vtkExactVesselDistance::BuildInternal()
{
  Internals& impl = *this->Impl;
  impl.Trees.clear();
  if (!impl.Device)
  {
    impl.Device.reset(rtcNewDevice("verbose=0"));
    if (!impl.Device)
    {
      throw std::runtime_error("cannot create an Embree device (CPU without SSE2?)");
    }
    rtcSetDeviceErrorFunction(impl.Device.get(), &OnEmbreeError, &impl.LastError);
  }
  for (const auto& surface : this->Surfaces)
  {
    ClassTree tree;
    const double* b = surface->Bounds();
    double extent = 0;
    for (int a = 0; a < 3; ++a)
    {
      tree.Origin[a] = 0.5 * (b[2 * a] + b[2 * a + 1]);
      extent = std::max(extent, 0.5 * (b[2 * a + 1] - b[2 * a]));
    }
    // Each float coordinate is within half an ulp of the double one; points, bounds and the
    // query's centre all round, so widen by a few ulps of the largest coordinate.
    tree.SlackMm = 8.0 * FLT_EPSILON * (extent + this->RangeMm + 1.0);
    tree.Scene.reset(rtcNewScene(impl.Device.get()));
    rtcSetSceneBuildQuality(tree.Scene.get(), RTC_BUILD_QUALITY_MEDIUM);
    // The inside vote's rays carry their own filter (CollectCrossing); the other rays none.
    rtcSetSceneFlags(tree.Scene.get(), RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(impl.Device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
      RTC_FORMAT_FLOAT3, 3 * sizeof(float), surface->NumberOfPoints()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
      RTC_FORMAT_UINT3, 3 * sizeof(unsigned), surface->NumberOfTriangles()));
    if (!vertices || !indices)
    {
      rtcReleaseGeometry(geometry);
      throw vp::InputError(surface->Name(), "out of memory building the distance tree (" + impl.LastError + ")");
    }
    for (std::size_t i = 0; i < surface->NumberOfPoints(); ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        vertices[3 * i + a] = static_cast<float>(surface->Point(static_cast<std::int32_t>(i))[a] - tree.Origin[a]);
      }
    }
    for (std::size_t t = 0; t < surface->NumberOfTriangles(); ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        indices[3 * t + k] = static_cast<unsigned>(surface->Triangle(t)[k]);
      }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(tree.Scene.get(), geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(tree.Scene.get());
    if (rtcGetDeviceError(impl.Device.get()) != RTC_ERROR_NONE)
    {
      throw vp::InputError(surface->Name(), "cannot build the distance tree (" + impl.LastError + ")");
    }
    if (!surface->IsClosed() && this->VoteOnOpenSurfaces && this->VoteFieldCellMm > 0.0)
    {
      // Reaching the range beyond the vessel's box (at most MaxVoteFieldPadMm): a tip in range
      // lies within it, and one beyond the range is voted on only inside the box.
      tree.VoteField = std::make_unique<vp::InsideVoteField>(*surface, this->VoteFieldCellMm,
        std::min(this->RangeMm, MaxVoteFieldPadMm), MaxVoteFieldCells,
        [&tree](const double p[3], bool& uncertain) { return VoteInsideRays(tree, p, uncertain); });
    }
    impl.Trees.push_back(std::move(tree));
  }
}

void vtkExactVesselDistance::ComputeProximity(const double tip[3], const double* axis,
  vp::ProximityResult& result, const vp::ProximityResult* previous) const
{
  this->BeginResult(tip, result);
  const double displacement = previous ? std::sqrt(vp::Distance2(tip, previous->Tip)) : 0.0;
  for (std::size_t c = 0; c < this->Surfaces.size(); ++c)
  {
    const vp::VesselSurface& surface = *this->Surfaces[c];
    const ClassTree& tree = this->Impl->Trees[c];
    vp::ClassProximity& out = result.Classes[c];

    double radius = this->RangeMm;
    if (previous && c < previous->Classes.size() && previous->Classes[c].InRange &&
      previous->Classes[c].ClassName == out.ClassName)
    {
      // The triangle inequality bounds the new distance by the old one plus the step.
      radius = std::min(radius, previous->Classes[c].DistanceMm + displacement);
    }
    const QueryState state = FindNearestTriangle(tree, surface, tip, radius);
    const double distance = std::sqrt(state.Best2);
    if (state.Triangle < 0 || distance > this->RangeMm)
    {
      // Out of range is no answer for a tip inside the class: its wall may lie farther than the
      // range, and that is a breach, never "safe".
      this->FindDepthBeyondRange(static_cast<int>(c), tip, out);
    }
    else
    {
      FillAnswer(tree, surface, this->VoteOnOpenSurfaces, tip, state, out);
    }

    if (axis)
    {
      RTCIntersectContext intersect;
      rtcInitIntersectContext(&intersect);
      RTCRayHit hit = MakeRay(tree, tip, axis, static_cast<float>(this->RangeMm + tree.SlackMm));
      rtcIntersect1(tree.Scene.get(), &intersect, &hit);
      if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID)
      {
        // Re-intersect the hit triangle in double; keep the float answer on a grazing miss.
        const auto& tri = surface.Triangle(hit.hit.primID);
        const double t = vp::RayTriangle(tip, axis, surface.Point(tri[0]), surface.Point(tri[1]), surface.Point(tri[2]));
        const double along = t >= 0.0 ? t : static_cast<double>(hit.ray.tfar);
        if (along <= this->RangeMm)
        {
          out.DirectionalMm = along;
        }
      }
    }
  }
}

bool vtkExactVesselDistance::FindDepthBeyondRange(int classIndex, const double tip[3], vp::ClassProximity& out) const
{
  this->EnsureBuilt();
  const auto c = static_cast<std::size_t>(classIndex);
  const vp::VesselSurface& surface = *this->Surfaces.at(c);
  const double* b = surface.Bounds();
  for (int a = 0; a < 3; ++a)
  {
    if (!(tip[a] >= b[2 * a] && tip[a] <= b[2 * a + 1]))
    {
      return false; // outside the class's box: outside the class
    }
  }
  if (!surface.IsClosed() && this->VoteOnOpenSurfaces)
  {
    // The vote the answer would take, first: a tip it finds outside needs no search for the
    // nearest wall, which, unbounded, costs many times the vote's five rays (the z-buffer's
    // batches ask this of every answer beyond the range). The wall's distance only turns the
    // vote to "outside" on the surface, where this answer is "outside" anyway.
    bool uncertain = false;
    if (!VoteInsideTree(this->Impl->Trees[c], tip, std::numeric_limits<double>::infinity(), uncertain) && !uncertain)
    {
      return false;
    }
  }
  const QueryState state =
    FindNearestTriangle(this->Impl->Trees[c], surface, tip, std::numeric_limits<double>::infinity());
  if (state.Triangle < 0)
  {
    return false;
  }
  vp::ClassProximity answer;
  answer.ClassName = out.ClassName;
  FillAnswer(this->Impl->Trees[c], surface, this->VoteOnOpenSurfaces, tip, state, answer);
  if (!answer.Inside.value_or(false) && !answer.InsideUncertain)
  {
    return false; // outside, and the wall beyond the range: out of range
  }
  answer.DirectionalMm = out.DirectionalMm;
  out = answer;
  return true;
}

void vtkExactVesselDistance::VisitTrianglesNear(
  int classIndex, const double centre[3], double radiusMm, const TriangleVisitor& visit) const
{
  this->EnsureBuilt();
  const ClassTree& tree = this->Impl->Trees.at(static_cast<std::size_t>(classIndex));
  VisitorState state{ &visit, tree.SlackMm };
  RunPointQuery(tree, centre, radiusMm, &VisitForCaller, &state);
}

double vtkExactVesselDistance::NearestDistanceWithin(
  int classIndex, const double point[3], double radiusMm, std::optional<bool>* inside, double wallPoint[3],
  double outwardNormal[3]) const
{
  this->EnsureBuilt();
  const auto c = static_cast<std::size_t>(classIndex);
  const vp::VesselSurface& surface = *this->Surfaces.at(c);
  const QueryState state = FindNearestTriangle(this->Impl->Trees.at(c), surface, point, radiusMm);
  const double best = std::sqrt(state.Best2);
  const bool found = state.Triangle >= 0 && best <= radiusMm;
  const std::optional<bool> in =
    found ? surface.IsInside(point, static_cast<std::size_t>(state.Triangle), state.Closest, state.Feature) : std::nullopt;
  if (inside)
  {
    *inside = in;
  }
  if (wallPoint && found)
  {
    std::copy(state.Closest, state.Closest + 3, wallPoint);
  }
  if (outwardNormal && in)
  {
    if (best > 1e-9)
    {
      for (int a = 0; a < 3; ++a)
      {
        outwardNormal[a] = (*in ? state.Closest[a] - point[a] : point[a] - state.Closest[a]) / best;
      }
    }
    else
    {
      const double* n = surface.OutwardNormal(static_cast<std::size_t>(state.Triangle));
      std::copy(n, n + 3, outwardNormal);
    }
  }
  return found ? best : std::numeric_limits<double>::infinity();
}

double vtkExactVesselDistance::DistanceUpperBoundWithin(
  int classIndex, const double point[3], double knownWithinMm, double toleranceMm, double wallPoint[3]) const
{
  this->EnsureBuilt();
  const auto c = static_cast<std::size_t>(classIndex);
  // A wall known within a distance is found in one search of that sphere; else they grow.
  const double start = std::isfinite(knownWithinMm) ? knownWithinMm : InitialSearchRadiusMm;
  const double radiusMm = std::isfinite(knownWithinMm) ? knownWithinMm : std::numeric_limits<double>::max();
  const QueryState state = FindNearestTriangle(
    this->Impl->Trees.at(c), *this->Surfaces.at(c), point, radiusMm, std::max(0.0, toleranceMm), start);
  const double best = std::sqrt(state.Best2);
  if (wallPoint)
  {
    std::copy(state.Closest, state.Closest + 3, wallPoint);
  }
  return state.Triangle >= 0 && best <= radiusMm ? best : std::numeric_limits<double>::infinity();
}

bool vtkExactVesselDistance::VoteInside(int classIndex, const double point[3], double distanceMm, bool& uncertain) const
{
  this->EnsureBuilt();
  return VoteInsideTree(this->Impl->Trees.at(static_cast<std::size_t>(classIndex)), point, distanceMm, uncertain);
}

const vp::InsideVoteField* vtkExactVesselDistance::GetVoteField(int classIndex) const
{
  this->EnsureBuilt();
  return this->Impl->Trees.at(static_cast<std::size_t>(classIndex)).VoteField.get();
}

void vtkExactVesselDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VoteOnOpenSurfaces: " << (this->VoteOnOpenSurfaces ? "On" : "Off") << "\n";
  os << indent << "VoteFieldCellMm: " << this->VoteFieldCellMm << (this->VoteFieldCellMm > 0.0 ? "" : " (off)") << "\n";
  os << indent << "Trees: " << this->Impl->Trees.size() << " (Embree BVH, point queries)\n";
}
