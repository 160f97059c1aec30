// vesselproximity batch: a cohort of cases from a manifest, each computed whole into its folder,
// then one table and one picture for them all.
#include "vpArguments.h"
#include "vpCohortRun.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpModuleServices.h"
#include "vtkVesselProximityLogic.h"

#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace vp
{
namespace
{
/// --shard K/N, both whole numbers.
void ParseShard(const std::string& text, CohortRequest& request)
{
  const std::size_t slash = text.find('/');
  char* end = nullptr;
  const long k = std::strtol(text.c_str(), &end, 10);
  const bool kWhole = slash != std::string::npos && end == text.c_str() + slash && slash > 0;
  const long n = kWhole ? std::strtol(text.c_str() + slash + 1, &end, 10) : 0;
  if (!kWhole || *end != '\0' || end == text.c_str() + slash + 1 || k < 1 || n < 1 || k > n || n > 100000)
  {
    throw InputError("--shard", "expected K/N with 1 <= K <= N (this run's share of the cases), got '" + Printable(text) + "'");
  }
  request.ShardIndex = static_cast<int>(k);
  request.ShardCount = static_cast<int>(n);
}
} // namespace

cli::ModuleDescription DescribeBatchCommand()
{
  using cli::ParameterType;
  return cli::ModuleDescription::Subcommand("vesselproximity batch",
    "a cohort: each case of a manifest from its segmentation to its distances, then one table for them all",
    "MANIFEST.csv names a case per line under a header: case,segmentation[,poses][,tips][,plan][,scalpel] (paths from "
    "the manifest's folder; plan: the tumours' surfaces, ';' between them). Each case is computed into OUTDIR/<case>/: "
    "models/ as models writes them, with poses frames.csv, summary.json and distance.png as track writes them (the "
    "plan's margins measured), with tips distance.json (exact), and case.json. A case folder is whole or as it was: "
    "a run again resumes, skipping the cases whose folders are whole with the same inputs. OUTDIR/cohort.csv has a "
    "row per case and class (case,class,tip_min_mm,surface_min_mm,penetration_max_mm3,breach_frames,margin_min_mm,"
    "error), cohort.png each class's closest tip approach per case. A failed case is its row's error; the run then "
    "exits 1.",
    {
      { "Cohort", "",
        {
          cli::Parameter(ParameterType::File, "manifest")
            .SetIndex(0)
            .SetRequired()
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("MANIFEST.csv")
            .SetDescription("The cases, a line each, under a header naming the columns."),
          OutputFolderOption("The cohort's folder: a folder per case, cohort.csv and cohort.png.").SetRequired(),
          Option(ParameterType::Integer, "jobs", "Cases computed at once, each on a thread of its own.")
            .SetFlag("j")
            .SetPlaceholder("N")
            .SetDefault("1")
            .SetLogicName("Jobs"),
          Option(ParameterType::String, "shard",
            "This run's share: the cases at positions K, K+N, K+2N... (from 1) of the manifest, for a cluster's array "
            "job (Slurm: --shard $SLURM_ARRAY_TASK_ID/N); it writes OUTDIR/cohort-K-of-N.csv, and a run with --merge "
            "gathers the shards.")
            .SetPlaceholder("K/N")
            .SetLogicName("Shard"),
          Option(ParameterType::String, "merge",
            "Compute nothing: take each case of the manifest from the first of these cohort folders that holds it whole "
            "with the same inputs (a case in none is a row with its error), and write OUTDIR/cohort.csv and cohort.png.")
            .SetPlaceholder("DIR[,DIR...]")
            .SetLogicName("MergeFolders"),
        } },
    });
}

int RunBatchCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  CohortRequest request;
  request.Manifest = args.GetString("manifest");
  request.OutputFolder = args.GetString("output");
  request.Jobs = args.GetInteger("jobs");
  if (args.IsSet("shard"))
  {
    ParseShard(args.GetString("shard"), request);
  }
  if (args.IsSet("merge"))
  {
    for (const std::string& folder : SplitList(args.GetString("merge"), ','))
    {
      if (folder.empty())
      {
        throw InputError("--merge", "an empty folder in '" + Printable(args.GetString("merge")) + "'");
      }
      request.MergeFolders.push_back(folder);
    }
  }
  std::mutex said; // the workers' lines one at a time
  const CohortReport report = RunCohort(
    request, [&module]() { return module.CreateLogic(); },
    [&](const std::string& name, const std::string& stage) {
      std::lock_guard<std::mutex> lock(said);
      std::fprintf(stderr, "batch: %s: %s\n", name.c_str(), stage.c_str());
    },
    [&](const CohortCaseResult& r, int done, int total) {
      std::lock_guard<std::mutex> lock(said);
      if (!r.Error.empty())
      {
        std::fprintf(stderr, "batch: [%d/%d] %s failed: %s\n", done, total, r.Case.c_str(), r.Error.c_str());
      }
      else
      {
        std::fprintf(stderr, "batch: [%d/%d] %s %s (%d frames, %d tips)%s\n", done, total, r.Case.c_str(),
          r.Resumed ? "whole already" : "done", r.Frames, r.Tips,
          r.Resumed ? "" : (" in " + FixedText(r.Ms / 1000.0, "%.1f") + " s").c_str());
      }
    });
  if (report.Interrupted)
  {
    std::fprintf(stderr, "batch: interrupted: the whole cases are kept, a run again resumes from them\n");
    return 1;
  }
  std::printf("%d case(s): %d computed, %d whole already, %d failed, in %.1f s\n", static_cast<int>(report.Results.size()),
    report.Computed, report.Resumed, report.Failed, report.Ms / 1000.0);
  std::printf("wrote %s/%s%s\n", request.OutputFolder.c_str(), report.Files[0].c_str(),
    report.Files.size() > 1 ? (", " + report.Files[1]).c_str() : "");
  return report.Failed > 0 ? 1 : 0;
}
} // namespace vp
