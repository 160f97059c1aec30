#ifndef vpTrackingReport_h
#define vpTrackingReport_h

#include "vpExactComparison.h"
#include "vpPoseReading.h"
#include "vpTrackingSummary.h"
#include "vpVesselMeshSet.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

class vtkScalpelTrackingLogic;

namespace vp
{
/// summary.json of a tracking session: the poses' source, frames, engine and bound, surfaces,
/// scalpel, thresholds, per class the tip's and the instrument's closest approach and the
/// deepest penetration, time at each level, the level changes, frame times against the budget,
/// and the comparison with the exact engine when there was one. tracking: the logic that computed
/// the frames (its engine, scalpel and thresholds); surface: whether the whole instrument was measured.
nlohmann::ordered_json TrackingSummaryJson(const TrackingSummary& summary, vtkScalpelTrackingLogic* tracking, bool surface,
  const std::vector<NamedMesh>& vessels, const std::string& posesName, const ExactComparison* comparison);

/// How the poses were read, for summary.json: {"space", "units", "time_units", "registration":
/// {"file", "kind"} or null}.
nlohmann::ordered_json PoseReadingJson(const SettledReading& reading);
} // namespace vp

#endif
