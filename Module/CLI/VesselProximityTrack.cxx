// VesselProximityTrack: `vesselproximity track` as a 3D Slicer CLI module, so that a recorded
// session is reviewed in Slicer. Slicer hands over the vessel models and the scalpel (temporary
// files), the recorded poses (a pose file, or a PLUS/Slicer sequence export) and optionally the
// tracker-to-patient registration (a linear transform node); the program writes the frames table
// (shown as a table node), the summary and the plot, and returns the run's closest approaches.
#include "vpCliDescription.h"
#include "vpCliTableSchema.h"
#include "vpCliProgress.h"
#include "vpCliVessels.h"
#include "vpClock.h"
#include "vpDangerLevels.h"
#include "vpDistanceEngineFactory.h"
#include "vpInputError.h"
#include "vpOutputFile.h"
#include "vpPoseFile.h"
#include "vpRegistrationFile.h"
#include "vpRunFolder.h"
#include "vpTrackingRecorder.h"
#include "vtkVesselProximityLogic.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#ifndef VP_VERSION
#define VP_VERSION "0.1.0"
#endif

namespace
{
namespace fs = std::filesystem;
using vp::cli::Channel;
using vp::cli::Parameter;
using vp::cli::ParameterType;

vp::cli::ParameterGroup RecordingGroup()
{
  vp::cli::ParameterGroup recording{ "Recording", "The tracked poses, the scalpel and the registration", {} };
  recording.Parameters.push_back(Parameter(ParameterType::File, "poses")
                                   .SetLongFlag("poses")
                                   .SetChannel(Channel::Input)
                                   .SetFileExtensions(".csv,.json,.mha,.nrrd")
                                   .SetRequired()
                                   .SetLabel("Tracked poses")
                                   .SetDescription("The recorded scalpel poses, tool to tracker (or to the patient when "
                                                   "no registration is given): a pose file (CSV or JSON, as `vesselproximity "
                                                   "track` reads it) or a tracked sequence (PLUS or Slicer .igs.mha, "
                                                   ".igs.nrrd). Required."));
  recording.Parameters.push_back(Parameter(ParameterType::String, "toolName")
                                   .SetLongFlag("toolName")
                                   .SetLabel("Tool name")
                                   .SetDescription("In a tracked sequence, the tool whose transform is the scalpel "
                                                   "(Stylus for StylusToTracker); empty: the only one."));
  recording.Parameters.push_back(Parameter(ParameterType::Transform, "registration")
                                   .SetTypeAttribute("linear")
                                   .SetLongFlag("registration")
                                   .SetChannel(Channel::Input)
                                   .SetLabel("Tracker to patient")
                                   .SetDescription("The registration of the tracker to the patient (a linear transform "
                                                   "node, rigid). The poses are then read as RAS, Slicer's frame. Optional: "
                                                   "without it the poses are the patient's, LPS."));
  recording.Parameters.push_back(vp::cli::ScalpelModelParameter("The instrument's surface in its own coordinates, tip "
                                                                   "found from its shape. Optional: the built-in CUSA "
                                                                   "handpiece."));
  return recording;
}

vp::cli::ParameterGroup SettingsGroup()
{
  const vp::DangerThresholds defaults;
  vp::cli::ParameterGroup settings{ "Settings", "Engine and danger levels", {} };
  settings.Parameters.push_back(Parameter(ParameterType::StringEnumeration, "method")
                                  .SetLongFlag("method")
                                  .SetLogicName("Method")
                                  .SetLabel("Method")
                                  .SetDescription(vp::EngineMethodHelp(vp::EngineMethodNames(vp::OfferedForTracking), ". ") + ".")
                                  .SetDefault(vp::DistanceEngineSettings().Method)
                                  .SetElements(vp::EngineMethodNames(vp::OfferedForTracking)));
  auto threshold = [&](const char* name, const char* label, double value, const char* text) {
    settings.Parameters.push_back(Parameter(ParameterType::Float, name)
                                    .SetLongFlag(name)
                                    .SetLabel(label)
                                    .SetDescription(text)
                                    .SetDefault(vp::cli::FormatNumber(value))
                                    .SetRange(0.1, 100.0, 0.5));
  };
  threshold("cautionMm", "Caution (mm)", defaults.CautionMm, "Caution below this distance.");
  threshold("warningMm", "Warning (mm)", defaults.WarningMm, "Warning below this distance.");
  threshold("dangerMm", "Danger (mm)", defaults.DangerMm, "Danger below this distance (breach: inside a vessel).");
  settings.Parameters.push_back(Parameter(ParameterType::Boolean, "strict")
                                  .SetLongFlag("strict")
                                  .SetLabel("Refuse a doubtful recording")
                                  .SetDescription("Refuse the run, writing nothing, when the poses look misread (none "
                                                  "near the vessels, metres read as millimetres, a mirrored frame, "
                                                  "milliseconds read as seconds) instead of reporting it in Warnings.")
                                  .SetDefault("false"));
  return settings;
}

vp::cli::ParameterGroup ResectionGroup()
{
  vp::cli::ParameterGroup resection{ "Resection", "The tumour to be resected and its margin", {} };
  resection.Parameters.push_back(Parameter(ParameterType::Geometry, "tumour")
                                   .SetTypeAttribute("model")
                                   .SetFileExtensions(".stl,.vtk,.vtp,.obj")
                                   .SetLongFlag("tumour")
                                   .SetLogicName("Tumours")
                                   .SetChannel(Channel::Input)
                                   .SetLabel("Tumour")
                                   .SetDescription("The tumour's surface model (closed): every frame the tip's signed "
                                                   "distance to it (negative inside) and the margin's level (clear, near, "
                                                   "violated, inside) in the frames table. Optional."));
  resection.Parameters.push_back(Parameter(ParameterType::Float, "marginMm")
                                   .SetLongFlag("marginMm")
                                   .SetLogicName("MarginMm")
                                   .SetLabel("Margin (mm)")
                                   .SetDescription("The resection margin: closer is violated; up to as much again beyond "
                                                   "it is near.")
                                   .SetDefault(vp::cli::FormatNumber(vp::MarginSettings().MarginMm))
                                   .SetRange(0.0, 50.0, 0.5));
  return resection;
}

vp::cli::ParameterGroup OutputsGroup()
{
  vp::cli::ParameterGroup outputs{ "Outputs", "The review of the recording", {} };
  outputs.Parameters.push_back(Parameter(ParameterType::Table, "framesTable")
                                 .SetFileExtensions(".csv")
                                 .SetLongFlag("framesTable")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Frames table")
                                 .SetDescription("One row per pose: time, tip (LPS mm), per class the distance, "
                                                 "closest point and danger level (frames.csv of `vesselproximity track`)."));
  outputs.Parameters.push_back(Parameter(ParameterType::File, "summary")
                                 .SetFileExtensions(".json")
                                 .SetLongFlag("summary")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Summary")
                                 .SetDescription("summary.json: per class the closest approach and when, time at each "
                                                 "level, level changes, frame times. Optional."));
  outputs.Parameters.push_back(Parameter(ParameterType::File, "plot")
                                 .SetFileExtensions(".png")
                                 .SetLongFlag("plot")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Distance plot")
                                 .SetDescription("distance.png: distance over time per class with the danger bands. "
                                                 "Optional."));
  outputs.Parameters.push_back(Parameter(ParameterType::Directory, "outputDirectory")
                                 .SetLongFlag("outputDirectory")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Output folder")
                                 .SetDescription("Also keep the whole run (frames.csv, summary.json, distance.png) in "
                                                 "this folder, as `vesselproximity track -o` does. Optional."));
  return outputs;
}

vp::cli::ParameterGroup ResultsGroup()
{
  vp::cli::ParameterGroup out{ "Results", "The run's closest approaches (-1: never within range)", {} };
  out.Parameters.push_back(Parameter(ParameterType::Integer, "frames")
                             .SetChannel(Channel::Output)
                             .SetLabel("Frames")
                             .SetDescription("Poses replayed.")
                             .SetDefault("0"));
  out.Parameters.push_back(Parameter(ParameterType::String, "worstLevel")
                             .SetChannel(Channel::Output)
                             .SetLabel("Worst level")
                             .SetDescription("The worst danger level reached, of the tip or the whole instrument: safe, "
                                             "caution, warning, danger or breach."));
  out.Parameters.push_back(Parameter(ParameterType::String, "worstLevelCause")
                             .SetChannel(Channel::Output)
                             .SetLabel("Worst level's cause")
                             .SetDescription("What set the worst level: tip, instrument (the whole instrument's surface "
                                             "came closer than the tip), or none when safe all along."));
  out.Parameters.push_back(Parameter(ParameterType::String, "warnings")
                             .SetChannel(Channel::Output)
                             .SetLabel("Warnings")
                             .SetDescription("Why the poses may be misread (none near the vessels, units, a mirrored "
                                             "frame), one per line; empty when none. Strict refuses the run instead.")
                             .SetDefault(""));
  out.Parameters.push_back(Parameter(ParameterType::String, "worstMarginLevel")
                             .SetChannel(Channel::Output)
                             .SetLabel("Worst margin level")
                             .SetDescription("With a tumour, the worst margin level reached: clear, near, violated or "
                                             "inside; empty without one."));
  // Distances as text: a Slicer number field always holds a number, and no number means "none".
  out.Parameters.push_back(Parameter(ParameterType::String, "tumourMinimumMm")
                             .SetChannel(Channel::Output)
                             .SetLabel("Tumour closest (mm)")
                             .SetDescription("With a tumour, the tip's smallest signed distance to it over the run "
                                             "(negative: inside); no value without one.")
                             .SetDefault(""));
  for (const vp::cli::VesselClassParameter& v : vp::cli::VesselClassParameters())
  {
    out.Parameters.push_back(Parameter(ParameterType::String, std::string(v.Parameter) + "MinimumMm")
                               .SetChannel(Channel::Output)
                               .SetLabel(std::string(v.Label) + " closest (mm)")
                               .SetDescription(std::string("The tip's smallest signed distance to the ") + v.ClassName +
                                 " over the run, negative inside (minus the penetration depth); no value when never "
                                 "within range.")
                               .SetDefault(""));
    out.Parameters.push_back(Parameter(ParameterType::String, std::string(v.Parameter) + "InstrumentMinimumMm")
                               .SetChannel(Channel::Output)
                               .SetLabel(std::string(v.Label) + " instrument closest (mm)")
                               .SetDescription(std::string("The whole instrument's closest approach to the ") + v.ClassName +
                                 " over the run, negative inside (minus its deepest penetration); no value when never "
                                 "within range.")
                               .SetDefault(""));
  }
  return out;
}

vp::cli::ModuleDescription Describe()
{
  auto d = vp::cli::ModuleDescription::VesselProximity("VesselProximityTrack", "Vessel Proximity Track", VP_VERSION,
    { vp::cli::VesselModelsGroup(), RecordingGroup(), SettingsGroup(), ResectionGroup(), OutputsGroup(), ResultsGroup() });
  d.Description =
    "Reviews a recorded tracking session: replays the scalpel's poses against the vessel models and writes, per "
    "frame, the tip's and the whole instrument's distance to each vessel class with its danger level (a table Slicer "
    "shows), the run's summary and a distance plot. Same as `vesselproximity track`.";
  return d;
}

/// A private folder for the run beside where Slicer wants the table: on the same file system, so
/// each output is put in place by a rename.
std::string StagingFolder(const std::string& near)
{
  std::string pattern = (fs::absolute(near).parent_path() / ".vesselproximity-track-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
  {
    throw vp::InputError(near, "cannot make a working folder beside it");
  }
  return pattern;
}

/// Copies a file of the run to where Slicer reads it back, as every output is written (whole or
/// not at all, never replacing a device or a pipe: vp::WriteFileAtomically).
void PlaceOutput(const std::string& from, const std::string& to)
{
  std::ifstream in(from, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in)
  {
    throw vp::InputError(from, "cannot be read back from the run's folder");
  }
  vp::WriteFileAtomically(to, bytes.str());
}

/// The scene Slicer's parameters ask for.
vp::SceneRequest SceneFromParameters(const vp::cli::ParsedArguments& args)
{
  vp::SceneRequest request;
  for (const auto& [className, file] : vp::cli::GivenVesselModels(args))
  {
    request.Vessels.push_back({ className, file, nullptr, std::nullopt });
  }
  request.ScalpelFile = args.IsSet("scalpel") ? args.GetString("scalpel") : std::string();
  request.Engine.Method = args.GetString("method");
  request.CompareWithExact = request.Engine.Method == "both";
  request.Tracking.Thresholds = { args.GetNumber("cautionMm"), args.GetNumber("warningMm"), args.GetNumber("dangerMm") };
  request.Tracking.Thresholds.Validate("--cautionMm/--warningMm/--dangerMm");
  if (args.IsSet("tumour"))
  {
    // Slicer's temporary file name says nothing of the tumour (and a path is no ID=FILE entry).
    request.Tumours = { { "tumour", args.GetString("tumour"), nullptr, std::nullopt } };
  }
  request.Tracking.Margin.MarginMm = args.GetNumber("marginMm");
  request.Tracking.Margin.NearBandMm = request.Tracking.Margin.MarginMm; // "up to as much again beyond it is near"
  request.Tracking.Margin.Validate("--marginMm");
  return request;
}

/// The run's folder (the given output directory, else a private one removed at the end), its
/// inputs noted: what the run reads is never written over.
class TrackRunFolder
{
public:
  TrackRunFolder(const vp::cli::ParsedArguments& args, const std::string& posesFile, const vp::SceneRequest& request)
    : Keep(args.IsSet("outputDirectory"))
    , Where(this->Keep ? args.GetString("outputDirectory")
                       : StagingFolder(args.IsSet("framesTable") ? args.GetString("framesTable") : posesFile))
    , Removal{ this->Keep ? std::string() : this->Where }
    , Run(this->Where, "summary.json")
  {
    std::vector<std::string> inputs = { posesFile, request.ScalpelFile };
    for (const std::vector<vp::NamedMesh>* meshes : { &request.Vessels, &request.Tumours })
    {
      for (const vp::NamedMesh& mesh : *meshes)
      {
        inputs.push_back(mesh.FileName);
      }
    }
    this->Run.SetInputs(inputs);
  }
  TrackRunFolder(const TrackRunFolder&) = delete;
  TrackRunFolder& operator=(const TrackRunFolder&) = delete;
  /// Commits the run and puts each output Slicer asked for in place.
  void Place(const vp::cli::ParsedArguments& args)
  {
    this->Run.Commit();
    for (const auto& [parameter, file] : { std::pair<const char*, const char*>{ "framesTable", "frames.csv" },
           { "summary", "summary.json" }, { "plot", "distance.png" } })
    {
      if (args.IsSet(parameter))
      {
        PlaceOutput((fs::path(this->Where) / file).string(), args.GetString(parameter));
      }
    }
    if (args.IsSet("framesTable"))
    {
      // Typed for Slicer: the table's columns by their names.
      std::ifstream frames(args.GetString("framesTable"));
      std::string header;
      std::getline(frames, header);
      vp::cli::WriteTableSchema(args.GetString("framesTable"), vp::cli::FramesTableColumns(header));
    }
  }
  vp::RunFolder& GetRun() { return this->Run; }

private:
  /// Removes a private folder once the run (declared after it, so destroyed before) is done.
  struct Remover
  {
    std::string Folder;
    ~Remover()
    {
      std::error_code ec;
      if (!this->Folder.empty())
      {
        fs::remove_all(this->Folder, ec);
      }
    }
  };
  bool Keep;
  std::string Where;
  Remover Removal;
  vp::RunFolder Run;
};

/// What set the run's worst level: the tip, the whole instrument (worse than the tip), or none.
std::string WorstLevelCause(const vp::TrackingSummary& summary)
{
  if (summary.GetWorstLevel() == vp::DangerLevel::Safe)
  {
    return "none";
  }
  return summary.GetInstrumentMeasured() && summary.GetWorstInstrumentLevel() > summary.GetWorstTipLevel() ? "instrument" : "tip";
}

/// Each class's closest approach, the tip's and the whole instrument's (negative inside: the
/// deepest penetration), as Slicer shows them.
void SetClassResults(const vp::TrackingSummary& summary, vp::cli::ReturnValues& results)
{
  for (const vp::cli::VesselClassParameter& v : vp::cli::VesselClassParameters())
  {
    for (std::size_t c = 0; c < summary.GetClassNames().size(); ++c)
    {
      if (summary.GetClassNames()[c] != v.ClassName)
      {
        continue;
      }
      const vp::ClassMinimum& m = summary.GetTipMinimum()[c];
      if (m.Seen)
      {
        results.Set(std::string(v.Parameter) + "MinimumMm", m.Inside ? -m.DistanceMm : m.DistanceMm);
      }
      const bool deep = c < summary.GetPenetrationMaximum().size() && summary.GetPenetrationMaximum()[c].Known &&
        summary.GetPenetrationMaximum()[c].DepthFrame >= 0;
      if (deep)
      {
        results.Set(std::string(v.Parameter) + "InstrumentMinimumMm", -summary.GetPenetrationMaximum()[c].DepthMm);
      }
      else if (c < summary.GetSurfaceMinimum().size() && summary.GetSurfaceMinimum()[c].Seen)
      {
        results.Set(std::string(v.Parameter) + "InstrumentMinimumMm", summary.GetSurfaceMinimum()[c].DistanceMm);
      }
    }
  }
}

/// What Slicer shows of the run: frames, the worst levels and their cause, each class's closest
/// approaches.
void SetResults(const vp::TrackingSummary& summary, vp::cli::ReturnValues& results)
{
  results.Set("frames", summary.GetNumberOfFrames());
  results.Set("worstLevel", std::string(vp::DangerLevelName(summary.GetWorstLevel())));
  results.Set("worstLevelCause", WorstLevelCause(summary));
  if (!summary.GetTumours().empty())
  {
    results.Set("worstMarginLevel", std::string(vp::MarginLevelName(summary.GetWorstMarginLevel())));
    results.Set("tumourMinimumMm", summary.GetTumours()[0].MarginMinMm);
  }
  SetClassResults(summary, results);
}

/// The run's warnings about its poses, one a line; under strict, the first refuses the run
/// before anything is placed (nothing on stderr: a Slicer CLI's success is silent).
std::string CheckedWarnings(const std::vector<vp::TrajectoryWarning>& warnings, bool strict, const std::string& posesFile)
{
  if (strict && !warnings.empty())
  {
    throw vp::InputError(posesFile, warnings.front().Text + "; strict refuses the run");
  }
  std::string text;
  for (const vp::TrajectoryWarning& w : warnings)
  {
    text += (text.empty() ? "" : "\n") + w.Text;
  }
  return text;
}

void Run(const vp::cli::ParsedArguments& args, vp::cli::ReturnValues& results)
{
  const double start = vp::NowMs();
  vp::cli::FilterProgress progress("VesselProximityTrack");
  const vp::SceneRequest request = SceneFromParameters(args);
  vp::PoseReading reading;
  reading.ToolName = args.GetString("toolName");
  if (args.IsSet("registration"))
  {
    reading.Registration = vp::ReadTrackerRegistration(args.GetString("registration"));
  }
  const std::string posesFile = args.GetString("poses");
  const std::size_t poseCount = vp::PoseStream::CountPoses(posesFile, reading);
  TrackRunFolder folder(args, posesFile, request);

  vtkNew<vtkVesselProximityLogic> proximity;
  const vp::OpenedScene scene = proximity->OpenScene(request);
  progress.Stage("Replaying the poses", 0.1); // the poses, models and scalpel read and checked
  vp::TrackingRecorder session(proximity, scene.Vessels);
  session.SetLoadAndBuildMs(vp::NowMs() - start);
  session.SetProgress([&](std::size_t done, std::size_t expected) {
    progress.Stage("Replaying the poses", 0.1 + 0.85 * static_cast<double>(done) / static_cast<double>(expected));
  });
  vp::PoseStream poses(posesFile, poseCount, reading);
  if (!session.Run(poses, folder.GetRun()))
  {
    throw vp::InputError(posesFile, "the replay was interrupted");
  }
  const std::string warnings = CheckedWarnings(session.GetWarnings(), args.GetBoolean("strict"), posesFile);
  progress.Stage("Writing the outputs", 0.97);
  folder.Place(args);
  SetResults(session.GetSummary(), results);
  results.Set("warnings", warnings);
  progress.Finish();
}
} // namespace

int main(int argc, char* argv[])
{
  // Errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  return vp::cli::RunProgram(Describe(), argc, argv, Run);
}
