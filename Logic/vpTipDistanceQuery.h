#ifndef vpTipDistanceQuery_h
#define vpTipDistanceQuery_h

#include "vpExactComparison.h"
#include "vpProximityResult.h"
#include "vpRegistrationFile.h"
#include "vpTumourProximity.h"
#include "vpVesselMeshSet.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <string>
#include <utility>
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
  /// Registration: the tips and the axis are the tracker's (in the LPS convention), taken into
  /// the patient by it; the answers, tips included, are the patient's. Unset: they are the patient's.
  std::optional<TrackerRegistration> Registration;
  /// Tumours (closed, LPS) each tip is also measured against: its signed distance, exact, negative
  /// inside, however far (what track's tumour_mm is; vtkTumourMarginDistance). Empty: none.
  std::vector<NamedMesh> Tumours;
};

struct TipDistanceAnswer
{
  std::vector<ProximityResult> Results;
  /// With tumours: per tip, each tumour's signed distance and closest point, in request order.
  std::vector<TumourMargin> Tumours;
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

/// What the chunks of ComputeTipDistancesInChunks add up to.
struct TipDistanceTotals
{
  bool Compared = false;
  ExactComparison Comparison;
  double BatchMs = 0.0;
  std::size_t Tips = 0;
  double QueryMs() const;
};

/// The same, chunkTips tips at a time in the order given: each chunk's answer goes to visit with
/// the index of its first tip as soon as it is computed, and is gone after, so that memory
/// follows the chunk, not the tips (a million tips with --json took 3.5 GB). The comparison with
/// the exact engine is the totals' (the chunk's WithinBound says it per tip and class).
TipDistanceTotals ComputeTipDistancesInChunks(const TipDistanceRequest& request, std::size_t chunkTips,
  const std::function<void(const TipDistanceAnswer& chunk, std::size_t firstTip)>& visit);

/// The JSON report of `distance --json` and of the CLI's report file: the engine, its bound, the
/// surfaces, the registration ({"file", "kind"} or null), per tip the nearest class and every class's answer (points in RAS when ras), the
/// comparison with the exact engine, and the times.
nlohmann::ordered_json TipDistanceReportJson(
  const TipDistanceRequest& request, const TipDistanceAnswer& answer, bool ras, double loadMs);
/// The same report in pieces, for one written as its chunks come: the members before
/// "results", one tip's entry (answer.Results[i]), and the members after.
nlohmann::ordered_json TipDistanceHeaderJson(const TipDistanceRequest& request, bool ras);
nlohmann::ordered_json TipResultJson(const TipDistanceAnswer& answer, std::size_t i, bool ras);
/// A tip's "tumours" entry: per tumour {"signed_mm", "inside", "point"}; null without tumours.
nlohmann::ordered_json TipTumoursJson(const TipDistanceAnswer& answer, std::size_t i, bool ras);
nlohmann::ordered_json TipDistanceTrailerJson(const TipDistanceRequest& request, const TipDistanceTotals& totals, double loadMs);
/// One entry of "results" as the report's dump(2) writes it (four spaces in).
std::string IndentedItem(const nlohmann::ordered_json& item);
/// The report's text around its "results" entries, so that the whole is the same as
/// TipDistanceReportJson(...).dump(2) with the entries (IndentedItem, joined by ",\n") between
/// the two: from the header and the trailer; anyResults says whether there is an entry at all.
std::pair<std::string, std::string> TipDistanceReportAround(
  const nlohmann::ordered_json& header, const nlohmann::ordered_json& trailer, bool anyResults);
} // namespace vp

#endif
