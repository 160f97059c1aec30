#include "vpBreachBenchmark.h"

#include "vpClock.h"
#include "vpDefaultScalpel.h"
#include "vpInputError.h"
#include "vpQuantile.h"
#include "vpSceneRequest.h"
#include "vpTrackingSession.h"
#include "vtkExactVesselDistance.h"
#include "vtkFclSurfaceDistance.h"
#include "vtkScalpelPenetration.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselProximityLogic.h"
#include "vpVec3.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace vp
{
namespace
{
using Json = BenchJson;
using namespace vec3;
using Vec = Vec3;

/// The overlap bands of the report (mm³ of instrument inside the vessels, all classes): [low, high).
const std::array<std::array<double, 2>, 3> Bands = { { { 0.0, 100.0 }, { 100.0, 1000.0 }, { 1000.0, 1e300 } } };

/// A surface point and its outward unit normal.
struct SurfacePoint
{
  Vec Point;
  Vec Outward;
};

/// count triangle centres of the mesh, picked by area, with their outward normals (the mesh's
/// winding, turned over when its signed volume says it winds inward).
std::vector<SurfacePoint> PickSurfacePoints(vtkPolyData* mesh, int count, std::mt19937& random)
{
  std::vector<SurfacePoint> triangles;
  std::vector<double> areas;
  double signedVolume = 0.0;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    if (n != 3)
    {
      continue;
    }
    Vec p[3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids[k], p[k].data());
    }
    const Vec normal = Cross(p[1] - p[0], p[2] - p[0]);
    const double twiceArea = Norm(normal);
    signedVolume += Dot(p[0], Cross(p[1], p[2])) / 6.0;
    if (twiceArea <= 0.0)
    {
      continue;
    }
    triangles.push_back({ (1.0 / 3.0) * (p[0] + p[1] + p[2]), (1.0 / twiceArea) * normal });
    areas.push_back(twiceArea);
  }
  std::vector<SurfacePoint> picked;
  if (triangles.empty())
  {
    return picked;
  }
  std::discrete_distribution<std::size_t> byArea(areas.begin(), areas.end());
  const double side = signedVolume < 0.0 ? -1.0 : 1.0;
  for (int i = 0; i < count; ++i)
  {
    const SurfacePoint& t = triangles[byArea(random)];
    picked.push_back({ t.Point, side * t.Outward });
  }
  return picked;
}

/// The pose that puts the instrument's tip at target with its axis along direction (unit): the
/// least rotation taking the model's axis to it (vec3::Rotate about their common normal), then the
/// translation that lands the tip.
std::array<double, 16> PoseAt(const Vec& target, const Vec& direction, const double tip[3], const double axis[3])
{
  const Vec a = Normalized({ axis[0], axis[1], axis[2] });
  const Vec normal = Cross(a, direction);
  const Vec about = Norm(normal) > 1e-12 ? Normalized(normal) : PerpendicularTo(a, { 1, 0, 0 });
  const double angle = std::atan2(Norm(normal), Dot(a, direction));
  std::array<double, 16> pose{};
  for (int j = 0; j < 3; ++j)
  {
    const Vec column = Rotate({ j == 0 ? 1.0 : 0.0, j == 1 ? 1.0 : 0.0, j == 2 ? 1.0 : 0.0 }, about, angle);
    for (int i = 0; i < 3; ++i)
    {
      pose[4 * i + j] = column[i];
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    pose[4 * i + 3] = target[i] - (pose[4 * i] * tip[0] + pose[4 * i + 1] * tip[1] + pose[4 * i + 2] * tip[2]);
  }
  pose[15] = 1.0;
  return pose;
}

} // namespace

std::vector<TrackedPose> BreachPoses(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const BreachBenchSettings& s)
{
  std::mt19937 random(s.Seed);
  std::vector<TrackedPose> poses;
  for (const NamedMesh& v : vessels)
  {
    const std::vector<SurfacePoint> points = PickSurfacePoints(v.Mesh, s.PointsPerClass, random);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const SurfacePoint& p = points[i];
      const Vec inward = -1.0 * p.Outward;
      const double push = s.MaxPushMm * static_cast<double>(i + 1) / static_cast<double>(points.size());
      for (double depth : { -2.0, push, 0.5 * push })
      {
        TrackedPose pose;
        pose.TimeS = 0.05 * static_cast<double>(poses.size());
        const Vec target = p.Point + depth * inward;
        pose.ModelToWorld = PoseAt(target, inward, scalpel->GetTipMm(), scalpel->GetAxis());
        poses.push_back(pose);
      }
    }
  }
  return poses;
}

namespace
{
/// One engine's frames: time and what it answered of the whole instrument.
struct Run
{
  std::vector<double> FrameMs, TipMs, SurfaceMs, PenetrationMs;
  std::vector<std::vector<Penetration>> Answers;
};

vtkSmartPointer<vtkVesselProximityLogic> OpenBreachScene(
  const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const DistanceEngineSettings& engine, long long budget)
{
  SceneRequest request;
  request.PenetrationQueryBudget = budget;
  request.Vessels = vessels;
  request.Scalpel = scalpel;
  request.Engine = engine;
  request.ComputeSurfaceDistance = true;
  request.ComputePenetration = true;
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  logic->OpenScene(request);
  return logic;
}

Run RunFrames(vtkVesselProximityLogic* logic, const std::vector<TrackedPose>& poses)
{
  TrackingSession session(logic);
  Run run;
  for (const TrackedPose& pose : poses)
  {
    const TrackedFrame& frame = session.Process(pose);
    run.FrameMs.push_back(frame.FrameMs);
    run.TipMs.push_back(frame.PartsMs.TipMs);
    run.SurfaceMs.push_back(frame.PartsMs.SurfaceMs);
    run.PenetrationMs.push_back(frame.PartsMs.PenetrationMs);
    run.Answers.push_back(frame.Penetrations);
  }
  return run;
}

/// The anchor and the reference on the same poses: FCL's whole-instrument distance (warm-started,
/// as the module runs it), timed; then, from its answers, the penetration walked without a budget
/// on a fine lattice.
struct Reference
{
  std::vector<double> FclMs;
  std::vector<std::vector<Penetration>> Answers;
  double BuildMs = 0.0;
};

Reference MeasureReference(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel,
  const std::vector<TrackedPose>& poses, double cellMm)
{
  vtkNew<vtkExactVesselDistance> exact;
  for (const NamedMesh& v : vessels)
  {
    exact->AddVessel(v.ClassName, v.Mesh);
  }
  exact->Build();
  vtkNew<vtkFclSurfaceDistance> fcl;
  fcl->SetVesselDistance(exact);
  fcl->SetToolSurface(scalpel->GetModel());
  fcl->Build();
  vtkNew<vtkScalpelPenetration> fine;
  fine->SetVesselDistance(exact);
  fine->SetToolSurface(scalpel->GetModel());
  fine->SetCellSizeMm(cellMm);
  fine->SetQueryBudget(0);
  fine->Build();
  Reference ref;
  ref.BuildMs = fine->GetBuildTimeMs();
  std::vector<SurfaceProximity> surface, previous;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const double start = NowMs();
    fcl->ComputeSurfaceProximity(poses[i].ModelToWorld, surface, i > 0 ? &previous : nullptr);
    ref.FclMs.push_back(NowMs() - start);
    ref.Answers.emplace_back();
    fine->ComputePenetration(poses[i].ModelToWorld, surface, ref.Answers.back());
    previous = surface;
    if (i % 60 == 59)
    {
      std::fprintf(stderr, ".");
    }
  }
  return ref;
}

double TotalVolume(const std::vector<Penetration>& answers)
{
  double v = 0.0;
  for (const Penetration& p : answers)
  {
    v += p.Known ? p.VolumeMm3 : 0.0;
  }
  return v;
}

/// Per frame, all classes together: time, volume and its bound, the reference's volume, the
/// deepest class's depth and bound, the reference's depth.
Json PerPose(const Run& run, const Reference& ref)
{
  Json rows = Json::array();
  for (std::size_t f = 0; f < run.FrameMs.size(); ++f)
  {
    double volume = 0, volumeBound = 0, depth = 0, depthBound = 0, refDepth = 0;
    for (const Penetration& p : run.Answers[f])
    {
      volume += p.VolumeMm3;
      volumeBound += p.VolumeBoundMm3;
      if (p.DepthMm >= depth)
      {
        depth = p.DepthMm;
        depthBound = p.DepthBoundMm;
      }
    }
    for (const Penetration& p : ref.Answers[f])
    {
      refDepth = std::max(refDepth, p.DepthMm);
    }
    rows.push_back({ run.FrameMs[f], run.PenetrationMs[f], volume, volumeBound, TotalVolume(ref.Answers[f]), depth, depthBound, refDepth });
  }
  return rows;
}

/// An engine's frames against the reference: timings over the run, its penetrating frames and
/// each overlap band, and its volume and depth errors.
Json Compare(const Run& run, const Reference& ref)
{
  Json out;
  out["frame_ms"] = Timing(run.FrameMs);
  out["parts_ms"] = { { "tip", Timing(run.TipMs) }, { "surface", Timing(run.SurfaceMs) },
    { "penetration", Timing(run.PenetrationMs) } };
  std::vector<double> penetrating;
  std::array<std::vector<double>, Bands.size()> bands;
  double maxVolumeError = 0.0, maxRelative = 0.0, maxDepthError = 0.0, maxVolumeBound = 0.0, maxDepthBound = 0.0;
  int outsideContract = 0, belowTruth = 0, unknown = 0;
  for (std::size_t f = 0; f < run.FrameMs.size(); ++f)
  {
    const double overlap = TotalVolume(ref.Answers[f]);
    if (overlap > 0.0)
    {
      penetrating.push_back(run.FrameMs[f]);
      for (std::size_t b = 0; b < Bands.size(); ++b)
      {
        if (overlap >= Bands[b][0] && overlap < Bands[b][1])
        {
          bands[b].push_back(run.FrameMs[f]);
        }
      }
    }
    for (std::size_t c = 0; c < ref.Answers[f].size() && c < run.Answers[f].size(); ++c)
    {
      const Penetration& a = run.Answers[f][c];
      const Penetration& r = ref.Answers[f][c];
      if (!a.Known || !r.Known)
      {
        unknown += a.Known != r.Known ? 1 : 0;
        continue;
      }
      const double volumeError = a.VolumeMm3 - r.VolumeMm3;
      const double depthError = a.DepthMm - r.DepthMm;
      maxVolumeError = std::max(maxVolumeError, std::abs(volumeError));
      maxDepthError = std::max(maxDepthError, std::abs(depthError));
      maxVolumeBound = std::max(maxVolumeBound, a.VolumeBoundMm3);
      maxDepthBound = std::max(maxDepthBound, a.DepthBoundMm);
      if (r.DepthMm >= 1.0)
      {
        maxRelative = std::max(maxRelative, std::abs(volumeError) / r.VolumeMm3);
        // The contract: within 10 % or 0.5 mm³ from 1 mm deep.
        outsideContract += std::abs(volumeError) > std::max(0.1 * r.VolumeMm3, 0.5) ? 1 : 0;
            }
      // Danger understated: less than the truth by more than both stated bounds.
      belowTruth += volumeError < -(a.VolumeBoundMm3 + r.VolumeBoundMm3) || depthError < -(a.DepthBoundMm + r.DepthBoundMm) ? 1 : 0;
    }
  }
  out["penetrating_frame_ms"] = Timing(penetrating);
  Json byBand = Json::array();
  for (std::size_t b = 0; b < Bands.size(); ++b)
  {
    Json j = Timing(bands[b]);
    j["overlap_from_mm3"] = Bands[b][0];
    j["overlap_to_mm3"] = Bands[b][1] < 1e300 ? Json(Bands[b][1]) : Json(nullptr);
    byBand.push_back(j);
  }
  out["bands"] = byBand;
  out["max_volume_error_mm3"] = maxVolumeError;
  out["max_volume_error_relative_from_1mm"] = maxRelative;
  out["max_depth_error_mm"] = maxDepthError;
  out["max_volume_bound_mm3"] = maxVolumeBound;
  out["max_depth_bound_mm"] = maxDepthBound;
  out["per_pose_columns"] = { "frame_ms", "penetration_ms", "volume_mm3", "volume_bound_mm3", "reference_volume_mm3",
    "depth_mm", "depth_bound_mm", "reference_depth_mm" };
  out["per_pose"] = PerPose(run, ref);
  out["answers_outside_contract"] = outsideContract;
  out["answers_below_truth_beyond_bounds"] = belowTruth;
  out["answers_known_differently"] = unknown;
  return out;
}
} // namespace

BenchJson BenchBreach(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const BreachBenchSettings& settings,
  const DistanceEngineSettings* zbuffer)
{
  DistanceEngineSettings exactSettings;
  exactSettings.Method = "exact";
  std::fprintf(stderr, "bench: breach, opening the scene");
  vtkSmartPointer<vtkScalpelModel> tool = scalpel ? vtkSmartPointer<vtkScalpelModel>(scalpel) : MakeDefaultScalpel();
  vtkSmartPointer<vtkVesselProximityLogic> exact = OpenBreachScene(vessels, tool, exactSettings, settings.QueryBudget);
  const std::vector<TrackedPose> poses = BreachPoses(vessels, tool, settings);
  Json out;
  out["scene"] = "the instrument pushed along the inward normal at surface points of each class (picked by area): "
                 "2 mm outside, pushed in, withdrawn half way; every frame through the logic (tip, whole instrument, "
                 "penetration)";
  out["poses"] = poses.size();
  out["points_per_class"] = settings.PointsPerClass;
  out["max_push_mm"] = settings.MaxPushMm;
  out["reference_cell_mm"] = settings.ReferenceCellMm;
  long long triangles = 0;
  for (const NamedMesh& v : vessels)
  {
    triangles += v.Mesh->GetNumberOfPolys();
  }
  out["vessel_triangles"] = triangles;
  std::fprintf(stderr, ", exact");
  const Run exactRun = RunFrames(exact, poses);
  Run zbufferRun;
  std::string zbufferUnavailable;
  std::string zbufferDevice;
  if (zbuffer)
  {
    std::fprintf(stderr, ", z-buffer");
    try
    {
      vtkSmartPointer<vtkVesselProximityLogic> logic = OpenBreachScene(vessels, tool, *zbuffer, settings.QueryBudget);
      zbufferDevice = logic->GetDistanceEngine()->GetDeviceDescription();
      zbufferRun = RunFrames(logic, poses);
    }
    catch (const DeviceError& e)
    {
      zbufferUnavailable = e.what();
    }
  }
  std::fprintf(stderr, ", exact without a budget");
  const Run unbudgeted = RunFrames(OpenBreachScene(vessels, tool, exactSettings, 0), poses);
  std::fprintf(stderr, ", FCL and the fine reference");
  const Reference ref = MeasureReference(vessels, tool, poses, settings.ReferenceCellMm);
  std::fprintf(stderr, "\n");
  out["query_budget"] = settings.QueryBudget;
  out["exact"] = Compare(exactRun, ref);
  out["exact_without_budget"] = Compare(unbudgeted, ref);
  if (zbuffer)
  {
    out["zbuffer"] = zbufferUnavailable.empty() ? Compare(zbufferRun, ref) : Json{ { "unavailable", zbufferUnavailable } };
    out["zbuffer"]["device"] = zbufferDevice;
  }
  Json fcl = Timing(ref.FclMs);
  fcl["what"] = "vtkFclSurfaceDistance (FCL, warm-started): the whole instrument's distance only, no penetration";
  out["fcl_surface"] = fcl;
  double largest = 0.0;
  int penetrating = 0;
  for (const auto& answers : ref.Answers)
  {
    largest = std::max(largest, TotalVolume(answers));
    penetrating += TotalVolume(answers) > 0.0 ? 1 : 0;
  }
  out["penetrating_poses"] = penetrating;
  out["largest_overlap_mm3"] = largest;
  return out;
}
} // namespace vp
