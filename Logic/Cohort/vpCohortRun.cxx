#include "vpCohortRun.h"

#include "vpClock.h"
#include "vpDangerBands.h"
#include "vpDecimal.h"
#include "vpDistancePlot.h"
#include "vpPlotValues.h"
#include "vpVesselLabelTable.h"
#include "vpInputError.h"
#include "vpOutputFile.h"
#include "vpRunFolder.h"
#include "vpSegmentationImport.h"
#include "vpSignalHold.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

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

namespace
{
/// One batch at a time writes a cohort folder: an exclusive lock on OUT/.vesselproximity-batch.lock
/// (a shard's own, .vesselproximity-batch-K-of-N.lock: the shards of an array job write their
/// disjoint cases side by side), held for the run, the holder's process id in it for the one
/// turned away.
class CohortFolderLock
{
public:
  CohortFolderLock(const std::string& folder, int shard, int shards)
  {
    const std::string file = folder + "/.vesselproximity-batch" +
      (shards > 1 ? "-" + std::to_string(shard) + "-of-" + std::to_string(shards) : std::string()) + ".lock";
    this->Descriptor = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (this->Descriptor < 0)
    {
      throw InputError(folder, "cannot take its batch lock (" + file + ")");
    }
    if (::flock(this->Descriptor, LOCK_EX | LOCK_NB) != 0)
    {
      char holder[32] = "";
      const ssize_t n = ::pread(this->Descriptor, holder, sizeof holder - 1, 0);
      holder[n > 0 ? n : 0] = '\0';
      ::close(this->Descriptor);
      throw InputError(folder, std::string("another batch (process ") + (n > 0 ? holder : "?") +
        ") is writing this cohort folder; one at a time");
    }
    const std::string pid = std::to_string(::getpid());
    if (::ftruncate(this->Descriptor, 0) != 0 || ::pwrite(this->Descriptor, pid.data(), pid.size(), 0) < 0)
    {
      // The lock holds without the number: the one turned away is told "process ?".
    }
  }
  ~CohortFolderLock() { ::close(this->Descriptor); }
  CohortFolderLock(const CohortFolderLock&) = delete;
  CohortFolderLock& operator=(const CohortFolderLock&) = delete;

private:
  int Descriptor = -1;
};

/// Refuses a case whose input is one of the files the cohort writes beside its cases (a poses
/// file named cohort.png in OUTDIR), before anything is computed.
void RefuseInputsOverCohortFiles(const std::vector<CohortCase>& cases, const CohortRequest& request)
{
  namespace fs = std::filesystem;
  std::error_code e;
  const fs::path out = fs::weakly_canonical(request.OutputFolder, e);
  for (const CohortCase& c : cases)
  {
    std::vector<std::string> inputs = { c.Segmentation, c.Poses, c.Tips, c.Scalpel };
    for (const std::string& entry : c.Plan)
    {
      inputs.push_back(entry.substr(entry.find('=') == std::string::npos ? 0 : entry.find('=') + 1));
    }
    for (const std::string& input : inputs)
    {
      const fs::path path = input.empty() ? fs::path() : fs::weakly_canonical(input, e);
      if (!input.empty() && path.parent_path() == out && IsCohortFileName(path.filename().string()))
      {
        throw InputError(request.Manifest, "line " + std::to_string(c.Line) + ": case '" + c.Name + "' reads " + input +
          ", a file the cohort writes in " + request.OutputFolder + ": an output never replaces an input");
      }
    }
  }
}

/// Makes the cohort's folder; refuses one that holds the manifest (the run's tables would sit
/// beside, or over, its input) and merge folders that are not folders.
void PrepareCohortFolder(const CohortRequest& request)
{
  struct stat out{}, beside{};
  const std::filesystem::path manifest(request.Manifest);
  const std::string parent = manifest.has_parent_path() ? manifest.parent_path().string() : std::string(".");
  if (::stat(request.OutputFolder.c_str(), &out) == 0 && ::stat(parent.c_str(), &beside) == 0 && out.st_dev == beside.st_dev &&
    out.st_ino == beside.st_ino)
  {
    throw InputError(request.OutputFolder, "holds the manifest " + request.Manifest +
      ": the cohort's folder takes its cases and tables only (give another -o)");
  }
  for (const std::string& folder : request.MergeFolders)
  {
    if (!std::filesystem::is_directory(folder))
    {
      throw InputError(folder, "is no folder to merge from");
    }
  }
  std::error_code made;
  std::filesystem::create_directories(request.OutputFolder, made);
  if (made || !std::filesystem::is_directory(request.OutputFolder))
  {
    throw InputError(request.OutputFolder, "cannot be made a folder" + (made ? ": " + made.message() : std::string()));
  }
}

/// MemAvailable from /proc/meminfo, bytes; 0 when it cannot be read.
double AvailableMemoryBytes()
{
  std::ifstream in("/proc/meminfo");
  for (std::string key; in >> key;)
  {
    double kb = 0.0;
    std::string unit;
    in >> kb >> unit;
    if (key == "MemAvailable:")
    {
      return kb * 1024.0;
    }
  }
  return 0.0;
}
} // namespace

int CohortJobsFor(int requested, std::size_t cases, std::string& capped)
{
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const double memory = AvailableMemoryBytes();
  const int byMemory = memory > 0.0 ? std::max(1, static_cast<int>(memory / CohortCaseMemoryBytes)) : requested;
  const int jobs = std::max(1, std::min({ requested, cores, byMemory, static_cast<int>(std::max<std::size_t>(1, cases)) }));
  capped.clear();
  if (jobs < requested && jobs < static_cast<int>(cases))
  {
    char text[160];
    std::snprintf(text, sizeof text, "-j %d capped at %d: %d cores, %.1f GiB of memory available at about %.0f GiB a case",
      requested, jobs, cores, memory / (1 << 30), CohortCaseMemoryBytes / (1 << 30));
    capped = text;
  }
  return jobs;
}

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

namespace
{
/// The vessel classes a cohort reports on: the label table's (not the liver, which no tip is
/// measured against, nor the tumours, each a row of its own), then any other class a case had,
/// in the order met.
std::vector<std::string> CohortClasses(const std::vector<CohortCaseResult>& results)
{
  std::vector<std::string> classes;
  const VesselLabelTable table = VesselLabelTable::Default();
  for (const std::string& c : table.Classes())
  {
    if (table.RoleOf(c) == ModelRole::Vessel)
    {
      classes.push_back(c);
    }
  }
  for (const CohortCaseResult& r : results)
  {
    for (const CohortClassRow& row : r.Classes)
    {
      if (std::find(classes.begin(), classes.end(), row.ClassName) == classes.end())
      {
        classes.push_back(row.ClassName);
      }
    }
  }
  return classes;
}

const CohortClassRow* RowOf(const CohortCaseResult& r, const std::string& className)
{
  const auto it = std::find_if(r.Classes.begin(), r.Classes.end(), [&](const CohortClassRow& row) { return row.ClassName == className; });
  return it == r.Classes.end() ? nullptr : &*it;
}
} // namespace

std::string CohortCsv(const std::vector<CohortCaseResult>& results)
{
  std::string csv = "case,class,tip_min_mm,surface_min_mm,penetration_max_mm3,breach_frames,margin_min_mm,error\n";
  const std::vector<std::string> classes = CohortClasses(results);
  for (const CohortCaseResult& r : results)
  {
    if (!r.Error.empty() || r.Classes.empty())
    {
      csv += r.Case + ",,,,,,," + CsvCell(r.Error.empty() ? std::string("no vessel class") : r.Error) + "\n";
      continue;
    }
    for (const std::string& name : classes)
    {
      const CohortClassRow* row = RowOf(r, name);
      if (!row)
      {
        // A row all the same, so that a patient without an artery reads as one, not as a gap.
        csv += r.Case + "," + name + ",,,,,," + CsvCell("no " + name + " in this case's segmentation") + "\n";
        continue;
      }
      csv += r.Case + "," + row->ClassName + "," + Number(row->TipMinMm) + "," + Number(row->SurfaceMinMm) + "," +
        Number(row->PenetrationMaxMm3) + "," + std::to_string(row->BreachFrames) + "," + Number(r.MarginMinMm) + ",\n";
    }
    // Then each tumour, its own margin: the case's smallest above hides which tumour it was.
    for (const CohortTumourRow& t : r.Tumours)
    {
      csv += r.Case + "," + CsvCell(t.Id) + ",," + Number(t.SurfaceMinMm) + ",,," + Number(t.MarginMinMm) + ",\n";
    }
  }
  return csv;
}

namespace
{
/// A series over the cases, NaN (no point) where a case has no value.
PlotSeries CaseSeries(const std::string& name, const Rgb& colour, std::size_t cases, LineStyle style)
{
  PlotSeries s{ name, colour, std::vector<double>(cases, std::numeric_limits<double>::quiet_NaN()) };
  s.Style = style;
  return s;
}
} // namespace

void WriteCohortPlot(const std::vector<CohortCaseResult>& results, const std::string& fileName)
{
  const double none = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> cases;
  std::vector<PlotSeries> series;
  DistancePlotOptions options;
  const std::vector<std::string> classes = CohortClasses(results);
  double largestVolumeMm3 = 0.0;
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const Rgb colour = ClassDisplayColour(classes[c], static_cast<int>(c));
    PlotSeries tip = CaseSeries(classes[c] + " (tip)", colour, results.size(), LineStyle::Solid);
    PlotSeries instrument = CaseSeries(classes[c] + " (instrument)", InstrumentColour(colour), results.size(), LineStyle::Dashed);
    bool any = false;
    for (std::size_t i = 0; i < results.size(); ++i)
    {
      const CohortClassRow* row = RowOf(results[i], classes[c]);
      tip.ValuesMm[i] = row ? row->TipMinMm.value_or(none) : none;
      // As in distance.png: below zero, the instrument's depth inside.
      instrument.ValuesMm[i] = !row ? none : row->PenetrationDepthMaxMm ? -*row->PenetrationDepthMaxMm : row->SurfaceMinMm.value_or(none);
      largestVolumeMm3 = std::max(largestVolumeMm3, row ? row->PenetrationMaxMm3.value_or(0.0) : 0.0);
      any = any || std::isfinite(tip.ValuesMm[i]) || std::isfinite(instrument.ValuesMm[i]);
    }
    if (!any)
    {
      tip.Name = classes[c] + ": in no case";
    }
    instrument.DeepestNote = InstrumentVolumeNote(largestVolumeMm3);
    largestVolumeMm3 = 0.0;
    series.push_back(std::move(tip));
    if (any)
    {
      series.push_back(std::move(instrument));
    }
  }
  PlotSeries margin = CaseSeries("tumour margin kept (tip)", TumourDisplayColour, results.size(), LineStyle::Dotted);
  bool anyMargin = false;
  for (std::size_t i = 0; i < results.size(); ++i)
  {
    cases.push_back(static_cast<double>(i + 1));
    options.XTickLabels.push_back(results[i].Case + (results[i].Error.empty() ? "" : " (failed)"));
    margin.ValuesMm[i] = results[i].MarginMinMm.value_or(none);
    anyMargin = anyMargin || results[i].MarginMinMm.has_value();
  }
  if (anyMargin)
  {
    series.push_back(std::move(margin));
  }
  options.Title = "closest approach per case: tip (solid), instrument (dashed, below 0: inside)" +
    std::string(anyMargin ? ", tumour margin (dotted)" : "");
  options.XLabel = "case (" + std::to_string(results.size()) + ", cohort.csv order)";
  options.YLabel = "closest approach (mm)";
  options.GrowToFitLegend = true;
  WriteDistancePlotPng(fileName, cases, series, DangerBands(DangerThresholds(), true), options);
}

namespace
{
using CaseFinished = std::function<void(std::size_t, CohortCaseResult)>;

/// A merge: each case from the first merged folder that holds it whole, else a row saying so.
void MergeCohortCases(const std::vector<CohortCase>& cases, const CohortRequest& request, const CaseFinished& finish)
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

/// The cases jobs at a time, each resumed when whole (else computed, saying why), each ended at
/// once as "interrupted" once a held signal came.
void ComputeCohortCases(const std::vector<CohortCase>& cases, const CohortRequest& request, int jobs,
  const CohortLogicFactory& makeLogic, const CohortStageObserver& stages, const CaseFinished& finish)
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
      std::string whyNot;
      std::optional<CohortCaseResult> earlier = CompletedCohortCase(cases[i], folder, &whyNot);
      if (!earlier && !whyNot.empty() && stages)
      {
        stages(cases[i].Name, "computed again: " + whyNot);
      }
      finish(i, earlier ? std::move(*earlier) : RunCohortCase(cases[i], folder, request.Settings, makeLogic, stages));
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < jobs; ++j)
  {
    workers.emplace_back(work);
  }
  work();
  for (std::thread& t : workers)
  {
    t.join();
  }
}

/// The counts, and unless interrupted the table and the picture (a shard's table alone).
void FinishCohortReport(const CohortRequest& request, CohortReport& report)
{
  for (const CohortCaseResult& r : report.Results)
  {
    report.Interrupted = report.Interrupted || r.Error == "interrupted";
    report.Resumed += r.Resumed ? 1 : 0;
    report.Computed += !r.Resumed && r.Error.empty() ? 1 : 0;
    report.Failed += r.Error.empty() ? 0 : 1;
  }
  if (report.Interrupted)
  {
    return;
  }
  if (request.ShardCount > 1)
  {
    const std::string name = "cohort-" + std::to_string(request.ShardIndex) + "-of-" + std::to_string(request.ShardCount) + ".csv";
    WriteFileAtomically(request.OutputFolder + "/" + name, CohortCsv(report.Results));
    report.Files = { name };
    return;
  }
  WriteFileAtomically(request.OutputFolder + "/cohort.csv", CohortCsv(report.Results));
  WriteCohortPlot(report.Results, request.OutputFolder + "/cohort.png");
  report.Files = { "cohort.csv", "cohort.png" };
}
} // namespace

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
  RefuseInputsOverCohortFiles(cases, request);
  PrepareCohortFolder(request);
  const CohortFolderLock lock(request.OutputFolder, request.ShardIndex, request.ShardCount);
  const SignalHold hold; // the workers' case folders nest their holds in this one
  PrepareConcurrentImports();
  CohortReport report;
  report.Jobs = CohortJobsFor(request.Jobs, cases.size(), report.JobsCapped);
  if (!report.JobsCapped.empty() && stages)
  {
    stages("cohort", report.JobsCapped); // said before any case starts
  }
  report.Results.resize(cases.size());
  std::mutex told;
  int done = 0;
  const CaseFinished finish = [&](std::size_t i, CohortCaseResult result) {
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
    MergeCohortCases(cases, request, finish);
  }
  else
  {
    ComputeCohortCases(cases, request, report.Jobs, makeLogic, stages, finish);
  }
  FinishCohortReport(request, report);
  report.Ms = NowMs() - start;
  return report;
}
} // namespace vp
