#ifndef vpTrackingOptions_h
#define vpTrackingOptions_h

#include "vpCliDescription.h"
#include "vpDangerLevels.h"
#include "vpMarginLevels.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpTrackingSummary.h"
#include "vpSceneRequest.h"

#include <string>

namespace vp
{
/// --tip X,Y,Z and --axis X,Y,Z: the scalpel's tip and axis in model coordinates.
std::vector<cli::Parameter> ScalpelTipOptions();
/// --scalpel FILE (required) and the tip options: the instrument of track and live.
std::vector<cli::Parameter> ScalpelOptions();
/// --frame-budget-ms MS, default the parameter set's (16.7, one refresh at 60 Hz; 0: no budget).
cli::Parameter FrameBudgetOption();
/// What tracking shares (track, live, view): --danger-mm, --hysteresis-mm, --frame-budget-ms,
/// --haptic-k, --haptic-c, --tumour, --margin-mm and --no-surface, with the parameter set's defaults.
cli::ParameterGroup TrackingOptions();

/// --pose-space LPS|RAS, --pose-units mm|m and --time-units s|ms: how a pose file's numbers are
/// read (left out: what the file declares, else LPS, mm, s).
std::vector<cli::Parameter> PoseReadingOptions();
/// What those options say (each unset when not given).
PoseReading ParsePoseReading(const cli::ParsedArguments& args);
/// The frame, units and registration alone (--pose-space, --pose-units, --registration), for a
/// stream that has no times or tools to read.
PoseReading ParsePoseFrame(const cli::ParsedArguments& args);

/// --danger-mm C,W,D, validated: throws InputError naming the option.
DangerThresholds ParseDangerThresholds(const cli::ParsedArguments& args);
/// --tip and --axis, each optional.
ScalpelTipDefinition ParseTipDefinition(const cli::ParsedArguments& args);
/// --frame-budget-ms, not negative; throws InputError naming the option.
double ParseFrameBudgetMs(const cli::ParsedArguments& args);
/// --hysteresis-mm, not negative (vtkScalpelTrackingLogic::SetHysteresisMm); throws InputError.
double ParseHysteresisMm(const cli::ParsedArguments& args);
/// --margin-mm and --near-band-mm (the band, by default, as wide as the margin), each from 0 to
/// MarginSettings::MaximumMm and only with tumours; throws InputError naming the option.
MarginSettings ParseMarginSettings(const cli::ParsedArguments& args, bool tumours);

/// "frame median X ms, p95 Y ms, max Z ms; K of N frames over the B ms budget" (or "no frame
/// budget"): how track and view report the frames' computing times.
std::string FrameTimesText(const TrackingSummary& summary, double budgetMs);

/// The scene the shared options ask for (track, view): --vessels, --scalpel (none: the built-in
/// handpiece) with --tip and --axis, the engine of --method with its settings (for "both", the
/// comparison with the exact engine), --danger-mm, --frame-budget-ms, --hysteresis-mm, the
/// tumours and their margin (--tumour, --margin-mm, --near-band-mm) and --no-surface. Nothing is read or opened here: vtkVesselProximityLogic::OpenScene does it.
/// Throws InputError naming the option.
SceneRequest ParseSceneRequest(const cli::ParsedArguments& args);
/// The scene of a command that records its frames (track, live): ParseSceneRequest with
/// --repair, its classes checked against frames.csv's columns before anything is read or said.
SceneRequest ParseRecordedSceneRequest(const cli::ParsedArguments& args);
/// The files the scene reads (its vessels, tumours, liver, scalpel and the scalpel's definition
/// beside it): what a run's folder and its file outputs must never write over.
std::vector<std::string> SceneInputFiles(const SceneRequest& request);
} // namespace vp

#endif
