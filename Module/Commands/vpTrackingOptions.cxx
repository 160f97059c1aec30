#include "vpTrackingOptions.h"

#include "vpArguments.h"
#include "vpEngineOptions.h"
#include "vpFramesCsv.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpRegistrationFile.h"
#include "vpScalpelLoader.h"

#include <cstdio>

namespace vp
{
namespace
{
/// The defaults the help shows are the logic's own.
TrackingSettings Defaults()
{
  return TrackingSettings();
}
} // namespace

std::vector<cli::Parameter> ScalpelTipOptions()
{
  return {
    Option(cli::ParameterType::String, "tip",
      "The scalpel's tip in model coordinates; else FILE.json beside the model ({\"tip_mm\": [x,y,z], \"axis\": "
      "[x,y,z]}), else found automatically (reported).")
      .SetPlaceholder("X,Y,Z"),
    Option(cli::ParameterType::String, "axis", "The direction the scalpel points, in model coordinates (need not be unit length).")
      .SetPlaceholder("X,Y,Z")
      .SetLogicName("Axis"),
  };
}

std::vector<cli::Parameter> ScalpelOptions()
{
  std::vector<cli::Parameter> scalpel = {
    Option(cli::ParameterType::File, "scalpel", "The scalpel's surface model (STL, VTK, VTP or OBJ), in model coordinates.")
      .SetChannel(cli::Channel::Input)
      .SetRequired(),
  };
  for (const cli::Parameter& p : ScalpelTipOptions())
  {
    scalpel.push_back(p);
  }
  return scalpel;
}

cli::Parameter FrameBudgetOption()
{
  return Option(cli::ParameterType::Double, "frame-budget-ms",
    "The time one frame may take (60 Hz by default; 0: no budget); the frames over it are counted and shown.")
    .SetPlaceholder("MS")
    .SetDefault(cli::FormatNumber(Defaults().FrameBudgetMs))
    .SetLogicName("FrameBudgetMs");
}

cli::ParameterGroup TrackingOptions()
{
  const DangerThresholds d = Defaults().Thresholds;
  using cli::FormatNumber;
  return { "Tracking", "",
    {
      Option(cli::ParameterType::String, "danger-mm",
        "Caution, warning and danger thresholds; a tip inside a vessel is a breach. The level uses the distance "
        "minus the engine's error bound.")
        .SetPlaceholder("C,W,D")
        .SetDefault(FormatNumber(d.CautionMm) + "," + FormatNumber(d.WarningMm) + "," + FormatNumber(d.DangerMm)),
      Option(cli::ParameterType::Double, "hysteresis-mm",
        "A level is entered at once but left only when the distance exceeds its threshold by this much (0: none), so "
        "tracking noise does not flicker it.")
        .SetPlaceholder("MM")
        .SetDefault(FormatNumber(Defaults().HysteresisMm))
        .SetLogicName("HysteresisMm"),
      FrameBudgetOption(),
      Option(cli::ParameterType::Double, "haptic-k",
        "A haptic device's contact stiffness: the force F = k * depth + c * rate pushes the instrument out of a vessel "
        "it has entered (frames.csv haptic_force_n, haptic_x/y/z; live sends it); 0: off.")
        .SetPlaceholder("N/MM")
        .SetDefault(FormatNumber(Defaults().Haptic.StiffnessNPerMm))
        .SetLogicName("HapticStiffnessNPerMm"),
      Option(cli::ParameterType::Double, "haptic-c",
        "The contact's damping: newton-seconds per mm of the depth's rate (filtered over 20 ms, bounded at 200 mm/s: "
        "no spike when the depth jumps); 0: off.")
        .SetPlaceholder("NS/MM")
        .SetDefault(FormatNumber(Defaults().Haptic.DampingNsPerMm))
        .SetLogicName("HapticDampingNsPerMm"),
      Option(cli::ParameterType::String, "tumour",
        "Tumours to be resected (surface models, LPS mm, closed): the tip's signed distance to each (frames.csv "
        "tumour_mm, negative inside, with tumour_id, the closest point, margin_level clear|near|violated|inside and "
        "tumour_surface_mm for the whole instrument; summary.json \"tumour\"). Each entry FILE (its id: the file's "
        "name), ID=FILE, or a models folder or its models.json (every tumour `models` found: tumour_01, ...).")
        .SetPlaceholder("FILE[,FILE...]")
        .SetLogicName("Tumours"),
      Option(cli::ParameterType::Double, "margin-mm",
        "The resection margin around every tumour (with --tumour): closer is 'violated'; up to --near-band-mm beyond it "
        "is 'near'. From 0 to 50.")
        .SetPlaceholder("MM")
        .SetDefault(FormatNumber(Defaults().Margin.MarginMm))
        .SetLogicName("MarginMm"),
      Option(cli::ParameterType::Double, "near-band-mm",
        "How far beyond the margin a tip is 'near' it (with --tumour). From 0 to 50. Default: the margin's own width.")
        .SetPlaceholder("MM")
        .SetLogicName("NearBandMm"),
      Switch("no-surface",
        "Skip the whole-instrument distance (the closest approach of any point of the scalpel surface, computed "
        "beside the tip's)."),
    } };
}

MarginSettings ParseMarginSettings(const cli::ParsedArguments& args, bool tumours)
{
  using cli::FormatNumber;
  for (const char* option : { "marginMm", "nearBandMm" })
  {
    if (args.IsSet(option) && !tumours)
    {
      throw InputError(std::string("--") + (option == std::string("marginMm") ? "margin-mm" : "near-band-mm"),
        "given without --tumour: there is no tumour to keep a margin from");
    }
  }
  MarginSettings margin;
  margin.MarginMm = args.GetNumber("marginMm");
  margin.NearBandMm = args.IsSet("nearBandMm") ? args.GetNumber("nearBandMm") : margin.MarginMm;
  for (const auto& [option, value] : { std::pair<const char*, double>{ "--margin-mm", margin.MarginMm }, { "--near-band-mm", margin.NearBandMm } })
  {
    if (!(value >= 0.0 && value <= MarginSettings::MaximumMm))
    {
      throw InputError(option, "expected a distance from 0 to " + FormatNumber(MarginSettings::MaximumMm) + " mm, got " + FormatNumber(value));
    }
  }
  return margin;
}

std::vector<cli::Parameter> PoseReadingOptions()
{
  using cli::ParameterType;
  return {
    Option(ParameterType::StringEnumeration, "pose-space",
      "The world frame of the poses: LPS (DICOM, the vessels') or RAS (3D Slicer's). Default: what the file declares, "
      "else LPS.")
      .SetElements({ "LPS", "RAS" })
      .SetLogicName("PoseSpace"),
    Option(ParameterType::StringEnumeration, "pose-units", "The poses' length unit. Default: what the file declares, else mm.")
      .SetElements({ "mm", "m" })
      .SetLogicName("PoseUnits"),
    Option(ParameterType::StringEnumeration, "time-units", "The poses' time unit. Default: what the file declares, else s.")
      .SetElements({ "s", "ms" })
      .SetLogicName("TimeUnits"),
    Option(ParameterType::String, "tool",
      "A tracked sequence's (PLUS .igs.mha, .igs.nrrd) tool: NAME for its NAMEToTrackerTransform, or a whole "
      "<From>To<To> name. Default: the sequence's default transform, or its only one.")
      .SetPlaceholder("NAME")
      .SetLogicName("ToolName"),
    Option(ParameterType::String, "reference",
      "A tracked sequence's reference: the poses become tool-to-reference, as PLUS composes them.")
      .SetPlaceholder("NAME")
      .SetLogicName("ReferenceName"),
    Option(ParameterType::File, "registration",
      "The tracker (or --reference) to the patient's images: register's RESULT.json (landmarks or icp), or a 3D "
      "Slicer transform (.h5, .tfm, .txt: the tracker's transform to RAS as Slicer saves it; the poses are then read "
      "as RAS, as Slicer holds them, unless --pose-space says otherwise). Every pose is taken into the patient by it.")
      .SetChannel(cli::Channel::Input)
      .SetPlaceholder("R.json|T.h5"),
  };
}

PoseReading ParsePoseFrame(const cli::ParsedArguments& args)
{
  PoseReading reading;
  if (args.IsSet("poseSpace"))
  {
    reading.Space = args.GetString("poseSpace") == "RAS" ? PoseSpace::RAS : PoseSpace::LPS;
  }
  if (args.IsSet("poseUnits"))
  {
    reading.MillimetresPerUnit = args.GetString("poseUnits") == "m" ? 1000.0 : 1.0;
  }
  if (args.IsSet("registration"))
  {
    reading.Registration = ReadTrackerRegistration(args.GetString("registration"));
  }
  return reading;
}

PoseReading ParsePoseReading(const cli::ParsedArguments& args)
{
  PoseReading reading = ParsePoseFrame(args);
  if (args.IsSet("timeUnits"))
  {
    reading.SecondsPerUnit = args.GetString("timeUnits") == "ms" ? 0.001 : 1.0;
  }
  reading.ToolName = args.GetString("tool");
  reading.ReferenceName = args.GetString("reference");
  return reading;
}

DangerThresholds ParseDangerThresholds(const cli::ParsedArguments& args)
{
  const auto d = ParsePoint(args.GetString("dangerMm"), "--danger-mm");
  const DangerThresholds thresholds{ d[0], d[1], d[2] };
  thresholds.Validate("--danger-mm");
  return thresholds;
}

ScalpelTipDefinition ParseTipDefinition(const cli::ParsedArguments& args)
{
  ScalpelTipDefinition tip;
  tip.Source = "--tip";
  if (args.IsSet("tip"))
  {
    tip.TipMm = ParsePoint(args.GetString("tip"), "--tip");
  }
  if (args.IsSet("axis"))
  {
    tip.Axis = ParsePoint(args.GetString("axis"), "--axis");
  }
  return tip;
}

double ParseFrameBudgetMs(const cli::ParsedArguments& args)
{
  const double budgetMs = args.GetNumber("frameBudgetMs"); // the parser refuses what is not a finite number
  if (budgetMs < 0.0)
  {
    throw InputError("--frame-budget-ms", "expected a time in ms, 0 or more (0: no budget), got '" + args.GetString("frameBudgetMs") + "'");
  }
  return budgetMs;
}

double ParseHysteresisMm(const cli::ParsedArguments& args)
{
  const double hysteresisMm = args.GetNumber("hysteresisMm");
  if (hysteresisMm < 0.0)
  {
    throw InputError("--hysteresis-mm", "expected a distance in mm, 0 or more (0: none), got '" + args.GetString("hysteresisMm") + "'");
  }
  return hysteresisMm;
}

std::string FrameTimesText(const TrackingSummary& summary, double budgetMs)
{
  char times[160];
  std::snprintf(times, sizeof times, "frame median %.4f ms, p95 %.4f ms, max %.4f ms; ", summary.GetFrameMsQuantile(0.5),
    summary.GetFrameMsQuantile(0.95), summary.GetFrameMsQuantile(1.0));
  return times +
    (budgetMs > 0 ? std::to_string(summary.GetFramesOverBudget()) + " of " + std::to_string(summary.GetNumberOfFrames()) +
          " frames over the " + FixedText(budgetMs, "%g") + " ms budget"
                  : std::string("no frame budget"));
}

SceneRequest ParseSceneRequest(const cli::ParsedArguments& args)
{
  SceneRequest request;
  for (const auto& [className, file] : ParsePairs(args.GetString("vessels"), "--vessels"))
  {
    request.Vessels.push_back({ className, file, nullptr, std::nullopt });
  }
  request.ScalpelFile = args.GetString("scalpel");
  request.Tip = ParseTipDefinition(args);
  const std::string method = args.GetString("method");
  request.Engine = ParseEngineSettings(method, args);
  request.CompareWithExact = method == "both";
  request.ComputeSurfaceDistance = !args.GetBoolean("noSurface");
  request.Tracking.Thresholds = ParseDangerThresholds(args);
  request.Tracking.FrameBudgetMs = ParseFrameBudgetMs(args);
  request.Tracking.HysteresisMm = ParseHysteresisMm(args);
  request.Tracking.Haptic.StiffnessNPerMm = args.GetNumber("hapticK");
  request.Tracking.Haptic.DampingNsPerMm = args.GetNumber("hapticC");
  if (args.IsSet("tumour"))
  {
    request.Tumours = TumourEntries(SplitList(args.GetString("tumour"), ','), "--tumour");
  }
  request.Tracking.Margin = ParseMarginSettings(args, !request.Tumours.empty());
  return request;
}

SceneRequest ParseRecordedSceneRequest(const cli::ParsedArguments& args)
{
  SceneRequest request = ParseSceneRequest(args);
  request.RepairVessels = args.GetBoolean("repair");
  std::vector<std::string> classes;
  for (const NamedMesh& vessel : request.Vessels)
  {
    classes.push_back(vessel.ClassName);
  }
  CheckFramesCsvColumns(classes, !request.Tumours.empty());
  return request;
}

std::vector<std::string> SceneInputFiles(const SceneRequest& request)
{
  std::vector<std::string> inputs = { request.ScalpelFile, request.LiverFile };
  if (!request.ScalpelFile.empty())
  {
    inputs.push_back(ScalpelDefinitionFileFor(request.ScalpelFile));
  }
  for (const std::vector<NamedMesh>* meshes : { &request.Vessels, &request.Tumours })
  {
    for (const NamedMesh& mesh : *meshes)
    {
      inputs.push_back(mesh.FileName);
    }
  }
  return inputs;
}
} // namespace vp
