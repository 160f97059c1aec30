#ifndef vpApproachPlanner_h
#define vpApproachPlanner_h

#include "vpApproachPlan.h"

#include <vtkSmartPointer.h>

#include <array>
#include <cstddef>
#include <functional>

class vtkOBBTree;
class vtkVesselProximityLogic;

namespace vp
{
/// Plans a straight approach to a target before any tracking: the poses that advance the
/// instrument along it, and the whole instrument's closest approach to each vessel class on the
/// way, computed by the logic's own frame loop (a vp::TrackingSession over the poses, as track runs
/// a pose file), so that replaying the plan's poses gives the same numbers. With a search, every
/// direction of the cone is run the same way and the safest kept: the one whose smallest
/// whole-instrument distance over all classes is largest (ties: the shallower penetration, then
/// the one nearer the asked direction).
///
///   vtkSmartPointer<vtkVesselProximityLogic> logic = ...; logic->OpenScene(request);
///   vp::ApproachPlanner planner(logic);
///   vp::ApproachPlan plan = planner.Plan(planRequest);
class ApproachPlanner
{
public:
  /// logic: its scene open (vtkVesselProximityLogic::OpenScene), the target among its tumours when
  /// the tip's depth in it is wanted.
  explicit ApproachPlanner(vtkVesselProximityLogic* logic);
  ~ApproachPlanner();
  ApproachPlanner(const ApproachPlanner&) = delete;
  ApproachPlanner& operator=(const ApproachPlanner&) = delete;

  /// Called about once a second with the poses computed and the poses there will be in all.
  void SetProgress(std::function<void(std::size_t done, std::size_t expected)> progress);

  /// Checks every setting of request but its target (a step, margin, stand-off or search out of
  /// range, neither or both of EntryMm and DirectionLps, a direction of zero length, a stand-off
  /// with an entry): throws
  /// vp::ParameterError naming it. What a front end calls before it opens anything.
  static void CheckSettings(const ApproachPlanRequest& request);

  /// The plan. Throws vp::ParameterError naming the request's setting: no target surface, neither
  /// or both of EntryMm and DirectionLps, a direction of zero length, an entry inside the target
  /// or at its centre, a line that misses the target, a step, margin, stand-off or search out of
  /// range, an approach of more than MaximumSteps poses.
  ApproachPlan Plan(const ApproachPlanRequest& request);

private:
  /// The asked approach's line: its direction, where it meets the target and its entry.
  PlannedApproach AskedLine(const ApproachPlanRequest& request, const std::array<double, 3>& centre) const;
  /// The line along direction through centre: false when it misses the target.
  bool LineThroughCentre(const std::array<double, 3>& centre, const std::array<double, 3>& direction, PlannedApproach& line) const;
  /// Poses every step from the entry to the margin past the surface point, then their frames.
  void Run(PlannedApproach& approach, const ApproachPlanRequest& request, ApproachPlan& plan);
  /// The cone's directions, each run; the safest of them and the asked one.
  void Search(const ApproachPlanRequest& request, ApproachPlan& plan);
  /// The progress callback, at most once a second.
  void Report();

  vtkSmartPointer<vtkVesselProximityLogic> Logic;
  vtkSmartPointer<vtkOBBTree> TargetTree;
  double TargetSizeMm = 0.0;
  std::function<void(std::size_t, std::size_t)> Progress;
  std::size_t ExpectedPoses = 0;
  std::size_t Done = 0;
  double LastReportMs = 0.0;
};
} // namespace vp

#endif
