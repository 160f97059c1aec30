#ifndef vpCohortRun_h
#define vpCohortRun_h

#include "vpCohortCase.h"

#include <functional>
#include <string>
#include <vector>

namespace vp
{
/// A cohort run as a front end asks for it (`vesselproximity batch`).
struct CohortRequest
{
  std::string Manifest;
  std::string OutputFolder;
  /// Cases computed at once, each on its own thread with its own logic (default 1).
  int Jobs = 1;
  /// This run's share of the manifest's cases: those whose position (from 0) modulo ShardCount is
  /// ShardIndex - 1; 1 of 1: every case. A cluster's array job runs one shard per task into the
  /// same output folder, then a run with MergeFolders gathers them.
  int ShardIndex = 1;
  int ShardCount = 1;
  /// Non-empty: nothing is computed; each case of the manifest is taken from the first of these
  /// folders that holds it whole (its case.json, the same inputs), and the cohort's table and
  /// picture are written for them all.
  std::vector<std::string> MergeFolders;
  CohortSettings Settings;
  /// Throws ParameterError naming the setting out of range (Jobs, Shard).
  void Validate() const;
};

/// What a cohort run did, case by case in the manifest's order.
struct CohortReport
{
  std::vector<CohortCaseResult> Results;
  int Computed = 0;
  int Resumed = 0;
  int Failed = 0;
  /// A held signal came: no table was written; a run again resumes from the whole cases.
  bool Interrupted = false;
  /// The table and the picture, as written (cohort.csv and cohort.png; with a shard of several,
  /// cohort-K-of-N.csv alone).
  std::vector<std::string> Files;
  double Ms = 0.0;
  /// Cases run at once, and why fewer than asked when they were (empty otherwise).
  int Jobs = 1;
  std::string JobsCapped;
};

/// How many cases may run at once: the request's, at most this machine's cores and what its
/// available memory holds at about CohortCaseMemoryBytes a case; capped says why when fewer.
constexpr double CohortCaseMemoryBytes = 1.0 * (1 << 30);
int CohortJobsFor(int requested, std::size_t cases, std::string& capped);

/// Told of each case as it ends, in the order they end: its result, the cases done and the total.
using CohortCaseObserver = std::function<void(const CohortCaseResult& result, int done, int total)>;

/// Runs the cohort: the manifest read (its one-line error thrown before anything is computed),
/// each case of this shard computed into OutputFolder/<case>/ (RunCohortCase) unless an earlier
/// run left it whole with the same inputs (CompletedCohortCase: resumed), Jobs at a time; then
/// OutputFolder/cohort.csv (CohortCsv) and cohort.png (CohortPlot), or, for one shard of several,
/// cohort-K-of-N.csv. A case that fails is a row with its error, never the end of the cohort.
/// Signals are held for the whole run (a case in progress ends whole or not at all).
CohortReport RunCohort(const CohortRequest& request, const CohortLogicFactory& makeLogic = {},
  const CohortStageObserver& stages = {}, const CohortCaseObserver& cases = {});

/// cohort.csv: `case,class,tip_min_mm,surface_min_mm,penetration_max_mm3,breach_frames,
/// margin_min_mm,error`, one row per case and vessel class (a failed case: one row, its error),
/// lengths to 4 decimals, empty where nothing measured it; an error with a comma or a quote is
/// quoted.
std::string CohortCsv(const std::vector<CohortCaseResult>& results);
/// cohort.png: each class's closest tip approach per case (signed: below 0 the tip went inside),
/// over the danger bands, cases along the x axis in the table's order.
void WriteCohortPlot(const std::vector<CohortCaseResult>& results, const std::string& fileName);
} // namespace vp

#endif
