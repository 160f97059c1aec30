#ifndef vpTipDistanceQuery_h
#define vpTipDistanceQuery_h

#include "vpExactComparison.h"
#include "vpProximityResult.h"
#include "vpVesselMeshSet.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <vector>

namespace vp
{
/// The distance from each of a list of tips to every vessel class, answered as one batch (the
/// z-buffer engine: one GPU submission per 256 tips, the same answers as tip by tip, bit for
/// bit): what `vesselproximity distance` and the Slicer distance CLI ask.
struct TipDistanceRequest
{
  /// Made by the caller first (MakeDistanceEngine), so that a missing device is reported before
  /// any file is read; built here.
  vtkSmartPointer<vtkVesselDistanceEngine> Engine;
  /// Every answer checked against the exact engine's (the engine's Method both).
  bool CompareWithExact = false;
  std::vector<NamedMesh> Vessels;
  std::vector<std::array<double, 3>> TipsMm; ///< LPS
  /// The scalpel's axis (LPS, any length), for the directional distance along it; throws
  /// ParameterError("Axis") when it is the zero vector.
  std::optional<std::array<double, 3>> Axis;
};

struct TipDistanceAnswer
{
  std::vector<ProximityResult> Results;
  /// With CompareWithExact: the exact engine's answers, and per tip and class whether the
  /// engine's answer keeps the accuracy contract.
  std::vector<ProximityResult> Exact;
  std::vector<std::vector<char>> WithinBound;
  ExactComparison Comparison;
  double BatchMs = 0.0;
  /// The batch's time per tip.
  double QueryMs() const;
};

TipDistanceAnswer ComputeTipDistances(const TipDistanceRequest& request);

/// The JSON report of `distance --json` and of the CLI's report file: the engine, its bound, the
/// surfaces, per tip the nearest class and every class's answer (points in RAS when ras), the
/// comparison with the exact engine, and the times.
nlohmann::ordered_json TipDistanceReportJson(
  const TipDistanceRequest& request, const TipDistanceAnswer& answer, bool ras, double loadMs);
} // namespace vp

#endif
