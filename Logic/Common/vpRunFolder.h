#ifndef vpRunFolder_h
#define vpRunFolder_h

#include <string>
#include <vector>

namespace vp
{
/// Creates an output folder and its missing parents, like mkdir -p; returns whether it was new.
/// Throws InputError naming the folder when it cannot be made.
bool CreateOutputFolder(const std::string& folder);

/// The files of one run in an output folder, put in place together. The run writes into a
/// staging folder inside the target (".vesselproximity-partial-PID", on the same file system);
/// Commit() removes the files of the previous run that this one does not write again (as its
/// report lists them: "files", or a models.json's structures), then renames each new file into
/// place, the report last. Until Commit() nothing in the target changes; a run that fails, or
/// whose RunFolder is destroyed without Commit(), removes its staging folder and leaves the
/// previous results exactly as they were. Files that no run of ours wrote are never touched.
///
/// SIGINT, SIGTERM and SIGHUP are held from Begin() to Commit() or destruction and acted on
/// after, so an interrupted run leaves the old results or the new, never a mixture and never a
/// staging folder. A run that streams its results while it computes (track's frames) begins
/// first and asks SignalPending() between steps, giving up (destroying the RunFolder) when one
/// came, so the user's Ctrl-C still stops it at once.
class RunFolder
{
public:
  /// report: the run's report file name ("models.json", "summary.json"), written last. Throws
  /// InputError(target, ...) when the target is a file.
  RunFolder(const std::string& target, const std::string& report);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  /// Holds the signals and creates the target (and its missing parents) and the staging folder.
  void Begin();
  /// The path to write a file of this run to: inside the staging folder once begun, in the
  /// target otherwise (to name it in messages).
  std::string File(const std::string& name);
  /// A folder of this run (created in the staging folder once begun; the target's path otherwise).
  /// The report lists it as "name/"; a later run that does not write it again removes it whole,
  /// one that does replaces it whole.
  std::string Folder(const std::string& name);
  /// Puts the run's files in place; throws InputError(target, ...) when it cannot.
  void Commit();

  const std::string& Target() const { return this->TargetPath; }
  /// The run's files ("name") and folders ("name/") noted so far, in the order given: what its
  /// report lists.
  const std::vector<std::string>& GetEntries() const { return this->Names; }
  /// Whether a held signal came since Begin().
  static bool SignalPending();

private:
  std::string TargetPath;
  std::string ReportName;
  std::string StagingPath;
  std::vector<std::string> Names; // the run's files ("name") and folders ("name/"), in the order given
  bool Begun = false;
  bool CreatedTarget = false;
  void Release();
  /// Notes an entry of the run ("name" or "name/") and returns its path: staged once begun.
  std::string Register(const std::string& entry);
};
} // namespace vp

#endif
