#include "vpApproachPlanner.h"

#include "vpApproachGeometry.h"
#include "vpApproachRecorder.h"
#include "vpClock.h"
#include "vpInputError.h"
#include "vpTrackingSession.h"
#include "vtkScalpelModel.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselProximityLogic.h"

#include <vtkOBBTree.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace vp
{
namespace
{
void CheckWithin(const char* setting, double value, double low, bool lowIncluded, double high, const char* unit)
{
  if (!(lowIncluded ? value >= low : value > low) || !(value <= high))
  {
    throw ParameterError(setting, "expected " + std::string(unit) + " from " + NumberText(low) + (lowIncluded ? "" : " (excluded)") +
        " to " + NumberText(high) + ", got " + NumberText(value));
  }
}
} // namespace

void ApproachPlanner::CheckSettings(const ApproachPlanRequest& request)
{
  if (request.EntryMm.has_value() == request.DirectionLps.has_value())
  {
    throw ParameterError("EntryMm/DirectionLps", "give one of the two: where the approach starts, or its direction");
  }
  if (request.DirectionLps && !(Length(*request.DirectionLps) > 1e-12 && std::isfinite(Length(*request.DirectionLps))))
  {
    throw ParameterError("DirectionLps", "has zero length: a direction needs one");
  }
  CheckWithin("StepMm", request.StepMm, 0.0, false, 50.0, "a step in mm");
  CheckWithin("MarginMm", request.MarginMm, 0.0, true, ApproachPlanRequest::MaximumMarginMm, "a distance in mm");
  CheckWithin("SearchDeg", request.SearchDeg, 0.0, true, ApproachPlanRequest::MaximumSearchDeg, "an angle in degrees");
  CheckWithin("SearchStepDeg", request.SearchStepDeg, 0.0, false, ApproachPlanRequest::MaximumSearchDeg, "an angle in degrees");
  CheckWithin("TimeStepS", request.TimeStepS, 0.0, false, 3600.0, "a time in s");
  if (request.StandOffMm && request.EntryMm)
  {
    throw ParameterError("StandOffMm", "goes with a direction: an entry already says where the approach starts");
  }
  if (request.StandOffMm)
  {
    CheckWithin("StandOffMm", *request.StandOffMm, 0.0, false, 2000.0, "a distance in mm");
  }
}

namespace
{
Vector3 Along(const Vector3& from, const Vector3& direction, double mm)
{
  return { from[0] + mm * direction[0], from[1] + mm * direction[1], from[2] + mm * direction[2] };
}

double Distance(const Vector3& a, const Vector3& b)
{
  return Length({ a[0] - b[0], a[1] - b[1], a[2] - b[2] });
}

double AngleDeg(const Vector3& a, const Vector3& b)
{
  const double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / 3.14159265358979323846;
}

double DeepestPenetrationMm(const PlannedApproach& approach)
{
  double deepestMm = 0.0;
  for (const ClassApproach& c : approach.Classes)
  {
    deepestMm = std::max(deepestMm, c.PenetrationDepthMm);
  }
  return deepestMm;
}

/// Whether a keeps further from the vessels than b: the larger clearance; between approaches that
/// both touch a vessel (or keep the same), the shallower penetration. Equals are not safer, so
/// that of two the one found first, nearer the asked direction, stays.
bool Safer(const PlannedApproach& a, const PlannedApproach& b)
{
  return a.ClearanceMm > b.ClearanceMm || (a.ClearanceMm == b.ClearanceMm && DeepestPenetrationMm(a) < DeepestPenetrationMm(b));
}

/// The poses along approach, as plan.csv holds them and a pose file's reader makes them from it.
void MakePoses(PlannedApproach& approach, const ApproachPlanRequest& request, vtkScalpelModel* scalpel)
{
  const double lengthMm = Distance(approach.EntryMm, approach.SurfacePointMm) + request.MarginMm;
  const long long steps = static_cast<long long>(std::ceil(lengthMm / request.StepMm - 1e-9));
  if (steps + 1 > ApproachPlanRequest::MaximumSteps)
  {
    throw ParameterError("StepMm", "the approach of " + NumberText(lengthMm) + " mm would take " + std::to_string(steps + 1) +
        " poses, more than " + std::to_string(ApproachPlanRequest::MaximumSteps) + ": take a longer step");
  }
  const double* axis = scalpel->GetAxis();
  const std::array<double, 4> q = QuaternionTurning({ axis[0], axis[1], axis[2] }, approach.Direction);
  const std::array<double, 16> rotation = PoseFromQuaternion({ 0, 0, 0 }, q);
  const double* tip = scalpel->GetTipMm();
  const SettledReading reading;
  approach.PoseValues.clear();
  approach.Poses.clear();
  for (long long i = 0; i <= steps; ++i)
  {
    const Vector3 tipMm = Along(approach.EntryMm, approach.Direction, std::min(static_cast<double>(i) * request.StepMm, lengthMm));
    std::array<double, 8> row{};
    // The time as plan.csv writes it (10 digits), so that the pose read back is this one.
    row[0] = std::strtod(FixedText(static_cast<double>(i) * request.TimeStepS, "%.10g").c_str(), nullptr);
    for (int a = 0; a < 3; ++a)
    {
      row[1 + a] = tipMm[a] - (rotation[4 * a] * tip[0] + rotation[4 * a + 1] * tip[1] + rotation[4 * a + 2] * tip[2]);
    }
    std::copy(q.begin(), q.end(), row.begin() + 4);
    TrackedPose pose;
    const std::string problem = MakeTrackedPose(row.data() + 1, 7, reading, pose);
    if (!problem.empty())
    {
      throw ParameterError(request.EntryMm ? "EntryMm" : "DirectionLps", "the approach's pose " + std::to_string(i) + ": " + problem);
    }
    pose.TimeS = row[0];
    approach.PoseValues.push_back(row);
    approach.Poses.push_back(pose);
  }
  approach.EndMm = Along(approach.SurfacePointMm, approach.Direction, request.MarginMm);
}
} // namespace

ApproachPlanner::ApproachPlanner(vtkVesselProximityLogic* logic)
  : Logic(logic)
{
}

ApproachPlanner::~ApproachPlanner() = default;

void ApproachPlanner::SetProgress(std::function<void(std::size_t, std::size_t)> progress)
{
  this->Progress = std::move(progress);
}

ApproachPlan ApproachPlanner::Plan(const ApproachPlanRequest& request)
{
  if (!request.Target || request.Target->GetNumberOfCells() == 0)
  {
    throw ParameterError("TargetName", "'" + Printable(request.TargetName) + "' has no surface");
  }
  ApproachPlanner::CheckSettings(request);
  this->TargetTree = vtkSmartPointer<vtkOBBTree>::New();
  this->TargetTree->SetDataSet(request.Target);
  this->TargetTree->BuildLocator();
  this->TargetSizeMm = request.Target->GetLength();
  ApproachPlan plan;
  plan.TargetName = request.TargetName;
  plan.TargetCentreMm = request.TargetCentreMm ? *request.TargetCentreMm : EnclosedVolumeCentre(request.Target);
  plan.StepMm = request.StepMm;
  plan.MarginMm = request.MarginMm;
  plan.TimeStepS = request.TimeStepS;
  plan.SearchDeg = request.SearchDeg;
  plan.SearchStepDeg = request.SearchDeg > 0.0 ? request.SearchStepDeg : 0.0;
  const double instrumentRangeMm = this->Logic->GetParameters()->GetInstrumentRangeMm();
  plan.RangeMm = instrumentRangeMm > 0.0 ? instrumentRangeMm : this->Logic->GetDistanceEngine()->GetRangeMm();
  plan.Asked = this->AskedLine(request, plan.TargetCentreMm);
  MakePoses(plan.Asked, request, this->Logic->GetScalpel());
  const std::size_t cone = ConeDirections(plan.Asked.Direction, request.SearchDeg, request.SearchStepDeg).size();
  this->ExpectedPoses = plan.Asked.Poses.size() * (1 + cone);
  this->LastReportMs = NowMs();
  this->Done = 0;
  this->Run(plan.Asked, request, plan);
  if (request.SearchDeg > 0.0)
  {
    this->Search(request, plan);
  }
  return plan;
}

PlannedApproach ApproachPlanner::AskedLine(const ApproachPlanRequest& request, const std::array<double, 3>& centre) const
{
  PlannedApproach line;
  if (request.EntryMm)
  {
    const Vector3 entry = *request.EntryMm;
    const double toCentreMm = Distance(entry, centre);
    if (!(toCentreMm > 1e-6))
    {
      throw ParameterError("EntryMm", "is the centre of '" + Printable(request.TargetName) + "': no direction to come from");
    }
    line.Direction = Normalized({ centre[0] - entry[0], centre[1] - entry[1], centre[2] - entry[2] });
    // Past the far side of the target: an odd number of crossings means the entry is inside it.
    const std::vector<double> t = LineCrossings(this->TargetTree, entry, line.Direction, toCentreMm + this->TargetSizeMm + 1.0);
    if (t.size() % 2 == 1)
    {
      throw ParameterError("EntryMm", "lies inside the target '" + Printable(request.TargetName) + "': an entry must be outside it");
    }
    if (t.empty())
    {
      throw ParameterError("EntryMm", "the line from it to the centre of '" + Printable(request.TargetName) + "' misses the target");
    }
    line.EntryMm = entry;
    line.SurfacePointMm = Along(entry, line.Direction, t.front());
    return line;
  }
  if (!this->LineThroughCentre(centre, Normalized(*request.DirectionLps), line))
  {
    throw ParameterError("DirectionLps", "the line along it through the centre of '" + Printable(request.TargetName) + "' misses the target");
  }
  double standOffMm = ApproachPlanRequest::DefaultStandOffMm;
  if (request.StandOffMm)
  {
    standOffMm = *request.StandOffMm;
  }
  else if (request.LiverBoundsMm)
  {
    // From outside the liver: where the line leaves the liver's box, 10 mm further back.
    const Vector3 back{ -line.Direction[0], -line.Direction[1], -line.Direction[2] };
    const double outMm = DistanceOutOfBox(line.SurfacePointMm, back, *request.LiverBoundsMm);
    standOffMm = outMm > 0.0 ? outMm + 10.0 : standOffMm;
  }
  line.EntryMm = Along(line.SurfacePointMm, line.Direction, -standOffMm);
  return line;
}

bool ApproachPlanner::LineThroughCentre(
  const std::array<double, 3>& centre, const std::array<double, 3>& direction, PlannedApproach& line) const
{
  const double reachMm = this->TargetSizeMm + 1.0;
  const Vector3 from = Along(centre, direction, -reachMm);
  const std::vector<double> t = LineCrossings(this->TargetTree, from, direction, 2.0 * reachMm);
  if (t.empty())
  {
    return false;
  }
  line.Direction = direction;
  line.SurfacePointMm = Along(from, direction, t.front());
  return true;
}

void ApproachPlanner::Run(PlannedApproach& approach, const ApproachPlanRequest& request, ApproachPlan& plan)
{
  if (approach.Poses.empty())
  {
    MakePoses(approach, request, this->Logic->GetScalpel());
  }
  TrackingSession session(this->Logic);
  ApproachRecorder recorder;
  session.AddOutput(&recorder);
  PoseListSource poses(approach.Poses, plan.TargetName);
  session.Run(poses, [this](const TrackedFrame&) {
    ++this->Done;
    this->Report();
  });
  recorder.Fill(approach, plan.RangeMm);
  plan.StepMs.insert(plan.StepMs.end(), recorder.GetStepMs().begin(), recorder.GetStepMs().end());
  approach.AngleFromAskedDeg = AngleDeg(approach.Direction, plan.Asked.Direction);
}

void ApproachPlanner::Search(const ApproachPlanRequest& request, ApproachPlan& plan)
{
  const double standOffMm = Distance(plan.Asked.EntryMm, plan.Asked.SurfacePointMm);
  plan.Safest = plan.Asked;
  for (const ConeDirection& d : ConeDirections(plan.Asked.Direction, request.SearchDeg, request.SearchStepDeg))
  {
    ++plan.DirectionsSearched;
    PlannedApproach candidate;
    if (!this->LineThroughCentre(plan.TargetCentreMm, d.Direction, candidate))
    {
      ++plan.DirectionsMissing;
      this->ExpectedPoses -= std::min(this->ExpectedPoses, plan.Asked.Poses.size());
      continue;
    }
    candidate.EntryMm = Along(candidate.SurfacePointMm, candidate.Direction, -standOffMm);
    this->Run(candidate, request, plan);
    if (Safer(candidate, *plan.Safest))
    {
      plan.Safest = std::move(candidate);
    }
  }
}

void ApproachPlanner::Report()
{
  if (this->Progress && NowMs() - this->LastReportMs > 1000.0)
  {
    this->LastReportMs = NowMs();
    this->Progress(this->Done, std::max(this->ExpectedPoses, this->Done));
  }
}
} // namespace vp
