#include "vpReplayBenchmark.h"

#include "vpClock.h"
#include "vpExactComparison.h"
#include "vpQuantile.h"
#include "vpRigidTransform.h"
#include "vpTrackingSession.h"
#include "vtkExactVesselDistance.h"
#include "vtkFclSurfaceDistance.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelPenetration.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"
#include "vtkZBufferSurfaceDistance.h"

#include <vtkNew.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

namespace vp
{
namespace
{
using Json = BenchJson;

/// A surgeon's path: straight 0.5 mm steps between waypoints that lie 1 to 15 mm off random
/// vessel surface points, so the tip keeps approaching and leaving vessels, as in a resection.
std::vector<std::array<double, 3>> PathNearVessels(const std::vector<NamedMesh>& vessels, std::size_t frames, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(1.0, 15.0);
  auto waypoint = [&]() {
    const NamedMesh& v = vessels[std::uniform_int_distribution<std::size_t>(0, vessels.size() - 1)(random)];
    double p[3];
    v.Mesh->GetPoint(std::uniform_int_distribution<vtkIdType>(0, v.Mesh->GetNumberOfPoints() - 1)(random), p);
    double d[3] = { normal(random), normal(random), normal(random) };
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double r = offset(random);
    return std::array<double, 3>{ p[0] + r * d[0] / n, p[1] + r * d[1] / n, p[2] + r * d[2] / n };
  };
  std::vector<std::array<double, 3>> path{ waypoint() };
  while (path.size() < frames)
  {
    const auto from = path.back();
    const auto to = waypoint();
    const double length = std::sqrt((to[0] - from[0]) * (to[0] - from[0]) + (to[1] - from[1]) * (to[1] - from[1]) +
      (to[2] - from[2]) * (to[2] - from[2]));
    const int steps = std::max(1, static_cast<int>(length / 0.5));
    for (int k = 1; k <= steps && path.size() < frames; ++k)
    {
      const double t = static_cast<double>(k) / steps;
      path.push_back({ from[0] + t * (to[0] - from[0]), from[1] + t * (to[1] - from[1]), from[2] + t * (to[2] - from[2]) });
    }
  }
  return path;
}

std::vector<TrackedPose> PosesAlong(const std::vector<std::array<double, 3>>& path, vtkScalpelModel* scalpel)
{
  std::vector<TrackedPose> poses;
  const double* tip = scalpel->GetTipMm();
  for (std::size_t i = 0; i < path.size(); ++i)
  {
    Matrix4 m = RotationAboutAxis({ 1.0, 1.0, 0.3 }, 0.2 * M_PI / 180.0 * static_cast<double>(i), { 0, 0, 0 });
    const Point3 turned = TransformPoint(m, { tip[0], tip[1], tip[2] });
    for (int a = 0; a < 3; ++a)
    {
      m[4 * a + 3] = path[i][a] - turned[a];
    }
    poses.push_back({ 0.02 * static_cast<double>(i), m }); // 50 Hz, a tracker's rate
  }
  return poses;
}

} // namespace

std::vector<TrackedPose> PosesNearVessels(const std::vector<NamedMesh>& vessels, std::size_t frames, unsigned seed, vtkScalpelModel* scalpel)
{
  return PosesAlong(PathNearVessels(vessels, frames, seed), scalpel);
}

namespace
{
struct Replay
{
  double FramesPerSecond = 0.0;
  std::vector<double> FrameMs;
  std::vector<TrackedFrame> Frames;
};

/// What every replay opens: the bench's vessels and scalpel, the engine and the instrument as the
/// replay asks (tip only unless it says otherwise).
struct ReplayScene
{
  const std::vector<NamedMesh>& Vessels;
  vtkScalpelModel* Scalpel;
};

/// The module's logic over the scene, opened from the request adjust makes of the tip-only one:
/// each replay measures the module as it tracks, its engines built once before the frames.
vtkSmartPointer<vtkVesselProximityLogic> OpenReplay(const ReplayScene& scene, const std::function<void(SceneRequest&)>& adjust = {})
{
  SceneRequest request;
  request.Vessels = scene.Vessels;
  request.Scalpel = scene.Scalpel;
  request.ComputeSurfaceDistance = false;
  if (adjust)
  {
    adjust(request);
  }
  vtkSmartPointer<vtkVesselProximityLogic> logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  logic->OpenScene(request);
  return logic;
}

/// The first count poses through a tracking session on the logic. afterEach (may be empty) runs
/// after each frame, outside its time.
Replay Run(vtkVesselProximityLogic* logic, const std::vector<TrackedPose>& poses, std::size_t count,
  const std::function<void()>& afterEach = {})
{
  Replay replay;
  const std::vector<TrackedPose> first(poses.begin(), poses.begin() + static_cast<std::ptrdiff_t>(std::min(count, poses.size())));
  PoseListSource source(first, "the replay's poses");
  TrackingSession session(logic);
  const double start = NowMs();
  session.Run(source, [&](const TrackedFrame& frame) {
    replay.Frames.push_back(frame);
    if (afterEach)
    {
      afterEach();
    }
  });
  const double elapsedMs = NowMs() - start;
  replay.FramesPerSecond = 1000.0 * static_cast<double>(first.size()) / std::max(1e-9, elapsedMs);
  for (const auto& f : replay.Frames)
  {
    replay.FrameMs.push_back(f.FrameMs);
  }
  return replay;
}

Json Entry(const Replay& r)
{
  int inRange = 0;
  for (const auto& f : r.Frames)
  {
    inRange += f.Proximity.NearestIndex() >= 0 ? 1 : 0;
  }
  return { { "frames", r.Frames.size() }, { "frames_with_a_class_in_range", inRange }, { "frames_per_second", r.FramesPerSecond },
    { "frame_median_ms", Quantile(r.FrameMs, 0.5) }, { "frame_p95_ms", Quantile(r.FrameMs, 0.95) } };
}


/// Plain FCL (no warm start: as MoveIt or Drake would call it) on every pose, timed per frame.
Replay PlainFcl(vtkExactVesselDistance* exact, vtkScalpelModel* scalpel, const std::vector<TrackedPose>& poses)
{
  vtkNew<vtkFclSurfaceDistance> fcl;
  fcl->SetVesselDistance(exact);
  fcl->SetToolSurface(scalpel->GetModel());
  fcl->WarmStartOff();
  fcl->Build();
  Replay replay;
  const double start = NowMs();
  for (const TrackedPose& pose : poses)
  {
    const double t0 = NowMs();
    TrackedFrame frame;
    fcl->ComputeSurfaceProximity(pose.ModelToWorld, frame.Surface);
    frame.FrameMs = NowMs() - t0;
    replay.FrameMs.push_back(frame.FrameMs);
    replay.Frames.push_back(std::move(frame));
  }
  replay.FramesPerSecond = 1000.0 * static_cast<double>(poses.size()) / std::max(1e-9, NowMs() - start);
  return replay;
}

/// The largest difference between two replays' whole-surface distances, whether each answer of a
/// lies within its own bound of b's (exact answers have bound 0), the answers of a farther than b's
/// (an approximate answer may overstate proximity, never understate it), the largest bound where
/// b is within 5 mm (where danger is decided), and the answers where one is in range and the
/// other not.
Json CompareSurfaces(const Replay& a, const Replay& b)
{
  double largest = 0.0, largestBound = 0.0, largestNearBound = 0.0;
  int outside = 0, farther = 0, disagreements = 0;
  for (std::size_t i = 0; i < std::min(a.Frames.size(), b.Frames.size()); ++i)
  {
    for (std::size_t c = 0; c < std::min(a.Frames[i].Surface.size(), b.Frames[i].Surface.size()); ++c)
    {
      const SurfaceProximity& x = a.Frames[i].Surface[c];
      const SurfaceProximity& y = b.Frames[i].Surface[c];
      if (x.InRange != y.InRange)
      {
        ++disagreements;
      }
      else if (x.InRange)
      {
        const double diff = std::abs(x.DistanceMm - y.DistanceMm);
        largest = std::max(largest, diff);
        largestBound = std::max(largestBound, x.ErrorBoundMm);
        outside += diff > x.ErrorBoundMm + 1e-9 ? 1 : 0;
        farther += x.DistanceMm > y.DistanceMm + 1e-9 ? 1 : 0;
        if (y.DistanceMm < 5.0)
        {
          largestNearBound = std::max(largestNearBound, x.ErrorBoundMm);
        }
      }
    }
  }
  return { { "max_abs_diff_mm", largest }, { "max_error_bound_mm", largestBound },
    { "max_error_bound_within_5mm", largestNearBound }, { "outside_bound", outside }, { "farther_than_reference", farther },
    { "in_range_disagreements", disagreements } };
}
/// Two replays' penetrations: the largest depth and volume differences, and the answers of a
/// whose difference from b's exceeds the two bounds together.
Json ComparePenetrations(const Replay& a, const Replay& b)
{
  double depth = 0.0, volume = 0.0;
  int outside = 0, overlapping = 0;
  for (std::size_t i = 0; i < std::min(a.Frames.size(), b.Frames.size()); ++i)
  {
    for (std::size_t c = 0; c < std::min(a.Frames[i].Penetrations.size(), b.Frames[i].Penetrations.size()); ++c)
    {
      const Penetration& x = a.Frames[i].Penetrations[c];
      const Penetration& y = b.Frames[i].Penetrations[c];
      if (!x.Known || !y.Known)
      {
        continue;
      }
      overlapping += y.VolumeMm3 > 0.0 ? 1 : 0;
      depth = std::max(depth, std::abs(x.DepthMm - y.DepthMm));
      volume = std::max(volume, std::abs(x.VolumeMm3 - y.VolumeMm3));
      outside += std::abs(x.DepthMm - y.DepthMm) > x.DepthBoundMm + y.DepthBoundMm + 1e-9 ||
          std::abs(x.VolumeMm3 - y.VolumeMm3) > x.VolumeBoundMm3 + y.VolumeBoundMm3 + 1e-9
        ? 1
        : 0;
    }
  }
  return { { "answers_with_exact_overlap", overlapping }, { "max_depth_diff_mm", depth }, { "max_volume_diff_mm3", volume },
    { "outside_bounds", outside } };
}

/// The z-buffer's full frame: tip, whole instrument and penetration, all from its layers.
void ReplayZBufferFullFrame(const ReplayScene& scene, const DistanceEngineSettings& settings, const std::vector<TrackedPose>& poses,
  const Replay& whole, Json& out)
{
  std::fprintf(stderr, ", z-buffer full frame");
  vtkSmartPointer<vtkVesselProximityLogic> logic = OpenReplay(scene, [&](SceneRequest& r) {
    r.Engine = settings;
    r.ComputeSurfaceDistance = true;
  });
  const Replay zfull = Run(logic, poses, poses.size());
  Json f = Entry(zfull);
  f["includes"] = "tip, whole-instrument distance, penetration depth and volume, all from the z-buffer's layers";
  f["vs_exact_penetration"] = ComparePenetrations(zfull, whole);
  out["zbuffer_full_frame"] = f;
}

/// The z-buffer engine's own tip answers over the same frames, against the exact ones.
void ReplayZBufferTip(const ReplayScene& scene, const DistanceEngineSettings& settings, const std::vector<TrackedPose>& poses,
  const Replay& tip, Json& out)
{
  std::fprintf(stderr, ", z-buffer (render");
  const double renderStart = NowMs();
  vtkSmartPointer<vtkVesselProximityLogic> logic = OpenReplay(scene, [&](SceneRequest& r) { r.Engine = settings; });
  const double renderMs = NowMs() - renderStart; // the build, the layers' rendering and the query ceilings
  vtkVesselDistanceEngine* zbuffer = logic->GetDistanceEngine();
  std::fprintf(stderr, ", frames)");
  const Replay cached = Run(logic, poses, poses.size());
  ExactComparison check;
  for (std::size_t i = 0; i < cached.Frames.size(); ++i)
  {
    check.Add(cached.Frames[i].Proximity, tip.Frames[i].Proximity, zbuffer->GetRangeMm(), zbuffer->GetErrorBoundMm());
  }
  Json z = Entry(cached);
  z["device"] = zbuffer->GetDeviceDescription();
  z["build_and_render_ms"] = renderMs;
  z["error_bound_mm"] = zbuffer->GetErrorBoundMm();
  z["max_abs_diff_vs_exact_mm"] = check.MaxAbsDifferenceMm;
  z["outside_bound"] = check.OutsideBound;
  out["zbuffer_cached"] = z;
}

/// The whole instrument on the z-buffer's layers (no penetration), then the full frame.
void ReplayZBufferInstrument(const ReplayScene& scene, const DistanceEngineSettings& settings, const std::vector<TrackedPose>& poses,
  const Replay& whole, Json& out)
{
  std::fprintf(stderr, ", z-buffer whole instrument");
  vtkSmartPointer<vtkVesselProximityLogic> logic = OpenReplay(scene, [&](SceneRequest& r) {
    r.Engine = settings;
    r.ComputeSurfaceDistance = true;
    r.ComputePenetration = false;
  });
  auto* zsurface = vtkZBufferSurfaceDistance::SafeDownCast(logic->GetTrackingLogic()->GetSurfaceDistance());
  if (!zsurface)
  {
    return; // a moving box: the module measures the instrument with FCL, measured above
  }
  std::vector<double> evaluated, submissions;
  const Replay zwhole = Run(logic, poses, poses.size(), [&]() {
    evaluated.push_back(static_cast<double>(zsurface->GetLastEvaluatedSamples()));
    submissions.push_back(static_cast<double>(zsurface->GetLastSubmissions()));
  });
  Json w = Entry(zwhole);
  w["includes"] = "tip and whole-instrument distance on the z-buffer's layers (no penetration)";
  w["build_ms"] = zsurface->GetBuildTimeMs();
  w["tool_samples"] = zsurface->GetNumberOfSamples();
  w["error_bound_mm"] = zsurface->GetErrorBoundMm();
  w["field_memory_mb"] = static_cast<double>(zsurface->GetFieldMemoryBytes()) / (1024.0 * 1024.0);
  w["field_layer_cells_per_cell"] = zsurface->GetFieldLayerCellsPerCell();
  w["samples_evaluated_median"] = Quantile(evaluated, 0.5);
  w["samples_evaluated_p95"] = Quantile(evaluated, 0.95);
  w["submissions_median"] = Quantile(submissions, 0.5);
  w["submissions_p95"] = Quantile(submissions, 0.95);
  w["vs_exact_tip_and_surface"] = CompareSurfaces(zwhole, whole);
  out["zbuffer_tip_and_surface"] = w;
  ReplayZBufferFullFrame(scene, settings, poses, whole, out);
}

/// The exact pipeline's replays: the tip alone; tip, whole instrument (FCL, warm start) and
/// penetration; plain FCL as MoveIt or Drake would call it; bounding spheres; the whole instrument
/// within the caution distance; and the brute-force tip on the first frames.
struct ExactReplays
{
  Replay Tip, Whole, Plain, Spheres, Near, Slow;
  Json Sizes; ///< triangle counts and build times, for the report
  double SurfaceRangeMm = 0.0;
  double RangeMm = 0.0;
};

/// The module's whole instrument with the method and range given, no penetration.
Replay ReplayInstrument(const ReplayScene& scene, InstrumentMethod method, double rangeMm, const std::vector<TrackedPose>& poses,
  vtkSmartPointer<vtkVesselProximityLogic>& logic)
{
  logic = OpenReplay(scene, [&](SceneRequest& r) {
    r.ComputeSurfaceDistance = true;
    r.Instrument = method;
    r.InstrumentRangeMm = rangeMm;
    r.ComputePenetration = false;
  });
  return Run(logic, poses, poses.size());
}

ExactReplays RunExactReplays(const ReplayScene& scene, const std::vector<TrackedPose>& poses, int bruteFrames)
{
  ExactReplays r;
  vtkSmartPointer<vtkVesselProximityLogic> tip = OpenReplay(scene);
  r.RangeMm = tip->GetDistanceEngine()->GetRangeMm();
  r.Tip = Run(tip, poses, poses.size());
  std::fprintf(stderr, ", whole surface (FCL, warm start)");
  vtkSmartPointer<vtkVesselProximityLogic> whole = OpenReplay(scene, [](SceneRequest& req) { req.ComputeSurfaceDistance = true; });
  r.Whole = Run(whole, poses, poses.size());
  vtkScalpelSurfaceDistance* surface = whole->GetTrackingLogic()->GetSurfaceDistance();
  std::fprintf(stderr, ", plain FCL");
  r.Plain = PlainFcl(tip->GetExactDistance(), scene.Scalpel, poses);
  std::fprintf(stderr, ", bounding spheres");
  vtkSmartPointer<vtkVesselProximityLogic> spheres;
  r.Spheres = ReplayInstrument(scene, InstrumentMethod::BoundingSpheres, 0.0, poses, spheres);
  std::fprintf(stderr, ", whole surface within the caution distance");
  vtkSmartPointer<vtkVesselProximityLogic> near;
  r.Near = ReplayInstrument(scene, InstrumentMethod::Fcl, tip->GetDangerThresholds().CautionMm, poses, near);
  r.SurfaceRangeMm = near->GetTrackingLogic()->GetSurfaceDistance()->GetRangeMm();
  std::fprintf(stderr, ", brute force");
  vtkSmartPointer<vtkVesselProximityLogic> brute = OpenReplay(scene, [](SceneRequest& req) { req.Engine.Method = "brute"; });
  r.Slow = Run(brute, poses, static_cast<std::size_t>(bruteFrames));
  r.Sizes = { { "tool_triangles", surface->GetNumberOfToolTriangles() },
    { "tool_triangles_split_for_spheres", spheres->GetTrackingLogic()->GetSurfaceDistance()->GetNumberOfToolTriangles() },
    { "surface_build_ms", vtkFclSurfaceDistance::SafeDownCast(surface)->GetBuildTimeMs() },
    { "penetration_build_ms", whole->GetTrackingLogic()->GetPenetration()->GetBuildTimeMs() } };
  return r;
}

void AddExactReplays(const ExactReplays& r, Json& out)
{
  out["tool_triangles"] = r.Sizes["tool_triangles"];
  out["tool_triangles_split_for_spheres"] = r.Sizes["tool_triangles_split_for_spheres"];
  out["exact_tip"] = Entry(r.Tip);
  out["exact_tip_and_surface"] = Entry(r.Whole);
  out["exact_tip_and_surface"]["surface_build_ms"] = r.Sizes["surface_build_ms"];
  out["exact_tip_and_surface"]["penetration_build_ms"] = r.Sizes["penetration_build_ms"];
  out["exact_tip_and_surface"]["includes"] = "tip, whole-instrument distance (FCL, warm start), penetration depth and volume";
  out["fcl_surface"] = Entry(r.Plain);
  out["fcl_surface"]["vs_exact_tip_and_surface"] = CompareSurfaces(r.Plain, r.Whole);
  out["spheres_tip_and_surface"] = Entry(r.Spheres);
  out["spheres_tip_and_surface"]["vs_exact_tip_and_surface"] = CompareSurfaces(r.Spheres, r.Whole);
  out["exact_tip_and_surface_within_caution"] = Entry(r.Near);
  out["surface_within_caution_mm"] = r.SurfaceRangeMm;
  out["brute_tip"] = Entry(r.Slow);
  ExactComparison bruteCheck;
  for (std::size_t i = 0; i < r.Slow.Frames.size(); ++i)
  {
    bruteCheck.Add(r.Slow.Frames[i].Proximity, r.Tip.Frames[i].Proximity, r.RangeMm, 0.0);
  }
  out["max_abs_diff_exact_vs_brute_mm"] = bruteCheck.MaxAbsDifferenceMm;
}
} // namespace

Json BenchReplay(const std::vector<NamedMesh>& vessels, std::size_t frames, unsigned seed, vtkScalpelModel* scalpel,
  const DistanceEngineSettings* zbuffer, int bruteFrames, const std::vector<TrackedPose>& givenPoses)
{
  const std::vector<std::array<double, 3>> path =
    givenPoses.empty() ? PathNearVessels(vessels, frames, seed) : std::vector<std::array<double, 3>>();
  const std::vector<TrackedPose> poses = givenPoses.empty() ? PosesAlong(path, scalpel) : givenPoses;
  std::size_t triangles = 0;
  for (const auto& v : vessels)
  {
    triangles += static_cast<std::size_t>(v.Mesh->GetNumberOfPolys());
  }
  std::fprintf(stderr, "bench: replay of %zu poses, %zu classes, %zu triangles: exact", poses.size(), vessels.size(), triangles);
  const ReplayScene scene{ vessels, scalpel };
  const ExactReplays replays = RunExactReplays(scene, poses, bruteFrames);
  Json out;
  out["poses"] = poses.size();
  out["classes"] = vessels.size();
  out["triangles"] = triangles;
  AddExactReplays(replays, out);
  if (zbuffer)
  {
    ReplayZBufferTip(scene, *zbuffer, poses, replays.Tip, out);
    ReplayZBufferInstrument(scene, *zbuffer, poses, replays.Whole, out);
  }
  std::fprintf(stderr, "\n");
  return out;
}
} // namespace vp
