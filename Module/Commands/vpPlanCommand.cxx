// vesselproximity plan: a straight approach to a target planned before any tracking: the poses that
// advance the instrument along it (plan.csv, a pose file track replays), the whole instrument's
// closest approach to each vessel class on the way and the safest direction of a cone (plan.json),
// and a picture of it (plan.png).
#include "vpApproachPlanFile.h"
#include "vpApproachPlanner.h"
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpDefaultScalpel.h"
#include "vpInputError.h"
#include "vpModelsFile.h"
#include "vpOutputFile.h"
#include "vpPlanPicture.h"
#include "vpPointCsv.h"
#include "vpQuantile.h"
#include "vpRunFolder.h"
#include "vpTrackingOptions.h"
#include "vpVirtualDisplay.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{
/// The structure --target names, or a refusal that lists the names the folder has.
const ModelStructure& FindTarget(const ModelsFile& models, const std::string& name)
{
  if (const ModelStructure* target = models.Find(name))
  {
    return *target;
  }
  std::string names;
  for (const ModelStructure& s : models.Structures)
  {
    names += (names.empty() ? "" : ", ") + s.Name;
  }
  throw InputError("--target", "'" + Printable(name) + "' is not in " + models.FileName + " (it has: " + names + ")");
}

/// The scene of the plan: every vessel of the folder (the target aside), the target as the tumour
/// whose depth the tip reaches, the liver to be shown, the scalpel; the exact engine.
/// A vessel class or tumour of the scene, to be read from its file.
NamedMesh MeshOf(const std::string& name, const std::string& file)
{
  NamedMesh mesh;
  mesh.ClassName = name;
  mesh.FileName = file;
  return mesh;
}

SceneRequest PlanSceneRequest(const ModelsFile& models, const ModelStructure& target, const cli::ParsedArguments& args)
{
  SceneRequest request;
  for (const ModelStructure& s : models.Structures)
  {
    if (s.Role == ModelRole::Vessel && s.Name != target.Name)
    {
      request.Vessels.push_back(MeshOf(s.ClassName, s.File));
    }
    if (s.Role == ModelRole::Liver && request.LiverFile.empty() && s.Name != target.Name)
    {
      request.LiverFile = s.File;
    }
  }
  if (request.Vessels.empty())
  {
    throw InputError(models.FileName, "lists no vessel besides the target: there is nothing to keep the instrument away from");
  }
  request.Tumours.push_back(MeshOf(target.Name, target.File));
  request.ScalpelFile = args.GetString("scalpel");
  request.Tip = ParseTipDefinition(args);
  request.Engine.Method = "exact";
  request.Engine.RangeMm = args.GetNumber("range");
  request.Tracking.Margin.MarginMm = std::min(args.GetNumber("marginMm"), MarginSettings::MaximumMm);
  request.Tracking.Margin.NearBandMm = request.Tracking.Margin.MarginMm;
  return request;
}

ApproachPlanRequest ParsePlanRequest(const cli::ParsedArguments& args, const ModelStructure& target)
{
  ApproachPlanRequest plan;
  plan.TargetName = target.Name;
  plan.TargetCentreMm = target.CentroidMm;
  if (args.IsSet("entry"))
  {
    plan.EntryMm = ParsePoint(args.GetString("entry"), "--entry");
  }
  if (args.IsSet("fromDirection"))
  {
    plan.DirectionLps = ParsePoint(args.GetString("fromDirection"), "--from-direction");
  }
  if (args.IsSet("standOffMm"))
  {
    plan.StandOffMm = args.GetNumber("standOffMm");
  }
  plan.StepMm = args.GetNumber("stepMm");
  plan.MarginMm = args.GetNumber("marginMm");
  plan.SearchDeg = args.GetNumber("searchDeg");
  plan.SearchStepDeg = args.GetNumber("searchStepDeg");
  ApproachPlanner::CheckSettings(plan); // refused before anything is read
  return plan;
}

std::string PointText(const std::array<double, 3>& p, const char* format = "%.2f")
{
  return "(" + FixedText(p[0], format) + ", " + FixedText(p[1], format) + ", " + FixedText(p[2], format) + ")";
}

void PrintApproach(const PlannedApproach& a)
{
  std::printf("  %-16s %12s %8s %12s  %s\n", "class", "closest mm", "at pose", "inside mm", "vessel point (LPS mm)");
  for (const ClassApproach& c : a.Classes)
  {
    std::printf("  %-16s %12s %8s %12s  %s\n", c.ClassName.c_str(), c.InRange ? FixedText(c.ClosestMm, "%.3f").c_str() : "out of range",
      c.InRange ? std::to_string(c.Step).c_str() : "", c.PenetrationDepthMm > 0.0 ? FixedText(c.PenetrationDepthMm, "%.3f").c_str() : "",
      c.InRange ? PointText({ c.PointMm[0], c.PointMm[1], c.PointMm[2] }).c_str() : "");
  }
}

void PrintPlan(const ApproachPlan& plan, const std::string& outDir, bool picture, const std::string& replay)
{
  const PlannedApproach& a = plan.Asked;
  std::printf("approach to %s from %s along %s: %zu poses %g mm apart, the tip %g mm past the target's surface at %s\n",
    plan.TargetName.c_str(), PointText(a.EntryMm).c_str(), PointText(a.Direction, "%.4f").c_str(), a.Poses.size(), plan.StepMm,
    plan.MarginMm, PointText(a.SurfacePointMm).c_str());
  PrintApproach(a);
  if (a.TipTargetSignedMm)
  {
    std::printf("  the tip ends %.3f mm %s the target's surface\n", std::abs(*a.TipTargetSignedMm), *a.TipTargetSignedMm < 0.0 ? "inside" : "outside");
  }
  std::printf("  clearance %s\n", a.ClearanceClass.empty() ? ("over " + FixedText(plan.RangeMm, "%g") + " mm (no vessel in range)").c_str()
                                                           : (FixedText(a.ClearanceMm, "%.3f") + " mm to " + a.ClearanceClass).c_str());
  if (plan.Safest)
  {
    const PlannedApproach& s = *plan.Safest;
    std::printf("safest of %d direction(s) within %g deg (%d missed the target): ", plan.DirectionsSearched + 1, plan.SearchDeg,
      plan.DirectionsMissing);
    if (s.AngleFromAskedDeg == 0.0)
    {
      std::printf("the asked one\n");
    }
    else
    {
      std::printf("from %s along %s, %.1f deg off: clearance %.3f mm%s%s (%+.3f mm)\n", PointText(s.EntryMm).c_str(),
        PointText(s.Direction, "%.4f").c_str(), s.AngleFromAskedDeg, s.ClearanceMm, s.ClearanceClass.empty() ? "" : " to ",
        s.ClearanceClass.c_str(), s.ClearanceMm - a.ClearanceMm);
      PrintApproach(s);
    }
  }
  std::printf("  pose median %.3f ms, p95 %.3f ms, max %.3f ms over %zu poses\n", Quantile(plan.StepMs, 0.5),
    Quantile(plan.StepMs, 0.95), Quantile(plan.StepMs, 1.0), plan.StepMs.size());
  std::printf("wrote %s/plan.csv, plan.json%s%s\nreplay: %s\n", outDir.c_str(), plan.Safest ? ", safest.csv" : "",
    picture ? ", plan.png" : "", replay.c_str());
}

/// The track command that replays the plan, as the user would type it: the same vessels, scalpel,
/// tip and range, the target as its tumour.
std::string ReplayCommand(
  const SceneRequest& request, const cli::ParsedArguments& args, const std::string& outDir, const std::string& scalpelFile)
{
  std::string vessels;
  for (const NamedMesh& v : request.Vessels)
  {
    vessels += (vessels.empty() ? "" : ",") + v.ClassName + "=" + v.FileName;
  }
  std::string same;
  for (const char* option : { "tip", "axis", "range" })
  {
    same += args.IsSet(option) ? std::string(" --") + option + " " + args.GetString(option) : "";
  }
  return "vesselproximity track --vessels " + vessels + " --scalpel " + scalpelFile + same + " --poses " + outDir +
    "/plan.csv --tumour " + request.Tumours.front().ClassName + "=" + request.Tumours.front().FileName + " -o " + outDir + "/track";
}

/// The files the plan reads: never removed or written over.
std::vector<std::string> PlanInputs(const ModelsFile& models, const SceneRequest& request)
{
  std::vector<std::string> inputs = SceneInputFiles(request);
  inputs.push_back(models.FileName);
  return inputs;
}
} // namespace

cli::ModuleDescription DescribePlanCommand()
{
  using cli::FormatNumber;
  using cli::ParameterType;
  const ApproachPlanRequest defaults;
  return cli::ModuleDescription::Subcommand("vesselproximity plan",
    "plan a straight approach to a target: its poses, the instrument's clearance on the way, the safest direction",
    "Plans a straight approach of the instrument (its axis on the line, tip first) to a target of a models folder, "
    "before any tracking, and writes OUTDIR/plan.csv (a pose every --step-mm from the entry to --margin-mm past "
    "the target's surface: track --poses replays it), OUTDIR/plan.json (the whole instrument's closest approach to "
    "each vessel class on the way, at which pose and where; with --search-deg, the safest direction of the cone) "
    "and OUTDIR/plan.png. The numbers are track's: the same logic computes them from the same poses.",
    {
      { "Inputs", "",
        {
          Option(ParameterType::Directory, "models",
            "A models folder (vesselproximity models writes one; models.json lists its structures): its vessels are "
            "measured, its liver shown, its --target approached.")
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("DIR")
            .SetRequired(),
          Option(ParameterType::String, "target", "The structure approached, by its id in models.json (tumour_03).")
            .SetPlaceholder("NAME")
            .SetLogicName("TargetName")
            .SetRequired(),
          OutputFolderOption("The plan's folder: plan.csv, plan.json, plan.png.").SetRequired(),
        } },
      { "Approach", "",
        {
          Option(ParameterType::String, "entry",
            "Where the tip starts (LPS mm, outside the target): the approach runs from it to the target's centre.")
            .SetPlaceholder("X,Y,Z")
            .SetLogicName("EntryMm"),
          Option(ParameterType::String, "from-direction",
            "Instead of --entry, the direction the instrument travels (LPS, any length): the line along it through the "
            "target's centre, from --stand-off-mm before the target's surface.")
            .SetPlaceholder("X,Y,Z")
            .SetLogicName("DirectionLps"),
          Option(ParameterType::Double, "stand-off-mm",
            "With --from-direction: how far before the target's surface the tip starts. Default: outside the liver's "
            "box (10 mm beyond it) when the folder has a liver, else " + FormatNumber(ApproachPlanRequest::DefaultStandOffMm) + " mm.")
            .SetPlaceholder("MM")
            .SetLogicName("StandOffMm"),
          Option(ParameterType::Double, "step-mm", "The distance between two poses.")
            .SetPlaceholder("MM")
            .SetDefault(FormatNumber(defaults.StepMm))
            .SetLogicName("StepMm"),
          Option(ParameterType::Double, "margin-mm", "How far past the target's surface the tip goes (as track's --margin-mm), 0 to 50.")
            .SetPlaceholder("MM")
            .SetDefault(FormatNumber(defaults.MarginMm))
            .SetLogicName("MarginMm"),
          Option(ParameterType::Double, "search-deg",
            "Also try every direction within this angle of the asked one (rings --search-step-deg apart, each aimed at "
            "the target's centre from as far away) and report the safest: the one whose smallest whole-instrument "
            "distance to any vessel is largest. 0: no search.")
            .SetPlaceholder("DEG")
            .SetDefault(FormatNumber(defaults.SearchDeg))
            .SetLogicName("SearchDeg"),
          Option(ParameterType::Double, "search-step-deg", "The angle between the search's rings, and between directions around a ring.")
            .SetPlaceholder("DEG")
            .SetDefault(FormatNumber(defaults.SearchStepDeg))
            .SetLogicName("SearchStepDeg"),
        } },
      { "Scalpel", "",
        [] {
          std::vector<cli::Parameter> scalpel = { Option(ParameterType::File, "scalpel",
            "The instrument's surface model (STL, VTK, VTP or OBJ), in model coordinates. Default: the built-in CUSA "
            "handpiece, written to OUTDIR/scalpel/ for the replay.")
                                                    .SetChannel(cli::Channel::Input) };
          for (const cli::Parameter& p : ScalpelTipOptions())
          {
            scalpel.push_back(p);
          }
          return scalpel;
        }() },
      { "Distance engine", "",
        { Option(ParameterType::Double, "range", "Vessels further than this from the instrument are out of range (as track's --range).")
            .SetPlaceholder("MM")
            .SetDefault(FormatNumber(vtkVesselDistanceEngine::DefaultRangeMm))
            .SetLogicName("RangeMm") } },
      { "Picture", "", { Switch("no-picture", "Skip plan.png (it needs a display, or Xvfb, which is started when there is none).") } },
    });
}

int RunPlanCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  const std::string outDir = args.GetString("output");
  RunFolder run(outDir, "plan.json");
  const ModelsFile models = ReadModelsFile(args.GetString("models"));
  if (models.Space == "RAS")
  {
    throw InputError(models.FileName, "its surfaces are in RAS; plan measures in LPS (write them with models --space LPS)");
  }
  const ModelStructure& target = FindTarget(models, args.GetString("target"));
  ApproachPlanRequest planRequest = ParsePlanRequest(args, target);
  const SceneRequest request = PlanSceneRequest(models, target, args);
  const bool picture = !args.GetBoolean("noPicture");
  VirtualDisplay display;
  if (picture && !display.Ensure())
  {
    throw InputError("plan.png", display.GetProblem() + " (--no-picture skips the picture)");
  }
  run.SetInputs(PlanInputs(models, request));
  vtkSmartPointer<vtkVesselProximityLogic> proximity = module.CreateLogic();
  StageProgress progress("plan", proximity);
  const OpenedScene scene = proximity->OpenScene(request);
  progress.Finish();
  planRequest.Target = scene.Tumours.front().Mesh;
  if (scene.Liver)
  {
    std::array<double, 6> box;
    scene.Liver->GetBounds(box.data());
    planRequest.LiverBoundsMm = box;
  }
  ApproachPlanner planner(proximity);
  planner.SetProgress([&progress](std::size_t done, std::size_t expected) { progress.FramesDone(done, expected); });
  const ApproachPlan plan = planner.Plan(planRequest);
  progress.Finish();
  ReportOpenedScene("plan", proximity, scene, request.ScalpelFile);
  run.Begin();
  std::string scalpelFile = request.ScalpelFile;
  if (scalpelFile.empty())
  {
    WriteDefaultScalpel(run.Folder("scalpel"));
    scalpelFile = outDir + "/scalpel/CusaHandpiece.stl";
  }
  WriteFileAtomically(run.File("plan.csv"), FormatApproachPosesCsv(plan.Asked));
  if (plan.Safest)
  {
    WriteFileAtomically(run.File("safest.csv"), FormatApproachPosesCsv(*plan.Safest));
  }
  if (picture)
  {
    progress.Stage("drawing plan.png");
    RenderPlanPicture(module, { proximity, scene.Liver, planRequest.Target, &plan, run.File("plan.png") });
    progress.Finish();
  }
  nlohmann::ordered_json json = ApproachPlanJson(plan);
  json["models"] = models.FileName;
  json["scalpel"] = request.ScalpelFile.empty() ? "built-in CUSA handpiece (" + scalpelFile + ")" : request.ScalpelFile;
  json["scalpel_tip_source"] = proximity->GetScalpel()->GetTipSource();
  WriteFileAtomically(run.File("plan.json"), json.dump(2) + "\n");
  run.Commit(); // the folder holds this plan whole, or the previous one as it was
  PrintPlan(plan, outDir, picture, ReplayCommand(request, args, outDir, scalpelFile));
  return 0;
}
} // namespace vp
