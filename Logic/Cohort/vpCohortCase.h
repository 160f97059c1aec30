#ifndef vpCohortCase_h
#define vpCohortCase_h

#include "vpCohortManifest.h"
#include "vpVesselModelSet.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkVesselProximityLogic;

namespace vp
{
/// What a cohort keeps of one vessel class of one case (cohort.csv's columns): the tip's closest
/// approach over the tracked frames and the tips (signed: negative inside), the whole
/// instrument's, its largest penetration volume and depth, and the frames at the breach level (the
/// tip's or the whole instrument's). Empty where nothing measured it (no poses, no tips, no
/// instrument).
struct CohortClassRow
{
  std::string ClassName;
  std::optional<double> TipMinMm;
  std::optional<double> SurfaceMinMm;
  std::optional<double> PenetrationMaxMm3;
  int BreachFrames = 0;
  /// The instrument's deepest penetration (mm; empty when it never went in or was not measured).
  std::optional<double> PenetrationDepthMaxMm = {};
};

/// One tumour of a case (the plan's, else the segmentation's): the resection margin its poses
/// kept and the instrument's closest approach to it.
struct CohortTumourRow
{
  std::string Id; ///< "tumour_03", or the plan's id
  std::optional<double> MarginMinMm;
  std::optional<double> SurfaceMinMm;
};

/// One case's outcome: its rows, or the one-line error that stopped it.
struct CohortCaseResult
{
  std::string Case;
  std::vector<CohortClassRow> Classes;
  std::optional<double> MarginMinMm; ///< the smallest resection margin over the case's tumours
  std::vector<CohortTumourRow> Tumours;
  std::string Error;                 ///< empty: the case's folder is whole
  bool Resumed = false;              ///< taken from a whole folder of an earlier run
  int Frames = 0;
  int Tips = 0;
  double Ms = 0.0;
};

/// How every case is computed: the models as `models` builds them by default, the exact engine,
/// the tracking defaults.
struct CohortSettings
{
  VesselModelParameters Models;
};

/// Makes the module logic a case computes with (a front end passes its module's; default
/// vtkVesselProximityLogic::New).
using CohortLogicFactory = std::function<vtkSmartPointer<vtkVesselProximityLogic>()>;
/// Told of each stage of a case as it starts ("models", "track", "tips").
using CohortStageObserver = std::function<void(const std::string& caseName, const std::string& stage)>;

/// Computes one case into folder, which holds it whole afterwards (a RunFolder whose report is
/// case.json) or, when it fails, as it was: models/ (<class>.stl per class, models.json), with
/// poses frames.csv, summary.json and distance.png as `track` writes them (the plan's tumours
/// measured), with tips distance.json as `distance --json` writes it (exact engine), and
/// case.json: the inputs (each path with its size, time and content hash), the rows, every file
/// written (size and hash), the times. Vessel classes
/// are the models' classes but the liver. Never throws for the case's own problems: they are the
/// result's Error, one line naming the file. Returns with Error "interrupted" when a held signal
/// came (RunFolder::SignalPending).
CohortCaseResult RunCohortCase(const CohortCase& c, const std::string& folder, const CohortSettings& settings,
  const CohortLogicFactory& makeLogic, const CohortStageObserver& observer = {});

/// The result of a case an earlier run left whole in folder (its case.json), when its inputs are
/// the same paths of the same sizes, times and contents (each file in a folder input so) and every
/// file the run wrote (case.json's "outputs") is still as written; empty otherwise (the case is to
/// be run), with why in whyNot (empty when the folder holds no run).
std::optional<CohortCaseResult> CompletedCohortCase(const CohortCase& c, const std::string& folder, std::string* whyNot = nullptr);

/// case.json's "inputs": each input of the case with its size, modification time and content hash
/// (a folder's files each).
nlohmann::ordered_json CohortCaseInputsJson(const CohortCase& c);
} // namespace vp

#endif
