#include "vpTrackingRecorder.h"

#include "vpOutputFile.h"
#include "vpClock.h"
#include "vpDistancePlotRecorder.h"
#include "vpFramesCsv.h"
#include "vpInputError.h"
#include "vpRunFolder.h"
#include "vpTrackingReport.h"
#include "vpTrackingSession.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityParameters.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <sys/resource.h>

namespace vp
{
TrackingRecorder::TrackingRecorder(vtkVesselProximityLogic* logic, std::vector<NamedMesh> vessels)
  : Logic(logic)
  , Vessels(std::move(vessels))
{
}

void TrackingRecorder::SetProgress(std::function<void(std::size_t, std::size_t)> progress)
{
  this->Progress = std::move(progress);
}

namespace
{
/// frames.csv as a run streams it into its staging folder: every write checked (one line naming
/// the file when one fails), flushed at least every second, so that a live run that dies loses
/// at most its last second of rows.
class FramesCsvFile
{
public:
  explicit FramesCsvFile(RunFolder& run)
    : Name(run.Target() + "/frames.csv")
    , Out(run.File("frames.csv"), std::ios::binary | std::ios::trunc)
  {
    this->Check();
  }
  void Write(const std::string& text)
  {
    this->Out << text;
    this->Check();
    if (NowMs() - this->LastFlushMs > 1000.0)
    {
      this->Out.flush();
      this->LastFlushMs = NowMs();
    }
  }
  void Close()
  {
    this->Out.flush();
    this->Check();
    this->Out.close();
  }

private:
  void Check() const
  {
    if (!this->Out)
    {
      throw InputError(this->Name, std::string("write failed: ") + std::strerror(errno));
    }
  }
  std::string Name;
  std::ofstream Out;
  double LastFlushMs = NowMs();
};

/// The plot for a run whose first frame this is (its tumours named there).
std::unique_ptr<DistancePlotRecorder> PlotFor(
  const TrackedFrame& frame, const std::vector<std::string>& classes, bool surface, double marginMm)
{
  std::vector<std::string> tumours;
  for (std::size_t t = 0; frame.Tumour && t < frame.Tumour->Tumours.size(); ++t)
  {
    tumours.push_back(frame.Tumour->Tumours[t].Id);
  }
  return std::make_unique<DistancePlotRecorder>(classes, surface, tumours, marginMm);
}

/// The trajectory's warnings and the reading's own (a header-less quaternion), into the report
/// with how the poses were read.
std::vector<TrajectoryWarning> ReadingWarnings(const TrajectoryCheck& check, const SettledReading* reading, nlohmann::ordered_json& doc)
{
  std::vector<TrajectoryWarning> all = check.Warnings();
  if (reading && reading->QuaternionOrderAssumed)
  {
    all.push_back({ "quaternion_order_assumed",
      "no header: each row was read as time,x,y,z,qw,qx,qy,qz (scalar first); a scalar-last quaternion read so turns "
      "the instrument" });
  }
  nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
  for (const TrajectoryWarning& w : all)
  {
    warnings.push_back({ { "kind", w.Kind }, { "text", w.Text } });
  }
  doc["warnings"] = warnings;
  if (reading)
  {
    doc["pose_reading"] = PoseReadingJson(*reading);
  }
  return all;
}

/// The session's own files, then whatever else the run has written beside them (the demo's).
std::vector<std::string> SessionFiles(const RunFolder& run)
{
  std::vector<std::string> files{ "frames.csv", "summary.json", "distance.png" };
  for (const std::string& entry : run.GetEntries())
  {
    if (std::find(files.begin(), files.end(), entry) == files.end())
    {
      files.push_back(entry);
    }
  }
  return files;
}

/// The report's own part of the run beside the summary (an output of its own, told of each frame
/// first): each frame into the trajectory's check, the plot, frames.csv and the comparison with
/// the exact engine; a gap in the plot where the tracker lost the tool.
class RunRecord : public FrameOutput
{
public:
  RunRecord(vtkVesselProximityLogic* logic, const TrackingSummary& summary, std::optional<ExactComparison>& comparison,
    TrajectoryCheck& check, FramesCsvFile& framesCsv)
    : Logic(logic)
    , Surface(logic->GetComputeSurfaceDistance())
    , Summary(summary)
    , Comparison(comparison)
    , Check(check)
    , FramesCsv(framesCsv)
  {
  }
  void OnFrame(const TrackedFrame& frame) override
  {
    this->Check.Add(frame);
    if (!this->Plot)
    {
      const double marginMm = this->Logic->GetTrackingLogic()->GetMarginSettings().MarginMm;
      this->Plot = PlotFor(frame, this->Summary.GetClassNames(), this->Surface, marginMm);
      this->FramesCsv.Write(
        FramesCsvHeader(this->Summary.GetClassNames(), this->Surface, frame.Haptic.has_value(), frame.Tumour.has_value()));
    }
    this->Plot->Add(frame);
    this->FramesCsv.Write(FramesCsvRow(frame, this->Surface));
    if (this->Comparison)
    {
      vtkVesselDistanceEngine* engine = this->Logic->GetDistanceEngine();
      this->Comparison->Add(frame.Proximity, frame.Exact ? *frame.Exact : frame.Proximity, engine->GetRangeMm(), engine->GetErrorBoundMm());
    }
  }
  void OnLost(const TrackedPose& lost) override
  {
    if (this->Plot)
    {
      this->Plot->AddLost(lost.TimeS);
    }
  }
  /// Null until the first frame.
  DistancePlotRecorder* GetPlot() const { return this->Plot.get(); }

private:
  vtkVesselProximityLogic* Logic;
  bool Surface;
  const TrackingSummary& Summary;
  std::optional<ExactComparison>& Comparison;
  TrajectoryCheck& Check;
  FramesCsvFile& FramesCsv;
  std::unique_ptr<DistancePlotRecorder> Plot;
};

double PeakResidentMb()
{
  struct rusage usage = {};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0; // Linux: kB
}
} // namespace

bool TrackingRecorder::Run(PoseSource& poses, RunFolder& run)
{
  vtkVesselProximityLogic* proximity = this->Logic;
  vtkVesselDistanceEngine* engine = proximity->GetDistanceEngine();
  const bool surface = proximity->GetComputeSurfaceDistance();
  const bool compare = proximity->GetCompareWithExact();
  this->Summary = TrackingSummary();
  this->Comparison = compare ? std::optional<ExactComparison>(ExactComparison()) : std::nullopt;
  vtkScalpelTrackingLogic* tracking = proximity->GetTrackingLogic();

  // The frames stream into frames.csv in the run's staging folder as they are computed, and the
  // summary and the plot keep what they need in memory that does not grow with the run.
  std::vector<std::string> classes;
  for (int c = 0; c < engine->GetNumberOfVessels(); ++c)
  {
    classes.push_back(engine->GetVesselName(c));
  }
  CheckFramesCsvColumns(classes, proximity->GetParameters()->GetNumberOfTumours() > 0); // before anything is written
  run.Begin();
  FramesCsvFile framesCsv(run);
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  proximity->GetVesselBounds(bounds);
  TrajectoryCheck check(bounds, engine->GetRangeMm());
  RunRecord record(proximity, this->Summary, this->Comparison, check, framesCsv);
  TrackingSession session(proximity);
  session.SetProgress(this->Progress);
  // The caller's outputs first: a peer hears of a change of level before the frame is recorded
  // (and even when recording it fails).
  for (FrameOutput* output : this->Outputs)
  {
    session.AddOutput(output);
  }
  session.AddOutput(&this->Summary); // before the record: the plot and frames.csv take its class names
  session.AddOutput(&record);
  const bool ended = session.Run(poses);
  if (!ended)
  {
    return false;
  }
  DistancePlotRecorder* plot = record.GetPlot();
  if (!plot)
  {
    throw InputError(poses.GetName(), "no poses");
  }
  framesCsv.Close();

  nlohmann::ordered_json doc = TrackingSummaryJson(this->Summary, tracking, surface, this->Vessels, poses.GetName(),
    this->Comparison ? &*this->Comparison : nullptr);
  doc["timing_ms"]["load_and_build"] = this->LoadAndBuildMs;
  this->Warnings = ReadingWarnings(check, poses.GetSettledReading(), doc);
  // Times the tracker did not see the tool: no frame, no distance (a gap in the record).
  doc["poses_lost"] = session.GetNumberOfLostPoses();
  if (session.GetNumberOfLostPoses() > 0)
  {
    doc["first_lost_time_s"] = session.GetFirstLostTimeS();
  }
  doc["files"] = SessionFiles(run);
  this->PeakMemoryMb = PeakResidentMb();
  doc["peak_memory_mb"] = this->PeakMemoryMb;
  nlohmann::ordered_json outputs = nlohmann::ordered_json::object();
  for (const FrameOutput* output : this->Outputs)
  {
    output->Report(outputs);
  }
  if (!outputs.empty())
  {
    doc["outputs"] = std::move(outputs);
  }
  if (this->ReportAddition)
  {
    this->ReportAddition(doc);
  }

  plot->Write(run.File("distance.png"), tracking->GetDangerThresholds());
  WriteFileAtomically(run.File("summary.json"), doc.dump(2) + "\n");
  this->Report = std::move(doc);
  return true;
}
} // namespace vp
