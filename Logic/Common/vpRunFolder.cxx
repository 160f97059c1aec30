#include "vpRunFolder.h"

#include "vpInputError.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace vp
{
namespace
{
// The signals held while a run is written, the first one that arrived, and the handlers they had.
const int HeldSignals[] = { SIGINT, SIGTERM, SIGHUP };
volatile std::sig_atomic_t PendingSignal = 0;
struct sigaction PreviousActions[3];
int Holders = 0; // RunFolders begun and not released

extern "C" void RecordSignal(int signal)
{
  if (PendingSignal == 0)
  {
    PendingSignal = signal;
  }
}

void HoldSignals()
{
  if (Holders++ > 0)
  {
    return;
  }
  PendingSignal = 0;
  struct sigaction record = {};
  record.sa_handler = RecordSignal;
  sigemptyset(&record.sa_mask);
  for (int i = 0; i < 3; ++i)
  {
    sigaction(HeldSignals[i], &record, &PreviousActions[i]);
  }
}

// Restores the handlers; a signal that came meanwhile is raised again, to act as it would have.
void ReleaseSignals()
{
  if (--Holders > 0)
  {
    return;
  }
  for (int i = 0; i < 3; ++i)
  {
    sigaction(HeldSignals[i], &PreviousActions[i], nullptr);
  }
  if (const int signal = PendingSignal)
  {
    PendingSignal = 0;
    std::raise(signal);
  }
}

// A report's entry: a file's name, or a folder's with its slash ("dicom/").
struct Entry
{
  std::string Name;
  bool Folder;
};

Entry SplitEntry(const std::string& entry)
{
  const bool folder = !entry.empty() && entry.back() == '/';
  return { folder ? entry.substr(0, entry.size() - 1) : entry, folder };
}

// The files the previous run's report says it wrote: "files", or a models.json's structures;
// none when there is no readable report (then nothing is removed).
std::set<std::string> PreviousRunFiles(const std::string& report)
{
  std::set<std::string> files;
  std::ifstream in(report);
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (!in || doc.is_discarded() || !doc.is_object())
  {
    return files;
  }
  const auto add = [&](const nlohmann::json& entry) {
    // Only a plain name in the folder, or a plain folder name with its slash ("dicom/"): a report
    // is data we do not control.
    if (!entry.is_string())
    {
      return;
    }
    const std::string text = entry.get<std::string>();
    const std::string name = SplitEntry(text).Name;
    if (!name.empty() && fs::path(name).filename() == name && name != "." && name != "..")
    {
      files.insert(text);
    }
  };
  if (doc.contains("files") && doc["files"].is_array())
  {
    for (const auto& name : doc["files"])
    {
      add(name);
    }
  }
  if (doc.contains("structures") && doc["structures"].is_array())
  {
    for (const auto& s : doc["structures"])
    {
      if (s.is_object() && s.contains("file"))
      {
        add(s["file"]);
      }
    }
  }
  return files;
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

RunFolder::RunFolder(const std::string& target, const std::string& report)
  : TargetPath(fs::path(target).lexically_normal().string())
  , ReportName(report)
{
  std::error_code ec;
  if (fs::exists(this->TargetPath, ec) && !fs::is_directory(this->TargetPath, ec))
  {
    throw InputError(target, "cannot create folder: a file has that name");
  }
  this->StagingPath = (fs::path(this->TargetPath) / (".vesselproximity-partial-" + std::to_string(::getpid()))).string();
}

bool RunFolder::SignalPending()
{
  return PendingSignal != 0;
}

RunFolder::~RunFolder()
{
  this->Release();
}

void RunFolder::Begin()
{
  if (this->Begun)
  {
    return;
  }
  HoldSignals();
  this->Begun = true;
  this->CreatedTarget = CreateOutputFolder(this->TargetPath);
  std::error_code ec;
  fs::remove_all(this->StagingPath, ec); // left by a killed process that had our pid
  if (!fs::create_directory(this->StagingPath, ec))
  {
    throw InputError(this->TargetPath, "cannot write here: " + ec.message());
  }
}

std::string RunFolder::Register(const std::string& entry)
{
  const std::string name = SplitEntry(entry).Name;
  if (!this->Begun)
  {
    return this->TargetPath + "/" + name;
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

namespace
{
/// A run's entry in the target: a file is replaced by the rename; a folder of the previous run is
/// removed first (a folder cannot be renamed onto one that is not empty).
void PutInPlace(const std::string& staged, const std::string& target, bool folder)
{
  std::error_code ec;
  if (folder && fs::is_directory(target, ec))
  {
    fs::remove_all(target, ec);
  }
  if (std::rename(staged.c_str(), target.c_str()) != 0)
  {
    throw InputError(target, std::string("cannot write: ") + std::strerror(errno));
  }
}
} // namespace

void RunFolder::Commit()
{
  if (!this->Begun)
  {
    return;
  }
  std::error_code ec;
  const std::set<std::string> ours(this->Names.begin(), this->Names.end());
  for (const std::string& stale : PreviousRunFiles(this->TargetPath + "/" + this->ReportName))
  {
    if (ours.count(stale))
    {
      continue;
    }
    const Entry entry = SplitEntry(stale);
    const std::string path = this->TargetPath + "/" + entry.Name;
    if (!entry.Folder)
    {
      fs::remove(path, ec);
    }
    else if (fs::is_directory(path, ec) && !fs::is_symlink(path, ec))
    {
      fs::remove_all(path, ec);
    }
  }
  // The report last: whoever sees the new report sees every file it lists.
  std::vector<std::string> order = this->Names;
  std::stable_partition(order.begin(), order.end(), [&](const std::string& n) { return n != this->ReportName; });
  for (const std::string& name : order)
  {
    const Entry entry = SplitEntry(name);
    if (!fs::exists(this->StagingPath + "/" + entry.Name, ec))
    {
      continue; // named, never written (a writer that failed quietly is the writer's to report)
    }
    PutInPlace(this->StagingPath + "/" + entry.Name, this->TargetPath + "/" + entry.Name, entry.Folder);
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
  fs::remove_all(this->StagingPath, ec);
  if (this->CreatedTarget)
  {
    fs::remove(this->TargetPath, ec); // only if empty: a failed first run leaves no folder
  }
  this->Begun = false;
  ReleaseSignals();
}
} // namespace vp
