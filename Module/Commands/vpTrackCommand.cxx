// vesselproximity track: a recorded stream of scalpel poses replayed against the vessels, with the
// per-frame record (frames.csv), the run's summary (summary.json) and its plot (distance.png).
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpClassName.h"
#include "vpCommands.h"
#include "vpDangerLevels.h"
#include "vpEngineOptions.h"
#include "vpFramesCsv.h"
#include "vpInputError.h"
#include "vpKeyFrameShots.h"
#include "vpKeyFrames.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpOutputOptions.h"
#include "vpTrackingOptions.h"
#include "vpTrackingRecorder.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"
#include "vpVirtualDisplay.h"

#include <cstdio>
#include <iostream>
#include <optional>

namespace vp
{
namespace
{
/// The reading options, and --strict.
std::vector<cli::Parameter> PoseReadingOptionsWithStrict()
{
  std::vector<cli::Parameter> options = PoseReadingOptions();
  options.push_back(Switch("strict",
    "Refuse the run (nothing written) when the poses look misread: none near a vessel, 1000 times too small or large, "
    "mirrored, timed in milliseconds, or quaternions without a header naming their order (without it, a warning on "
    "stderr and in summary.json)."));
  return options;
}

/// The flag that would read the poses as a warning suspects.
std::string Hint(const std::string& kind)
{
  return kind == "metres" ? " (--pose-units m)"
    : kind == "mirrored" ? " (--pose-space RAS)"
    : kind == "milliseconds" ? " (--time-units ms)"
    : kind == "no_pose_near_vessels" ? " (--pose-space, --pose-units)"
    : kind == "quaternion_order_assumed" ? " (name the columns in a header line: time,x,y,z,qx,qy,qz,qw if scalar last)"
                                     : "";
}

/// Each warning on stderr; under --strict the first refuses the run in one line instead.
void ReportTrajectoryWarnings(const std::vector<TrajectoryWarning>& warnings, bool strict, const std::string& posesFile)
{
  if (strict && !warnings.empty())
  {
    const std::size_t more = warnings.size() - 1;
    throw InputError(posesFile, warnings.front().Text + Hint(warnings.front().Kind) + "; --strict refuses the run" +
        (more ? " (" + std::to_string(more) + " more warning(s))" : ""));
  }
  for (const TrajectoryWarning& w : warnings)
  {
    std::cerr << "track: warning: " << posesFile << ": " << w.Text << Hint(w.Kind) << "\n";
  }
}

/// A tumour as the user named it: its models.json display name ("tumour 03 (livertumor03)"),
/// else its id spoken.
std::string TumourNameOf(const std::string& id, const std::vector<NamedMesh>& tumours)
{
  for (const NamedMesh& t : tumours)
  {
    if (t.ClassName == id && !t.DisplayName.empty())
    {
      return t.DisplayName;
    }
  }
  return TumourSpoken(id);
}

void PrintSummary(const TrackingRecorder& session, vtkVesselProximityLogic* proximity, const std::vector<NamedMesh>& tumours,
  const std::string& outDir, std::optional<std::size_t> shots)
{
  const TrackingSummary& summary = session.GetSummary();
  vtkVesselDistanceEngine* engine = proximity->GetDistanceEngine();
  const bool surface = proximity->GetComputeSurfaceDistance();
  const double budgetMs = proximity->GetTrackingLogic()->GetFrameBudgetMs();
  const std::vector<std::string>& classes = summary.GetClassNames();
  const std::size_t frameCount = static_cast<std::size_t>(summary.GetNumberOfFrames());
  std::printf("%zu frames over %.2f s, method %s on %s, error bound %.3f mm\n", frameCount, summary.GetDurationS(),
    engine->GetMethodName(), engine->GetDeviceDescription().c_str(), engine->GetErrorBoundMm());
  if (engine->GetErrorBoundMm() > 0)
  {
    // A bounded answer is not an exact number: say so where the numbers are read.
    std::printf("  (%s distances: the truth lies within %.3f mm of each; a distance of 0 may be a tip just outside)\n",
      engine->GetMethodName(), engine->GetErrorBoundMm());
  }
  std::printf("  %-16s %16s %10s %20s\n", "class", "tip minimum mm", "at time", surface ? "whole surface mm" : "");
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const ClassMinimum& m = summary.GetTipMinimum()[c];
    const ClassMinimum& s = summary.GetSurfaceMinimum()[c];
    std::printf("  %-16s %16s %10s %20s\n", classes[c].c_str(),
      m.Seen ? (FixedText(m.DistanceMm, "%.3f") + (m.Inside ? " inside" : "")).c_str() : "out of range",
      m.Seen ? FixedText(m.TimeS, "%.3f").c_str() : "", surface ? (s.Seen ? FixedText(s.DistanceMm, "%.3f").c_str() : "out of range") : "");
  }
  std::printf("  time at each level:");
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    std::printf(" %s %.2f s", DangerLevelName(static_cast<DangerLevel>(l)), summary.GetTimeInLevelS()[l]);
  }
  std::printf("\n  %zu level change(s), worst level %s (tip %s, instrument %s)\n", summary.GetChanges().size(),
    DangerLevelName(summary.GetWorstLevel()), DangerLevelName(summary.GetWorstTipLevel()),
    summary.GetInstrumentMeasured() ? DangerLevelName(summary.GetWorstInstrumentLevel()) : "not measured");
  for (const TumourMarginSummary& t : summary.GetTumours())
  {
    const char* inside = t.MarginMinMm < 0.0 ? " (inside)" : "";
    std::printf("  %s: smallest margin %.3f mm%s; time", TumourNameOf(t.Id, tumours).c_str(), t.MarginMinMm, inside);
    for (int l = 0; l < NumberOfMarginLevels; ++l)
    {
      std::printf(" %s %.2f s", MarginLevelName(static_cast<MarginLevel>(l)), t.TimeInLevelS[l]);
    }
    std::printf("\n");
  }
  const auto lost = session.GetReport().value("poses_lost", 0);
  if (lost > 0)
  {
    std::printf("  %d pose(s) lost by the tracker (from %.3f s): no frame and no distance for them\n", static_cast<int>(lost),
      session.GetReport().value("first_lost_time_s", 0.0));
  }
  std::printf("  %s\n", FrameTimesText(summary, budgetMs).c_str());
  if (const auto& check = session.GetComparison())
  {
    std::printf("  against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n",
      check->MaxAbsDifferenceMm, check->OutsideBound);
  }
  std::printf("wrote %s/frames.csv, summary.json, distance.png\n", outDir.c_str());
  if (shots)
  {
    std::printf("wrote %zu key frame(s) in %s/screenshots/ and their contact sheet %s/keyframes.png\n", *shots, outDir.c_str(),
      outDir.c_str());
  }
}
/// A display for the pictures (the run's own Xvfb when there is none), or the run refused.
void RequireDisplayFor(bool screenshots, VirtualDisplay& display)
{
  if (screenshots && !display.Ensure())
  {
    throw InputError("--screenshots", display.GetProblem());
  }
}

/// What the run reads: never removed or written over, even in its own output folder.
std::vector<std::string> TrackInputs(const std::string& posesFile, const SceneRequest& request)
{
  std::vector<std::string> inputs = SceneInputFiles(request);
  inputs.push_back(posesFile);
  return inputs;
}

/// The key frames' pictures and their contact sheet in the run, as a stage of progress (the
/// level changes left out said once it is cleared); how many.
std::size_t RenderTrackKeyFrames(const ModuleServices& module, vtkVesselProximityLogic* proximity, const OpenedScene& scene,
  const KeyFrameFinder& keys, std::vector<TrackedPose> poses, const std::string& camera, RunFolder& run, StageProgress& progress)
{
  progress.Stage("rendering the key frames");
  KeyFrameShotRequest pictures;
  pictures.Logic = proximity;
  pictures.Poses = std::move(poses);
  pictures.Keys = keys.GetKeyFrames();
  pictures.Liver = scene.Liver;
  vtkVesselProximityView::ParseCameraPreset(camera, pictures.Camera); // an enumeration: checked
  pictures.Folder = run.Folder("screenshots");
  pictures.ContactSheetFile = run.File("keyframes.png");
  const std::size_t shots = RenderKeyFrameShots(module, pictures).size();
  progress.Finish();
  if (keys.GetLevelChangesLeftOut() > 0)
  {
    std::fprintf(stderr, "track: %zu more level change(s) not pictured (the first %zu are)\n", keys.GetLevelChangesLeftOut(),
      KeyFrameFinder::MaximumLevelChanges);
  }
  return shots;
}

/// The z-buffer's answers outside its bound, when the run compared them with the exact engine.
void WarnOutsideBound(const TrackingRecorder& session, vtkVesselProximityLogic* proximity)
{
  if (session.GetComparison() && session.GetComparison()->OutsideBound > 0)
  {
    std::cerr << "vesselproximity: warning: " << session.GetComparison()->OutsideBound
              << " answer(s) of the z-buffer engine outside its error bound of "
              << proximity->GetDistanceEngine()->GetErrorBoundMm() << " mm\n";
  }
}
} // namespace

cli::ModuleDescription DescribeTrackCommand()
{
  using cli::ParameterType;
  return cli::ModuleDescription::Subcommand("vesselproximity track",
    "replay tracked scalpel poses: frames.csv, summary.json, distance.png, danger levels",
    "Replays tracked scalpel poses against the vessels and writes OUTDIR/frames.csv (one row per pose), "
    "summary.json and distance.png; the folder then holds this run whole, or the previous one as it was.",
    {
      { "Inputs", "",
        { VesselsOption().SetRequired(), RepairSwitch(),
          Option(ParameterType::File, "poses",
            "Tracked poses, model-to-world: CSV with a header naming its columns (time; x,y,z and qw,qx,qy,qz in any "
            "order; or m00..m33), `time,m00..m33` or `time,x,y,z,qw,qx,qy,qz` without one, or JSON.")
            .SetChannel(cli::Channel::Input)
            .SetRequired(),
          OutputFolderOption("The run's folder: frames.csv, summary.json, distance.png.").SetRequired() } },
      { "Poses", "", PoseReadingOptionsWithStrict() },
      { "Scalpel", "", ScalpelOptions() },
      EngineOptions(EngineMethodNames(OfferedForTracking)),
      TrackingOptions(),
      OutputOptions(OutputForTrack),
      { "Pictures", "",
        { Switch("screenshots",
            "Also OUTDIR/screenshots/ of the key frames (the first and last, each change of the danger level and of the "
            "margin's, the closest approach to each class and tumour, the instrument's first contact with each class and "
            "its deepest penetration, the first pose the tracker lost; frames under 0.5 s apart at the same levels are one "
            "picture) and OUTDIR/keyframes.png, a contact sheet of them captioned in words (rendered off-screen; Xvfb is "
            "started when there is no display)."),
          Option(ParameterType::StringEnumeration, "view",
            "The screenshots' camera, as view --view takes it; clear (the default) turns until the tip and its closest "
            "vessel point are in plain sight.")
            .SetDefault("clear")
            .SetElements({ "anterior", "lateral", "superior", "tool", "follow", "clear" }),
          Option(ParameterType::File, "liver", "A liver surface, shown translucent in the screenshots.")
            .SetChannel(cli::Channel::Input) } },
    });
}

int RunTrackCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  const std::string outDir = args.GetString("output");
  RunFolder run(outDir, "summary.json");

  // Everything that can be refused is read before any computing: poses first, they are cheap.
  // They are read through once to be checked and counted, and again, a pose at a time, as the
  // frames are computed: an hour of tracking never has to fit in memory.
  const double start = NowMs();
  const std::string posesFile = args.GetString("poses");
  const PoseReading reading = ParsePoseReading(args);
  const std::size_t poseCount = PoseStream::CountPoses(posesFile, reading);
  SceneRequest request = ParseRecordedSceneRequest(args);
  request.LiverFile = args.GetString("liver");
  const ChosenOutputs chosen(args, OutputForTrack, "track", TrackInputs(posesFile, request));
  // Pictures need a display: one that cannot be had refuses the run before it computes anything.
  const bool screenshots = args.GetBoolean("screenshots");
  VirtualDisplay display;
  RequireDisplayFor(screenshots, display);
  run.SetInputs(TrackInputs(posesFile, request));
  vtkSmartPointer<vtkVesselProximityLogic> proximity = module.CreateLogic();
  StageProgress progress("track", proximity);
  const OpenedScene scene = proximity->OpenScene(request);
  progress.Finish();
  // Under --strict the run may yet be refused after its frames: its one line comes alone.
  const bool strict = args.GetBoolean("strict");
  if (!strict)
  {
    ReportOpenedScene("track", proximity, scene, request.ScalpelFile);
  }
  TrackingRecorder session(proximity, scene.Vessels);
  session.SetLoadAndBuildMs(NowMs() - start);
  session.SetProgress([&progress](std::size_t done, std::size_t expected) { progress.FramesDone(done, expected); });
  KeyFrameFinder keys;
  for (FrameOutput* output : chosen.Get())
  {
    session.AddOutput(output);
  }
  session.AddOutput(screenshots ? &keys : nullptr);
  PoseStream poses(posesFile, poseCount, reading);
  if (!session.Run(poses, run))
  {
    return 1; // the RunFolder removes what was written, then the signal acts
  }
  progress.Finish();
  chosen.SayProblems();
  std::size_t shots = 0;
  if (screenshots)
  {
    shots = RenderTrackKeyFrames(module, proximity, scene, keys, ReadPoseFile(posesFile, reading), args.GetString("view"), run, progress);
  }
  ReportTrajectoryWarnings(session.GetWarnings(), strict, posesFile);
  if (strict)
  {
    ReportOpenedScene("track", proximity, scene, request.ScalpelFile);
  }
  run.Commit(); // the folder holds this run whole, or the previous one as it was
  WarnOutsideBound(session, proximity);
  PrintSummary(session, proximity, request.Tumours, outDir, screenshots ? std::optional<std::size_t>(shots) : std::nullopt);
  return 0;
}
} // namespace vp
