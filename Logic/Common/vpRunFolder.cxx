#include "vpRunFolder.h"

#include "vpSignalHold.h"

#include "vpInputError.h"
#include "vpOutputFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <ctime>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <system_error>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace vp
{
namespace
{
const char* LockName = ".lock";
const char* KeepName = ".keep-if-killed";
const char* PlanName = ".vesselproximity-plan.json";

// "dicom/" is the folder dicom, "frames.csv" a file.
std::pair<std::string, bool> SplitEntry(const std::string& entry)
{
  const bool folder = !entry.empty() && entry.back() == '/';
  return { folder ? entry.substr(0, entry.size() - 1) : entry, folder };
}

std::string Canonical(const std::string& path)
{
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal().string() : canonical.string();
}

using Json = nlohmann::json;

/// The entry named name as it is now at path, to tell whether it is still what a run wrote
/// (lstat: a link is never a run's entry); empty when there is no such file or folder.
std::optional<RunFolder::Entry> IdentityNow(const std::string& path, const std::string& name, bool folder)
{
  struct stat info;
  if (::lstat(path.c_str(), &info) != 0 || (folder ? !S_ISDIR(info.st_mode) : !S_ISREG(info.st_mode)))
  {
    return std::nullopt;
  }
  RunFolder::Entry e;
  e.Name = name;
  e.Folder = folder;
  e.Device = static_cast<unsigned long long>(info.st_dev);
  e.Inode = static_cast<unsigned long long>(info.st_ino);
  e.Size = folder ? 0 : static_cast<unsigned long long>(info.st_size);
  e.ModifiedNs = folder ? 0 : static_cast<long long>(info.st_mtim.tv_sec) * 1000000000LL + info.st_mtim.tv_nsec;
  return e;
}

/// Whether path is still the entry a run recorded.
bool SameIdentity(const std::string& path, const RunFolder::Entry& e)
{
  const std::optional<RunFolder::Entry> now = IdentityNow(path, e.Name, e.Folder);
  return now && now->Device == e.Device && now->Inode == e.Inode && now->Size == e.Size &&
    now->ModifiedNs == e.ModifiedNs;
}

Json EntryJson(const RunFolder::Entry& e)
{
  return Json{ { "name", e.Folder ? e.Name + "/" : e.Name }, { "device", e.Device }, { "inode", e.Inode },
    { "size", e.Size }, { "modified_ns", e.ModifiedNs } };
}

/// The entries of a marker or a plan's list; a list that is not what we write gives none (a
/// marker is a file anyone can edit: only plain names in the folder are taken).
std::vector<RunFolder::Entry> EntriesOf(const Json& list)
{
  std::vector<RunFolder::Entry> entries;
  if (!list.is_array())
  {
    return entries;
  }
  for (const Json& e : list)
  {
    if (!e.is_object() || !e.contains("name") || !e["name"].is_string())
    {
      continue;
    }
    const auto [name, folder] = SplitEntry(e["name"].get<std::string>());
    if (name.empty() || fs::path(name).filename() != name || name == "." || name == ".." ||
      name.rfind(".vesselproximity", 0) == 0)
    {
      continue;
    }
    RunFolder::Entry entry;
    entry.Name = name;
    entry.Folder = folder;
    entry.Device = e.value("device", 0ULL);
    entry.Inode = e.value("inode", 0ULL);
    entry.Size = e.value("size", 0ULL);
    entry.ModifiedNs = e.value("modified_ns", 0LL);
    entries.push_back(entry);
  }
  return entries;
}

Json ReadJsonOrNull(const std::string& file)
{
  // Ours, or nothing: a marker is a regular file of a few kilobytes (a FIFO put in its place
  // would block the open, a huge one take the memory).
  constexpr off_t MaxBytes = 16 << 20;
  struct stat info;
  if (::lstat(file.c_str(), &info) != 0 || !S_ISREG(info.st_mode) || info.st_size > MaxBytes)
  {
    return Json();
  }
  std::ifstream in(file);
  if (!in)
  {
    return Json();
  }
  const Json doc = Json::parse(in, nullptr, false);
  return doc.is_discarded() ? Json() : doc;
}

/// Whether the process that made a staging or commit folder is gone: its lock is free (or, for a
/// folder from before the lock, its process number names no process).
bool OwnerGone(const fs::path& folder)
{
  const int fd = ::open((folder / LockName).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd >= 0)
  {
    const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    ::close(fd);
    return free;
  }
  const std::string name = folder.filename().string();
  const std::string prefix = RunFolder::StagingPrefix();
  if (name.rfind(prefix, 0) != 0)
  {
    return false;
  }
  char* end = nullptr;
  const long pid = std::strtol(name.c_str() + prefix.size(), &end, 10);
  return end && *end == '\0' && pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

void Remove(const std::string& path, bool folder)
{
  std::error_code ec;
  if (folder)
  {
    fs::remove_all(path, ec);
  }
  else
  {
    fs::remove(path, ec);
  }
}
} // namespace

bool CreateOutputFolder(const std::string& folder)
{
  std::error_code ec;
  const bool created = !fs::exists(folder, ec);
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder, ec))
  {
    throw InputError(folder, "cannot create folder: " + (ec ? ec.message() : std::string("a file has that name")));
  }
  return created;
}

namespace
{
/// Completes a commit: the plan's entries into place (the report last), the previous run's
/// leftovers it names removed while they are still what that run wrote, the marker replaced,
/// the commit folder removed. Each step can be done again: a process killed in the middle
/// leaves what the next one completes.
void RollForward(const std::string& target, const std::string& commit)
{
  const Json plan = ReadJsonOrNull(commit + "/" + PlanName);
  using Step = RunFolder::Entry;
  if (plan.is_object())
  {
    const std::string report = plan.value("report", std::string());
    const std::vector<Step> moves = EntriesOf(plan.value("entries", Json::array()));
    const auto move = [&](const Step& m) {
      const std::string staged = commit + "/" + m.Name, placed = target + "/" + m.Name;
      struct stat info;
      if (::lstat(staged.c_str(), &info) != 0)
      {
        return; // put in place already
      }
      std::error_code ec;
      if (fs::is_directory(fs::symlink_status(placed, ec)) || m.Folder)
      {
        fs::remove_all(placed, ec); // the previous run's, checked when the plan was made
      }
      if (std::rename(staged.c_str(), placed.c_str()) != 0)
      {
        throw InputError(placed, std::string("cannot put in place: ") + std::strerror(errno));
      }
    };
    for (const Step& m : moves)
    {
      if (m.Name != report)
      {
        move(m);
      }
    }
    // The previous run's leftovers go before the report that says the run is whole, the report
    // last: whoever sees the new report sees every file it lists, and none of the old run's.
    for (const Step& r : EntriesOf(plan.value("remove", Json::array())))
    {
      const std::string path = target + "/" + r.Name;
      if (SameIdentity(path, r))
      {
        Remove(path, r.Folder);
      }
    }
    for (const Step& m : moves)
    {
      if (m.Name == report)
      {
        move(m);
      }
    }
    // The marker, made from the plan's entries, takes the place of whatever has its name (a name
    // of ours: a link put there is replaced, never written through).
    const std::string marker = commit + "/" + RunFolder::MarkerName();
    WriteFileAtomically(marker, Json{ { "entries", plan.value("entries", Json::array()) } }.dump(2) + "\n");
    if (std::rename(marker.c_str(), (target + "/" + RunFolder::MarkerName()).c_str()) != 0)
    {
      throw InputError(target, std::string("cannot record the run: ") + std::strerror(errno));
    }
  }
  std::error_code ec;
  fs::remove_all(commit, ec);
}

/// A commit a killed run left is completed; the staging folders of dead runs are removed.
/// A dead run's staging folder: removed, or when it asked to be kept (RunFolder::KeepIfKilled)
/// moved beside the runs as "interrupted-<its last change>", its own files left out.
void RemoveOrKeep(const fs::path& staging)
{
  std::error_code ec;
  if (!fs::exists(staging / KeepName, ec))
  {
    fs::remove_all(staging, ec);
    return;
  }
  fs::remove(staging / KeepName, ec);
  fs::remove(staging / LockName, ec);
  // Named for when it was found (UTC) and the process that wrote it.
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(when, sizeof when, "%Y%m%dT%H%M%SZ", &utc);
  const std::string pid = staging.filename().string().substr(std::string(RunFolder::StagingPrefix()).size());
  const std::string name = RunFolder::InterruptedPrefix() + std::string(when) + "-" + pid;
  fs::path kept = staging.parent_path() / name;
  for (int n = 2; fs::exists(kept, ec); ++n)
  {
    kept = staging.parent_path() / (name + "-" + std::to_string(n));
  }
  fs::rename(staging, kept, ec);
  if (ec)
  {
    fs::remove_all(staging, ec);
  }
}

void Recover(const std::string& target)
{
  std::error_code ec;
  const fs::path commit = fs::path(target) / RunFolder::CommitName();
  if (fs::is_directory(fs::symlink_status(commit, ec)) && OwnerGone(commit))
  {
    RollForward(target, commit.string());
  }
  for (const auto& entry : fs::directory_iterator(target, ec))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind(RunFolder::StagingPrefix(), 0) == 0 && fs::is_directory(fs::symlink_status(entry.path(), ec)) &&
      OwnerGone(entry.path()))
    {
      RemoveOrKeep(entry.path());
    }
  }
}
} // namespace

RunFolder::RunFolder(const std::string& target, const std::string& report)
  : TargetPath(fs::path(target).lexically_normal().string())
  , ReportName(report)
{
  std::error_code ec;
  if (fs::exists(this->TargetPath, ec) && !fs::is_directory(this->TargetPath, ec))
  {
    throw InputError(target, "cannot create folder: a file has that name");
  }
  this->StagingPath = (fs::path(this->TargetPath) / (StagingPrefix() + std::to_string(::getpid()))).string();
}

bool RunFolder::SignalPending()
{
  return SignalHold::Pending();
}

RunFolder::~RunFolder()
{
  this->Release();
}

void RunFolder::SetInputs(const std::vector<std::string>& paths)
{
  this->Inputs.clear();
  for (const std::string& p : paths)
  {
    if (!p.empty())
    {
      this->Inputs.push_back(Canonical(p));
    }
  }
}

bool RunFolder::TouchesInput(const std::string& path) const
{
  const std::string p = Canonical(path);
  for (const std::string& input : this->Inputs)
  {
    if (input == p || (input.size() > p.size() && input.compare(0, p.size(), p) == 0 && input[p.size()] == '/'))
    {
      return true;
    }
  }
  return false;
}

void RunFolder::Begin()
{
  if (this->Begun)
  {
    return;
  }
  this->Signals = std::make_unique<SignalHold>();
  this->Begun = true;
  this->CreatedTarget = CreateOutputFolder(this->TargetPath);
  Recover(this->TargetPath);
  const Json marker = ReadJsonOrNull(this->TargetPath + "/" + MarkerName());
  this->Previous = marker.is_object() ? EntriesOf(marker.value("entries", Json::array())) : std::vector<Entry>();
  std::error_code ec;
  if (fs::exists(this->StagingPath, ec))
  {
    RemoveOrKeep(this->StagingPath); // left by a killed process that had our pid
  }
  if (!fs::create_directory(this->StagingPath, ec))
  {
    throw InputError(this->TargetPath, "cannot write here: " + ec.message());
  }
  this->LockFd = ::open((this->StagingPath + "/" + LockName).c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (this->LockFd < 0 || ::flock(this->LockFd, LOCK_EX | LOCK_NB) != 0)
  {
    throw InputError(this->TargetPath, std::string("cannot write here: ") + std::strerror(errno));
  }
  if (this->Keep)
  {
    std::ofstream(this->StagingPath + "/" + KeepName) << "a run that streams what it records: kept if its process is killed\n";
  }
}

void RunFolder::KeepIfKilled()
{
  this->Keep = true;
  if (this->Begun)
  {
    std::ofstream(this->StagingPath + "/" + KeepName) << "a run that streams what it records: kept if its process is killed\n";
  }
}


std::string RunFolder::Register(const std::string& entry)
{
  const std::string name = SplitEntry(entry).first; // not a structured binding: a lambda below captures it
  const std::string placed = this->TargetPath + "/" + name;
  if (!this->Begun)
  {
    return placed;
  }
  struct stat info;
  if (::lstat(placed.c_str(), &info) == 0)
  {
    if (this->TouchesInput(placed))
    {
      throw InputError(placed, "is an input of this run: write the run to another folder");
    }
    const bool ours = std::any_of(this->Previous.begin(), this->Previous.end(), [&](const Entry& e) {
      return e.Name == name && SameIdentity(placed, e);
    });
    if (!ours)
    {
      throw InputError(placed, std::string("was not written by a run here (") + MarkerName() +
          " does not name it as it is now): move it away or write the run to another folder");
    }
  }
  if (std::find(this->Names.begin(), this->Names.end(), entry) == this->Names.end())
  {
    this->Names.push_back(entry);
  }
  return this->StagingPath + "/" + name;
}

std::string RunFolder::File(const std::string& name)
{
  return this->Register(name);
}

std::string RunFolder::Folder(const std::string& name)
{
  const std::string path = this->Register(name + "/");
  if (!this->Begun)
  {
    return path;
  }
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec)
  {
    throw InputError(this->TargetPath + "/" + name, "cannot create folder: " + ec.message());
  }
  return path;
}

void RunFolder::Commit()
{
  if (!this->Begun)
  {
    return;
  }
  // The plan: this run's entries as they are in the staging folder (a rename keeps them so), and
  // the previous run's that this one does not write again, unless the user changed them since or
  // the run reads them.
  Json entries = Json::array(), remove = Json::array();
  std::set<std::string> written;
  for (const std::string& entry : this->Names)
  {
    const auto [name, folder] = SplitEntry(entry);
    const std::optional<Entry> staged = IdentityNow(this->StagingPath + "/" + name, name, folder);
    if (!staged)
    {
      continue; // named, never written (a writer that failed quietly is the writer's to report)
    }
    entries.push_back(EntryJson(*staged));
    written.insert(name);
  }
  for (const Entry& e : this->Previous)
  {
    const std::string placed = this->TargetPath + "/" + e.Name;
    if (!written.count(e.Name) && SameIdentity(placed, e) && !this->TouchesInput(placed))
    {
      remove.push_back(EntryJson(e));
    }
  }
  try
  {
    WriteFileAtomically(this->StagingPath + "/" + PlanName,
      Json{ { "report", this->ReportName }, { "entries", entries }, { "remove", remove } }.dump(2) + "\n");
  }
  catch (const std::exception& e)
  {
    throw InputError(this->TargetPath, std::string("cannot put the run in place (") + e.what() +
        "): the folder holds the previous run as it was");
  }
  // The commit: one rename. From here the run is in place, or in the plan the next run completes.
  const std::string commit = this->TargetPath + "/" + CommitName();
  if (std::rename(this->StagingPath.c_str(), commit.c_str()) != 0)
  {
    const bool busy = errno == EEXIST || errno == ENOTEMPTY;
    throw InputError(this->TargetPath, std::string("cannot put the run in place: ") +
        (busy ? "another run is putting its files in place here" : std::strerror(errno)) +
        "; the folder holds the previous run as it was");
  }
  this->StagingPath.clear(); // the plan is no longer this run's to remove
  try
  {
    RollForward(this->TargetPath, commit);
  }
  catch (const std::exception& e)
  {
    throw InputError(this->TargetPath, std::string("the new run is committed but not wholly in place (") + e.what() +
        "): its plan is kept in " + CommitName() + ", and the next run here completes it before its own");
  }
  this->CreatedTarget = false; // it holds the run now
  this->Release();
}

void RunFolder::Release()
{
  if (!this->Begun)
  {
    return;
  }
  std::error_code ec;
  if (!this->StagingPath.empty())
  {
    fs::remove_all(this->StagingPath, ec);
  }
  if (this->LockFd >= 0)
  {
    ::close(this->LockFd); // a commit left half done is the next run's to complete
    this->LockFd = -1;
  }
  if (this->CreatedTarget)
  {
    fs::remove(this->TargetPath, ec); // only if empty: a failed first run leaves no folder
  }
  this->Begun = false;
  this->Signals.reset();
}
} // namespace vp
