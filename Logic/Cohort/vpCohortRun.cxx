#include "vpCohortRun.h"

#include "vpClock.h"
#include "vpDangerBands.h"
#include "vpDecimal.h"
#include "vpDistancePlot.h"
#include "vpInputError.h"
#include "vpOutputFile.h"
#include "vpRunFolder.h"
#include "vpSegmentationImport.h"
#include "vpSignalHold.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <thread>

namespace vp
{
namespace
{
std::string Number(const std::optional<double>& value)
{
  return value ? FixedText(*value, "%.4f") : std::string();
}

std::string CsvCell(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (const char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + "\"";
}
} // namespace

void CohortRequest::Validate() const
{
  if (this->Jobs < 1 || this->Jobs > 256)
  {
    throw ParameterError("Jobs", "expected 1 to 256 cases at once, got " + std::to_string(this->Jobs));
  }
  if (this->ShardCount < 1 || this->ShardIndex < 1 || this->ShardIndex > this->ShardCount)
  {
    throw ParameterError("Shard", "expected K/N with 1 <= K <= N, got " + std::to_string(this->ShardIndex) + "/" +
        std::to_string(this->ShardCount));
  }
  if (!this->MergeFolders.empty() && this->ShardCount > 1)
  {
    throw ParameterError("Shard", "a merge gathers every shard: it takes no shard of its own");
  }
}

std::string CohortCsv(const std::vector<CohortCaseResult>& results)
{
  std::string csv = "case,class,tip_min_mm,surface_min_mm,penetration_max_mm3,breach_frames,margin_min_mm,error\n";
  for (const CohortCaseResult& r : results)
  {
    if (!r.Error.empty() || r.Classes.empty())
    {
      csv += r.Case + ",,,,,,," + CsvCell(r.Error.empty() ? std::string("no vessel class") : r.Error) + "\n";
      continue;
    }
    for (const CohortClassRow& row : r.Classes)
    {
      csv += r.Case + "," + row.ClassName + "," + Number(row.TipMinMm) + "," + Number(row.SurfaceMinMm) + "," +
        Number(row.PenetrationMaxMm3) + "," + std::to_string(row.BreachFrames) + "," + Number(r.MarginMinMm) + ",\n";
    }
  }
  return csv;
}

void WriteCohortPlot(const std::vector<CohortCaseResult>& results, const std::string& fileName)
{
  std::vector<double> cases;
  std::vector<PlotSeries> series;
  for (std::size_t i = 0; i < results.size(); ++i)
  {
    cases.push_back(static_cast<double>(i + 1));
    for (const CohortClassRow& row : results[i].Classes)
    {
      auto it = std::find_if(series.begin(), series.end(), [&](const PlotSeries& s) { return s.Name == row.ClassName; });
      if (it == series.end())
      {
        series.push_back({ row.ClassName, ClassDisplayColour(row.ClassName, static_cast<int>(series.size())),
          std::vector<double>(results.size(), std::numeric_limits<double>::quiet_NaN()) });
        it = series.end() - 1;
      }
      it->ValuesMm[i] = row.TipMinMm.value_or(std::numeric_limits<double>::quiet_NaN());
    }
  }
  DistancePlotOptions options;
  options.Title = "closest tip approach per case (" + std::to_string(results.size()) + " cases, cohort.csv order)";
  options.XLabel = "case";
  options.YLabel = "tip minimum (mm)";
  options.WholeXTicks = true;
  WriteDistancePlotPng(fileName, cases, series, DangerBands(DangerThresholds(), true), options);
}

CohortReport RunCohort(const CohortRequest& request, const CohortLogicFactory& makeLogic, const CohortStageObserver& stages,
  const CohortCaseObserver& observer)
{
  request.Validate();
  const double start = NowMs();
  const std::vector<CohortCase> manifest = ReadCohortManifest(request.Manifest);
  std::vector<CohortCase> cases;
  for (std::size_t i = 0; i < manifest.size(); ++i)
  {
    if (static_cast<int>(i % static_cast<std::size_t>(request.ShardCount)) == request.ShardIndex - 1)
    {
      cases.push_back(manifest[i]);
    }
  }
  std::error_code made;
  std::filesystem::create_directories(request.OutputFolder, made);
  if (made || !std::filesystem::is_directory(request.OutputFolder))
  {
    throw InputError(request.OutputFolder, "cannot be made a folder" + (made ? ": " + made.message() : std::string()));
  }
  const SignalHold hold; // the workers' case folders nest their holds in this one
  PrepareConcurrentImports();
  CohortReport report;
  report.Results.resize(cases.size());
  std::mutex told;
  int done = 0;
  const auto finish = [&](std::size_t i, CohortCaseResult result) {
    std::lock_guard<std::mutex> lock(told);
    report.Results[i] = std::move(result);
    ++done;
    if (observer)
    {
      observer(report.Results[i], done, static_cast<int>(cases.size()));
    }
  };
  if (!request.MergeFolders.empty())
  {
    for (std::size_t i = 0; i < cases.size(); ++i)
    {
      std::optional<CohortCaseResult> found;
      for (const std::string& folder : request.MergeFolders)
      {
        if ((found = CompletedCohortCase(cases[i], folder + "/" + cases[i].Name)))
        {
          break;
        }
      }
      CohortCaseResult missing;
      missing.Case = cases[i].Name;
      missing.Error = "not whole in any merged folder (not run, failed, or its inputs changed since)";
      finish(i, found ? std::move(*found) : missing);
    }
  }
  else
  {
    std::atomic<std::size_t> next{ 0 };
    const auto work = [&]() {
      for (std::size_t i = next++; i < cases.size(); i = next++)
      {
        if (RunFolder::SignalPending())
        {
          CohortCaseResult stopped;
          stopped.Case = cases[i].Name;
          stopped.Error = "interrupted";
          finish(i, stopped);
          continue;
        }
        const std::string folder = request.OutputFolder + "/" + cases[i].Name;
        std::optional<CohortCaseResult> earlier = CompletedCohortCase(cases[i], folder);
        finish(i, earlier ? std::move(*earlier) : RunCohortCase(cases[i], folder, request.Settings, makeLogic, stages));
      }
    };
    std::vector<std::thread> workers;
    for (int j = 1; j < std::min<int>(request.Jobs, static_cast<int>(cases.size())); ++j)
    {
      workers.emplace_back(work);
    }
    work();
    for (std::thread& t : workers)
    {
      t.join();
    }
  }
  for (const CohortCaseResult& r : report.Results)
  {
    report.Interrupted = report.Interrupted || r.Error == "interrupted";
    report.Resumed += r.Resumed ? 1 : 0;
    report.Computed += !r.Resumed && r.Error.empty() ? 1 : 0;
    report.Failed += r.Error.empty() ? 0 : 1;
  }
  if (!report.Interrupted)
  {
    if (request.ShardCount > 1)
    {
      const std::string name =
        "cohort-" + std::to_string(request.ShardIndex) + "-of-" + std::to_string(request.ShardCount) + ".csv";
      WriteFileAtomically(request.OutputFolder + "/" + name, CohortCsv(report.Results));
      report.Files = { name };
    }
    else
    {
      WriteFileAtomically(request.OutputFolder + "/cohort.csv", CohortCsv(report.Results));
      WriteCohortPlot(report.Results, request.OutputFolder + "/cohort.png");
      report.Files = { "cohort.csv", "cohort.png" };
    }
  }
  report.Ms = NowMs() - start;
  return report;
}
} // namespace vp
