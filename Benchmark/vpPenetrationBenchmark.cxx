#include "vpPenetrationBenchmark.h"

#include "vpAnalyticShapes.h"
#include "vpClock.h"
#include "vpInputError.h"
#include "vpQuantile.h"
#include "vpSceneRequest.h"
#include "vpTrackingSession.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"

#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace vp
{
namespace
{
using Json = BenchJson;

const double ToolRadiusMm = 1.5;
const double ToolLengthMm = 40.0;
const double VesselRadiusMm = 10.0;

/// The depth bands the report is split into, mm: [low, high).
const std::array<std::array<double, 2>, 4> Bands = { { { 0.0, 1.0 }, { 1.0, 3.0 }, { 3.0, 6.0 }, { 6.0, 10.0001 } } };

/// Volume of the upright tool (tip face at height tip <= 0, on the sphere's axis) inside the
/// sphere: the columns' closed-form overlap, integrated over the radius by a fine midpoint rule
/// (the shapes' own integral, not a sampling of their meshes; about the axis it is symmetric).
double OverlapVolumeMm3(double tip)
{
  const int radial = 20000;
  double volume = 0.0;
  for (int i = 0; i < radial; ++i)
  {
    const double rho = (i + 0.5) * ToolRadiusMm / radial;
    const double h2 = VesselRadiusMm * VesselRadiusMm - rho * rho;
    if (h2 <= 0)
    {
      continue;
    }
    const double h = std::sqrt(h2);
    // The tool reaches far below the sphere (tip - 40 < -10): its column inside is [-h, min(tip, h)].
    const double length = std::max(0.0, std::min(tip, h) + h);
    volume += length * rho * (ToolRadiusMm / radial) * 2 * M_PI;
  }
  return volume;
}

/// The meshes are inscribed polygons (64 facets for the tool, 96 x 192 for the spheres): their
/// solids are smaller than the analytic ones by under 0.2 % of the volume, a few micrometres deep.
double FacetToleranceMm3(double volume)
{
  return 0.005 * volume + 0.05;
}
const double FacetToleranceMm = 0.01;

struct Sample
{
  double DepthMm = 0.0;
  double FrameMs = 0.0;
  Penetration Answer;
  double TrueVolumeMm3 = 0.0;
};

vtkSmartPointer<vtkVesselProximityLogic> OpenPenetrationScene(const DistanceEngineSettings& engine)
{
  SceneRequest request;
  const double centres[3][3] = { { 0, 0, 0 }, { 40, 0, 0 }, { -40, 0, 0 } };
  const char* classes[3] = { "portal_vein", "hepatic_artery", "hepatic_vein" };
  for (int c = 0; c < 3; ++c)
  {
    request.Vessels.push_back({ classes[c], "", MakeSphere(centres[c], VesselRadiusMm, 96, 192), std::nullopt });
  }
  const double axis[3] = { 0, 0, 1 };
  const double centre[3] = { 0, 0, -ToolLengthMm / 2 };
  request.Scalpel = vtkSmartPointer<vtkScalpelModel>::New();
  request.Scalpel->SetModel(MakeCappedCylinder(centre, axis, ToolRadiusMm, ToolLengthMm, 64));
  request.Scalpel->SetTipSource("the benchmark's cylinder: tip face at the origin, shaft along -z");
  request.Engine = engine;
  request.ComputeSurfaceDistance = true;
  request.ComputePenetration = true;
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  logic->OpenScene(request);
  return logic;
}

std::vector<Sample> Sweep(vtkVesselProximityLogic* logic, const std::vector<double>& depths, const std::vector<double>& truth)
{
  TrackingSession session(logic);
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < depths.size(); ++i)
  {
    TrackedPose pose;
    pose.TimeS = 0.05 * static_cast<double>(i);
    pose.ModelToWorld = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -VesselRadiusMm + depths[i], 0, 0, 0, 1 };
    const TrackedFrame& frame = session.Process(pose);
    samples.push_back({ depths[i], frame.FrameMs, frame.Penetrations.empty() ? Penetration() : frame.Penetrations[0], truth[i] });
  }
  return samples;
}

Json Summary(const std::vector<Sample>& samples)
{
  Json out;
  std::vector<double> all;
  for (const Sample& s : samples)
  {
    all.push_back(s.FrameMs);
  }
  out["frame_ms"] = Timing(all);
  Json bands = Json::array();
  double maxRelative = 0.0, maxAbsolute = 0.0, maxDepthError = 0.0;
  int outsideBound = 0, belowTruth = 0, unknown = 0;
  for (const auto& band : Bands)
  {
    std::vector<double> ms;
    double bandRelative = 0.0, bandAbsolute = 0.0;
    for (const Sample& s : samples)
    {
      if (s.DepthMm < band[0] || s.DepthMm >= band[1])
      {
        continue;
      }
      ms.push_back(s.FrameMs);
      if (!s.Answer.Known)
      {
        ++unknown;
        continue;
      }
      const double error = s.Answer.VolumeMm3 - s.TrueVolumeMm3;
      bandAbsolute = std::max(bandAbsolute, std::abs(error));
      bandRelative = std::max(bandRelative, std::abs(error) / s.TrueVolumeMm3);
    }
    Json b = Timing(ms);
    b["depth_from_mm"] = band[0];
    b["depth_to_mm"] = std::min(band[1], 10.0);
    b["max_volume_error_mm3"] = bandAbsolute;
    b["max_volume_error_relative"] = bandRelative;
    bands.push_back(b);
  }
  for (const Sample& s : samples)
  {
    if (!s.Answer.Known)
    {
      continue;
    }
    const double error = s.Answer.VolumeMm3 - s.TrueVolumeMm3;
    maxAbsolute = std::max(maxAbsolute, std::abs(error));
    if (s.DepthMm >= 1.0)
    {
      maxRelative = std::max(maxRelative, std::abs(error) / s.TrueVolumeMm3);
    }
    maxDepthError = std::max(maxDepthError, std::abs(s.Answer.DepthMm - s.DepthMm));
    const bool volumeInBound = std::abs(error) <= s.Answer.VolumeBoundMm3 + FacetToleranceMm3(s.TrueVolumeMm3);
    const bool depthInBound = std::abs(s.Answer.DepthMm - s.DepthMm) <= s.Answer.DepthBoundMm + FacetToleranceMm;
    outsideBound += volumeInBound && depthInBound ? 0 : 1;
    // Danger understated: less inside than the truth by more than the stated bound.
    belowTruth += s.Answer.DepthMm < s.DepthMm - s.Answer.DepthBoundMm - FacetToleranceMm ||
        s.Answer.VolumeMm3 < s.TrueVolumeMm3 - s.Answer.VolumeBoundMm3 - FacetToleranceMm3(s.TrueVolumeMm3)
      ? 1
      : 0;
  }
  out["bands"] = bands;
  out["max_volume_error_mm3"] = maxAbsolute;
  out["max_volume_error_relative_from_1mm"] = maxRelative;
  out["max_depth_error_mm"] = maxDepthError;
  out["answers_outside_their_bound"] = outsideBound;
  out["answers_below_truth_beyond_bound"] = belowTruth;
  out["answers_unknown"] = unknown;
  Json rows = Json::array();
  for (const Sample& s : samples)
  {
    rows.push_back({ s.DepthMm, s.FrameMs, s.Answer.DepthMm, s.Answer.DepthBoundMm, s.Answer.VolumeMm3, s.Answer.VolumeBoundMm3,
      s.TrueVolumeMm3 });
  }
  out["per_pose_columns"] = { "push_mm", "frame_ms", "depth_mm", "depth_bound_mm", "volume_mm3", "volume_bound_mm3",
    "true_volume_mm3" };
  out["per_pose"] = rows;
  return out;
}

/// FCL's penetration depth of the convex primitives themselves (EPA), the anchor where it applies:
/// its depth is the least translation that separates them, here the push along the axis.
Json FclPrimitives(const std::vector<double>& depths)
{
  auto cylinder = std::make_shared<fcl::Cylinderd>(ToolRadiusMm, ToolLengthMm);
  auto sphere = std::make_shared<fcl::Sphered>(VesselRadiusMm);
  fcl::CollisionObjectd vessel(sphere, fcl::Transform3d::Identity());
  std::vector<double> ms;
  double maxError = 0.0;
  for (double d : depths)
  {
    fcl::Transform3d pose = fcl::Transform3d::Identity();
    pose.translation() = fcl::Vector3d(0, 0, -VesselRadiusMm + d - ToolLengthMm / 2);
    fcl::CollisionObjectd tool(cylinder, pose);
    fcl::CollisionRequestd request(1, true);
    fcl::CollisionResultd result;
    const double start = NowMs();
    fcl::collide(&tool, &vessel, request, result);
    ms.push_back(NowMs() - start);
    const double depth = result.numContacts() > 0 ? result.getContact(0).penetration_depth : 0.0;
    maxError = std::max(maxError, std::abs(depth - d));
  }
  Json out = Timing(ms);
  out["what"] = "fcl::collide of fcl::Cylinder into fcl::Sphere with contacts (EPA): depth only, convex primitives only";
  out["max_depth_error_mm"] = maxError;
  return out;
}
} // namespace

BenchJson BenchPenetration(int poses, const DistanceEngineSettings* zbuffer)
{
  std::vector<double> depths, truth;
  for (int i = 0; i < poses; ++i)
  {
    depths.push_back(0.2 + (10.0 - 0.2) * i / std::max(1, poses - 1));
    truth.push_back(OverlapVolumeMm3(-VesselRadiusMm + depths.back()));
  }
  Json out;
  out["scene"] = "closed cylinder tool (radius 1.5 mm, 64 facets) pushed 0.2-10 mm along its axis into a sphere vessel "
                 "(radius 10 mm, 96 x 192) of 3 sphere classes; full frame through the logic (tip, whole instrument, "
                 "penetration)";
  out["poses"] = poses;
  std::fprintf(stderr, "bench: penetration sweep, exact");
  DistanceEngineSettings exact;
  exact.Method = "exact";
  out["exact"] = Summary(Sweep(OpenPenetrationScene(exact), depths, truth));
  if (zbuffer)
  {
    std::fprintf(stderr, ", z-buffer");
    try
    {
      out["zbuffer"] = Summary(Sweep(OpenPenetrationScene(*zbuffer), depths, truth));
    }
    catch (const DeviceError& e)
    {
      out["zbuffer"] = { { "unavailable", e.what() } };
    }
  }
  std::fprintf(stderr, ", FCL's primitives\n");
  out["fcl_primitives"] = FclPrimitives(depths);
  return out;
}
} // namespace vp
