#ifndef vpTrackingRecorder_h
#define vpTrackingRecorder_h

#include "vpExactComparison.h"
#include "vpPoseFile.h"
#include "vpTrackingSummary.h"
#include "vpTrajectoryCheck.h"
#include "vpFrameOutput.h"
#include "vpVesselMeshSet.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkVesselProximityLogic;

namespace vp
{
class RunFolder;

/// A tracking session (vp::TrackingSession) recorded into the run's report: frames.csv (a row per
/// frame, written as it is computed and flushed at least once a second), distance.png and summary.json, in the run's folder; the
/// caller commits it (RunFolder::Commit) with whatever else the run wrote. Memory does not grow
/// with the number of frames. Observers of the logic's tracking logic hear every frame and every
/// level change as they happen.
class TrackingRecorder
{
public:
  /// logic: opened (vtkVesselProximityLogic::OpenScene). vessels: the meshes as read
  /// (OpenedScene::Vessels), for the report's surface section (their files and repairs).
  TrackingRecorder(vtkVesselProximityLogic* logic, std::vector<NamedMesh> vessels);

  /// Called about once a second with the frames done so far and the source's expected count.
  void SetProgress(std::function<void(std::size_t done, std::size_t expected)> progress);
  /// Added to summary.json's timing_ms as load_and_build (the caller's time before Run()).
  void SetLoadAndBuildMs(double ms) { this->LoadAndBuildMs = ms; }
  /// An output of the run's frames beside the report (not owned; it outlives Run): told of each
  /// change of level, frame, lost pose and the end (vp::FrameOutput) before the report records
  /// them, so that a peer hears of danger first: the live results, the key frames (null: none).
  /// What each has to say goes into summary.json's "outputs" (FrameOutput::Report).
  void AddOutput(FrameOutput* output)
  {
    if (output)
    {
      this->Outputs.push_back(output);
    }
  }
  /// Called with summary.json before it is written, for the front end's own sections (a live
  /// run's latency and link counts).
  void SetReportAddition(std::function<void(nlohmann::ordered_json&)> addition) { this->ReportAddition = std::move(addition); }

  /// Runs every pose of the source and writes the report into run (begun here if it was not).
  /// summary.json's "files" lists the session's files and every entry the run noted before it
  /// (RunFolder::GetEntries): what a later run removes when it does not write them again.
  /// Returns false when a held signal came (RunFolder::SignalPending):
  /// the caller lets the RunFolder go and the signal acts. Throws InputError naming the file that
  /// could not be written, or the source's own error.
  bool Run(PoseSource& poses, RunFolder& run);

  const TrackingSummary& GetSummary() const { return this->Summary; }
  /// Against the exact engine, when the logic compares with it.
  const std::optional<ExactComparison>& GetComparison() const { return this->Comparison; }
  /// What the poses suggest was misread (TrajectoryCheck), also in summary.json's "warnings".
  const std::vector<TrajectoryWarning>& GetWarnings() const { return this->Warnings; }
  /// summary.json as written.
  const nlohmann::ordered_json& GetReport() const { return this->Report; }
  /// The process's peak resident memory when the run ended.
  double GetPeakMemoryMb() const { return this->PeakMemoryMb; }

private:
  vtkVesselProximityLogic* Logic;
  std::vector<NamedMesh> Vessels;
  std::function<void(std::size_t, std::size_t)> Progress;
  TrackingSummary Summary;
  std::optional<ExactComparison> Comparison;
  std::vector<TrajectoryWarning> Warnings;
  nlohmann::ordered_json Report;
  double LoadAndBuildMs = 0.0;
  double PeakMemoryMb = 0.0;
  std::vector<FrameOutput*> Outputs;
  std::function<void(nlohmann::ordered_json&)> ReportAddition;
};
} // namespace vp

#endif
