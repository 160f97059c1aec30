// vesselproximity demo: the main job on the built-in liver phantom, no data needed.
#include "vpArguments.h"
#include "vpCommands.h"
#include "vpDemoPipeline.h"
#include "vpOutputOptions.h"
#include "vpInputError.h"
#include "vpTrackingOptions.h"
#include "vpJsonFile.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{
} // namespace

void PrintDemoTable(const DemoReport& report)
{
  const nlohmann::json summary(report.Summary); // by class name, as the table lists them
  std::printf("\nVesselProximity demo: %d frames, method %s\n", report.Frames, report.Method.c_str());
  if (!report.MethodNote.empty())
  {
    std::printf("  note: %s\n", report.MethodNote.c_str());
  }
  std::printf("  %-78s %8s\n", "stage", "seconds");
  double total = 0;
  for (const auto& [name, seconds] : report.StageSeconds)
  {
    std::printf("  %-78s %8.2f\n", name.c_str(), seconds);
    total += seconds;
  }
  std::printf("  %-78s %8.2f\n", "total", total);
  std::printf("\n  %-16s %18s %18s\n", "vessel class", "closest tip (mm)", "closest surface");
  for (const auto& [name, entry] : summary.at("classes").items())
  {
    const auto& tip = entry.at("tip_minimum");
    const auto surface = entry.value("surface_minimum", nlohmann::json());
    std::printf("  %-16s %18s %18s\n", name.c_str(),
      tip.is_null() ? "out of range"
                    : (FixedText(tip.at("distance_mm").get<double>(), "%.2f") + (tip.at("inside").get<bool>() ? " inside" : "")).c_str(),
      surface.is_null() ? "-" : FixedText(surface.at("distance_mm").get<double>(), "%.2f").c_str());
  }
  const auto& instrument = summary.at("worst_instrument_level");
  std::printf("  worst level %s (tip %s, instrument %s); %zu level changes:", summary.at("worst_level").get<std::string>().c_str(),
    summary.at("worst_tip_level").get<std::string>().c_str(),
    instrument.is_null() ? "not measured" : instrument.get<std::string>().c_str(), summary.at("level_changes").size());
  for (const auto& change : summary.at("level_changes"))
  {
    std::printf(" %s", change.at("to").get<std::string>().c_str());
  }
  std::printf("\n");
  const auto& frameMs = summary.at("frame_ms");
  std::printf("  frame median %.3f ms, p95 %.3f ms, max %.3f ms; %d of %d frames over the %g ms budget\n",
    frameMs.at("median").get<double>(), frameMs.at("p95").get<double>(), frameMs.at("max").get<double>(),
    summary.at("frames_over_budget").get<int>(), summary.at("frames").get<int>(), frameMs.at("budget").get<double>());
  if (summary.contains("comparison"))
  {
    std::printf("  z-buffer against exact: largest difference %.3f mm (bound %.3f mm), %d answer(s) outside the bound\n",
      summary.at("comparison").at("max_abs_difference_mm").get<double>(), summary.at("error_bound_mm").get<double>(),
      summary.at("comparison").at("outside_bound").get<int>());
  }
  std::printf("\n  outputs in %s: frames.csv, summary.json, distance.png, poses.csv, models/, dicom/, scalpel/\n",
    report.OutDir.c_str());
  if (!report.Screenshots.empty())
  {
    std::printf("  %zu screenshots in %s/screenshots/\n", report.Screenshots.size(), report.OutDir.c_str());
  }
  else if (!report.ScreenshotProblem.empty())
  {
    std::printf("  no screenshots: %s\n", report.ScreenshotProblem.c_str());
  }
}

cli::ModuleDescription DescribeDemoCommand()
{
  return cli::ModuleDescription::Subcommand("vesselproximity demo",
    "the main job on the built-in liver phantom: DICOM, models, tracked CUSA, both engines, report",
    "The main job on a built-in phantom, no data needed: a procedural liver labelmap with three vessel trees written "
    "as DICOM series, its vessel models, the built-in CUSA handpiece, a trajectory that approaches and passes the "
    "vessels, both distance engines on every frame, and the outputs in OUTDIR: dicom/, models/, scalpel/, "
    "poses.csv, frames.csv, summary.json, distance.png and screenshots/ of the key frames (rendered off-screen; Xvfb "
    "is started when there is no display).",
    { { "Options", "",
      { OutputFolderOption("The run's folder.").SetDefault("vesselproximity-demo"),
        Switch("no-screenshots", "Skip the screenshots."), FrameBudgetOption(),
        Switch("live",
          "Track live: a tracker server on loopback streams the trajectory over OpenIGTLink at its own times, through the "
          "live path and back (summary.json adds the latency).") } },
      OutputOptions(OutputForDemo) });
}

int RunDemoCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  const ChosenOutputs chosen(args, OutputForDemo, "demo");
  const DemoReport report = RunDemoPipeline(module, args.GetString("output"), !args.GetBoolean("noScreenshots"),
    ParseFrameBudgetMs(args), args.GetBoolean("live"), chosen.Get());
  chosen.SayProblems();
  PrintDemoTable(report);
  return 0;
}
} // namespace vp
