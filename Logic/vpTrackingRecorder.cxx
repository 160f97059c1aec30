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

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

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
/// The tracking logic's level changes (the vessels' and the margin's) into a summary, for as
/// long as this lives.
class LevelChangesInto
{
public:
  LevelChangesInto(vtkScalpelTrackingLogic* tracking, TrackingSummary& summary)
    : Tracking(tracking)
  {
    this->OnChange->SetClientData(&summary);
    this->OnChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      static_cast<TrackingSummary*>(client)->AddChange(*static_cast<DangerLevelChange*>(call));
    });
    this->OnMarginChange->SetClientData(&summary);
    this->OnMarginChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      static_cast<TrackingSummary*>(client)->AddMarginChange(*static_cast<MarginLevelChange*>(call));
    });
    this->Tags[0] = tracking->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, this->OnChange);
    this->Tags[1] = tracking->AddObserver(vtkScalpelTrackingLogic::MarginLevelChangedEvent, this->OnMarginChange);
  }
  ~LevelChangesInto()
  {
    this->Tracking->RemoveObserver(this->Tags[0]);
    this->Tracking->RemoveObserver(this->Tags[1]);
  }
  LevelChangesInto(const LevelChangesInto&) = delete;
  LevelChangesInto& operator=(const LevelChangesInto&) = delete;

private:
  vtkScalpelTrackingLogic* Tracking;
  vtkNew<vtkCallbackCommand> OnChange, OnMarginChange;
  unsigned long Tags[2] = { 0, 0 };
};

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
  const LevelChangesInto changes(tracking, this->Summary);

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
  std::unique_ptr<DistancePlotRecorder> plot;
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  proximity->GetVesselBounds(bounds);
  TrajectoryCheck check(bounds, engine->GetRangeMm());
  TrackingSession session(proximity);
  session.SetProgress(this->Progress);
  const bool ended = session.Run(poses, [&](const TrackedFrame& frame) {
    this->Summary.Add(frame);
    check.Add(frame);
    if (!plot)
    {
      plot = PlotFor(frame, this->Summary.GetClassNames(), surface, tracking->GetMarginSettings().MarginMm);
      framesCsv.Write(FramesCsvHeader(this->Summary.GetClassNames(), surface, frame.Haptic.has_value(), frame.Tumour.has_value()));
    }
    plot->Add(frame);
    framesCsv.Write(FramesCsvRow(frame, surface));
    if (compare)
    {
      this->Comparison->Add(frame.Proximity, proximity->GetLastExactProximity(), engine->GetRangeMm(), engine->GetErrorBoundMm());
    }
    if (this->FrameObserver)
    {
      this->FrameObserver(frame);
    }
  },
    [&](const TrackedPose& lost) {
      if (plot)
      {
        plot->AddLost(lost.TimeS); // a gap in the plot where the tracker lost the tool
      }
      if (this->LostObserver)
      {
        this->LostObserver(lost);
      }
    });
  if (!ended)
  {
    return false;
  }
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
