#ifndef vpRunFolder_h
#define vpRunFolder_h

#include <memory>
#include <string>
#include <vector>

namespace vp
{
class SignalHold;

/// Creates an output folder and its missing parents, like mkdir -p; returns whether it was new.
/// Throws InputError naming the folder when it cannot be made.
bool CreateOutputFolder(const std::string& folder);

/// The files of one run in an output folder, put in place together, and nothing else touched.
///
/// The folder holds a marker, ".vesselproximity-run.json", naming the entries (files, and
/// folders as "name/") that the last run wrote, each with its identity (device, inode, and for
/// a file its size and time). A run writes into a staging folder inside the target
/// (".vesselproximity-partial-PID", on the same file system, locked while its process lives).
/// Commit() prepares a plan in the staging folder (the new entries, and the previous run's
/// entries this one does not write again, to remove), then renames the staging folder to
/// ".vesselproximity-commit": that one rename is the commit. Then the entries move into place,
/// the previous run's leftovers go, the report follows and the marker is replaced. A process killed
/// after the commit leaves the plan, which the next run in the folder completes before its own;
/// one killed before it leaves a staging folder, which the next run removes (its lock is free).
///
/// Nothing the runs did not write is removed or replaced:
/// - an entry is the previous run's only while the marker names it and its identity still holds
///   (a file the user replaced or edited since is theirs);
/// - an entry that is or holds one of the run's inputs (SetInputs) is never removed,
///   and writing over one is refused before anything is written;
/// - writing over a name the marker does not claim is refused ("not written by a run here").
///
/// SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGPIPE and SIGXFSZ are held from
/// Begin() to Commit() or destruction and acted on after, so an interrupted run leaves the old
/// results or the new, never a mixture; a signal the process ignores (nohup) stays ignored. A
/// run that streams its results while it computes (track's frames) asks SignalPending() between
/// steps and gives up (destroying the RunFolder) when one came, so Ctrl-C still stops it at once.
class RunFolder
{
public:
  /// report: the run's report file name ("models.json", "summary.json"), put in place last.
  /// Throws InputError(target, ...) when the target is a file.
  RunFolder(const std::string& target, const std::string& report);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  /// The files and folders the run reads: never removed or written over, wherever they lie.
  /// Before Begin().
  void SetInputs(const std::vector<std::string>& paths);
  /// Holds the signals, creates the target (and its missing parents), completes a commit a killed
  /// run left, removes the staging folders of dead runs, and makes this run's.
  void Begin();
  /// The path to write a file of this run to: inside the staging folder once begun, in the
  /// target otherwise (to name it in messages). Throws InputError when the name in the target
  /// is an input of the run or is not the previous run's to replace.
  std::string File(const std::string& name);
  /// A folder of this run (created in the staging folder once begun; the target's path otherwise).
  /// The marker lists it as "name/"; a later run that does not write it again removes it whole,
  /// one that does replaces it whole.
  std::string Folder(const std::string& name);
  /// Puts the run's files in place; throws InputError(target, ...) when it cannot.
  void Commit();
  /// A run that streams what it records (a live session) keeps it if its process is killed: the
  /// next run in the folder moves the dead run's staging folder to "interrupted-<UTC time>-<pid>"
  /// (its frames.csv as far as it was flushed), which no later run removes, rather than deleting it.
  /// Call before Begin() or after.
  void KeepIfKilled();

  const std::string& Target() const { return this->TargetPath; }
  /// The run's files ("name") and folders ("name/") noted so far, in the order given.
  const std::vector<std::string>& GetEntries() const { return this->Names; }
  /// Whether a held signal came since Begin().
  static bool SignalPending();

  /// An entry of a run as the marker records it: what makes it still the run's own.
  struct Entry
  {
    std::string Name;
    bool Folder = false;
    unsigned long long Device = 0, Inode = 0, Size = 0;
    long long ModifiedNs = 0;
  };

  /// The names the folder keeps for itself.
  static const char* MarkerName() { return ".vesselproximity-run.json"; }
  static const char* CommitName() { return ".vesselproximity-commit"; }
  static const char* StagingPrefix() { return ".vesselproximity-partial-"; }
  /// Where a killed run that was to be kept (KeepIfKilled) is moved: "interrupted-", when it was
  /// found and its process.
  static const char* InterruptedPrefix() { return "interrupted-"; }

private:
  std::string TargetPath;
  std::string ReportName;
  std::string StagingPath;
  std::vector<std::string> Names; // the run's files ("name") and folders ("name/"), in the order given
  std::vector<std::string> Inputs; // canonical paths
  std::vector<Entry> Previous;     // the marker's entries when the run began
  int LockFd = -1;                 // the staging folder's lock, held while the run lives
  std::unique_ptr<SignalHold> Signals; // from Begin() to the commit or the end
  bool Begun = false;
  bool Keep = false;
  bool CreatedTarget = false;
  void Release();
  /// Notes an entry of the run ("name" or "name/") and returns its path: staged once begun.
  std::string Register(const std::string& entry);
  /// Whether path is or holds one of the inputs (both canonical).
  bool TouchesInput(const std::string& path) const;
};
} // namespace vp

#endif
