// vp::RunFolder (issues 16 and 29): an output folder holds one run, whole. A new run replaces the
// files of the previous one (and removes those it does not write again), never removes or
// replaces anything no run of ours wrote or that the run reads, leaves the previous run exactly
// as it was when it fails, completes a commit a killed run left, removes the staging folders of
// dead runs, and holds its signals (but not an ignored one) until its files are in place.
#include "vpRunFolder.h"
#include "vpInputError.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <fstream>
#include <random>
#include <set>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
namespace fs = std::filesystem;
const std::string Marker = vp::RunFolder::MarkerName();

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

// Nothing but the given names (no staging or commit folder, no temporary file).
void ExpectExactly(const std::string& folder, std::set<std::string> names)
{
  std::set<std::string> found;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    found.insert(entry.path().filename().string());
  }
  EXPECT_EQ(found, names) << folder;
}

// One committed run writing each file with its text, and a folder when the name ends in '/'.
void CommitRun(const std::string& out, const std::vector<std::pair<std::string, std::string>>& files,
  const std::vector<std::string>& inputs = {})
{
  vp::RunFolder run(out, "report.json");
  run.SetInputs(inputs);
  run.Begin();
  for (const auto& [name, text] : files)
  {
    if (!name.empty() && name.back() == '/')
    {
      WriteText(run.Folder(name.substr(0, name.size() - 1)) + "/inside.txt", text);
    }
    else
    {
      WriteText(run.File(name), text);
    }
  }
  run.Commit();
}

std::string RefusalOf(const std::function<void()>& action)
{
  try
  {
    action();
  }
  catch (const vp::InputError& e)
  {
    return e.what();
  }
  return "(not refused)";
}

volatile std::sig_atomic_t Interrupts = 0;
extern "C" void CountInterrupt(int)
{
  Interrupts = Interrupts + 1;
}
} // namespace

TEST(RunFolder, ANewRunReplacesThePreviousOneAndLeavesOtherFilesAlone)
{
  const std::string dir = vp::test::MakeTempDir("runfolder");
  const std::string out = dir + "/out";
  CommitRun(out, { { "a.stl", "a1" }, { "b.stl", "b1" }, { "pictures/", "p1" }, { "report.json", "r1" } });
  WriteText(out + "/notes.txt", "the user's own");
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "a2");
    EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "a1") << "nothing changes before the commit";
    WriteText(run.File("report.json"), "r2");
    run.Commit();
  }
  ExpectExactly(out, { "a.stl", "report.json", "notes.txt", Marker });
  EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "a2");
  EXPECT_EQ(vp::test::Slurp(out + "/notes.txt"), "the user's own");

  // A file of the run that the user changed since is theirs: kept by a run that does not write
  // it, and not written over by one that does.
  WriteText(out + "/a.stl", "edited by hand, longer");
  CommitRun(out, { { "report.json", "r3" } });
  ExpectExactly(out, { "a.stl", "report.json", "notes.txt", Marker });
  const std::string refusal = RefusalOf([&] { CommitRun(out, { { "a.stl", "a4" }, { "report.json", "r4" } }); });
  EXPECT_NE(refusal.find(out + "/a.stl: was not written by a run here"), std::string::npos) << refusal;
  EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "edited by hand, longer");
  EXPECT_EQ(vp::test::Slurp(out + "/report.json"), "r3") << "the refused run changed nothing";

  // The marker is a file anyone can edit: it names plain names in its folder only.
  WriteText(dir + "/outside", "not in the folder");
  WriteText(out + "/" + Marker, R"({"entries": [{"name": "../outside"}, {"name": "/etc/passwd"}, {"name": "."}]})");
  CommitRun(out, { { "c.txt", "c5" } });
  EXPECT_TRUE(fs::exists(dir + "/outside"));
  fs::remove_all(dir);
}

TEST(RunFolder, AFailedRunLeavesThePreviousOneExactlyAsItWas)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_failed");
  const std::string out = dir + "/out";
  CommitRun(out, { { "a.stl", "a1" }, { "report.json", "r1" } });
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "half");
    // destroyed without Commit(): an exception on the way, say
  }
  ExpectExactly(out, { "a.stl", "report.json", Marker });
  EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "a1");
  // A failed first run leaves no folder at all.
  {
    vp::RunFolder run(dir + "/new/deeper", "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "half");
  }
  EXPECT_FALSE(fs::exists(dir + "/new/deeper"));
  // A file where the folder should be is refused before anything is done.
  WriteText(dir + "/taken", "x");
  EXPECT_THROW(vp::RunFolder(dir + "/taken", "report.json"), vp::InputError);
  fs::remove_all(dir);
}

// Issue 29: track with its inputs inside a previous run's folder and -o that folder deleted them.
// A commit that fails after its rename (here the run's record cannot take its place) says the new
// run is committed but not wholly in place, keeps its plan, and the next run completes it before
// its own once the obstacle is gone.
TEST(RunFolder, ACommitThatFailsMidwaySaysSoAndTheNextRunCompletesIt)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_midway");
  const std::string out = dir + "/out";
  CommitRun(out, { { "a.stl", "a1" }, { "report.json", "r1" } });
  std::string message;
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("b.stl"), "b2");
    WriteText(run.File("report.json"), "r2");
    fs::remove(out + "/" + Marker);
    fs::create_directories(out + "/" + Marker + "/blocking"); // a non-empty folder where the record goes
    try
    {
      run.Commit();
    }
    catch (const vp::InputError& e)
    {
      message = e.what();
    }
  }
  EXPECT_NE(message.find("the new run is committed but not wholly in place"), std::string::npos) << message;
  EXPECT_NE(message.find("the next run here completes it"), std::string::npos) << message;
  EXPECT_TRUE(fs::exists(out + "/.vesselproximity-commit")) << "the plan is kept";
  EXPECT_EQ(vp::test::Slurp(out + "/b.stl"), "b2") << "the new files are in place";
  fs::remove_all(out + "/" + Marker);
  CommitRun(out, { { "c.stl", "c3" }, { "report.json", "r3" } });
  EXPECT_FALSE(fs::exists(out + "/.vesselproximity-commit"));
  EXPECT_EQ(vp::test::Slurp(out + "/report.json"), "r3");
  EXPECT_FALSE(fs::exists(out + "/b.stl")) << "the completed run's file, replaced by the next run's";
  fs::remove_all(dir);
}

TEST(RunFolder, TheRunsInputsAreNeverRemovedNorWrittenOver)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_inputs");
  const std::string out = dir + "/out";
  CommitRun(out, { { "models/", "m" }, { "poses.csv", "p" }, { "dicom/", "d" }, { "report.json", "r1" } });
  // The next run reads a file inside models/ and poses.csv, and writes neither.
  CommitRun(out, { { "frames.csv", "f" }, { "report.json", "r2" } }, { out + "/models/inside.txt", out + "/poses.csv" });
  ExpectExactly(out, { "models", "poses.csv", "frames.csv", "report.json", Marker });
  EXPECT_EQ(vp::test::Slurp(out + "/models/inside.txt"), "m");
  // Writing over an input is refused before anything is written, through a link too.
  const std::string refusal =
    RefusalOf([&] { CommitRun(out, { { "poses.csv", "new" }, { "report.json", "r3" } }, { out + "/poses.csv" }); });
  EXPECT_NE(refusal.find(out + "/poses.csv: is an input of this run"), std::string::npos) << refusal;
  EXPECT_EQ(vp::test::Slurp(out + "/poses.csv"), "p");
  fs::create_symlink(out + "/poses.csv", dir + "/link.csv");
  const std::string viaLink =
    RefusalOf([&] { CommitRun(out, { { "poses.csv", "new" }, { "report.json", "r3" } }, { dir + "/link.csv" }); });
  EXPECT_NE(viaLink.find("is an input of this run"), std::string::npos) << viaLink;
  // Inputs kept by a run are no longer a run's: a later run leaves them too.
  CommitRun(out, { { "report.json", "r4" } });
  EXPECT_TRUE(fs::exists(out + "/poses.csv"));
  EXPECT_TRUE(fs::exists(out + "/models/inside.txt"));
  EXPECT_FALSE(fs::exists(out + "/frames.csv")) << "the previous run's own file goes";
  fs::remove_all(dir);
}

// Issue 29: an output path that was a link, a pipe or a device was replaced by a regular file.
TEST(RunFolder, ANameNoRunWroteIsNeverReplaced)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_foreign");
  const std::string out = dir + "/out";
  fs::create_directories(out);
  WriteText(dir + "/elsewhere.csv", "kept");
  fs::create_symlink(dir + "/elsewhere.csv", out + "/frames.csv");
  ASSERT_EQ(mkfifo((out + "/summary.json").c_str(), 0600), 0);
  for (const char* name : { "frames.csv", "summary.json" })
  {
    const std::string refusal = RefusalOf([&] { CommitRun(out, { { name, "x" }, { "report.json", "r" } }); });
    EXPECT_NE(refusal.find(out + "/" + name + ": was not written by a run here"), std::string::npos) << refusal;
  }
  EXPECT_TRUE(fs::is_symlink(out + "/frames.csv"));
  EXPECT_TRUE(fs::is_fifo(out + "/summary.json"));
  EXPECT_EQ(vp::test::Slurp(dir + "/elsewhere.csv"), "kept");
  ExpectExactly(out, { "frames.csv", "summary.json" });
  fs::remove_all(dir);
}

// Issue 29: a run killed (SIGKILL cannot be held) left ".vesselproximity-partial-PID" for ever.
// The next run removes the staging folder of a dead run, never that of a live one.
TEST(RunFolder, TheStagingFolderOfADeadRunIsRemovedAndALiveOnesKept)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_stale");
  const std::string out = dir + "/out";
  CommitRun(out, { { "a.stl", "a1" }, { "report.json", "r1" } });
  // Two runs in their own processes, each stopped after writing a file: one killed, one left.
  pid_t children[2];
  for (pid_t& child : children)
  {
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    child = fork();
    if (child == 0)
    {
      vp::RunFolder run(out, "report.json");
      run.Begin();
      WriteText(run.File("a.stl"), "half");
      (void)!write(ready[1], "x", 1);
      pause();
      _exit(0);
    }
    char c;
    ASSERT_EQ(read(ready[0], &c, 1), 1);
    close(ready[0]);
    close(ready[1]);
  }
  kill(children[0], SIGKILL);
  waitpid(children[0], nullptr, 0);
  const std::string dead = out + "/" + vp::RunFolder::StagingPrefix() + std::to_string(children[0]);
  const std::string live = out + "/" + vp::RunFolder::StagingPrefix() + std::to_string(children[1]);
  ASSERT_TRUE(fs::exists(dead));
  CommitRun(out, { { "a.stl", "a2" }, { "report.json", "r2" } });
  EXPECT_FALSE(fs::exists(dead)) << "a dead run's staging folder";
  EXPECT_TRUE(fs::exists(live)) << "a live run's staging folder";
  kill(children[1], SIGKILL);
  waitpid(children[1], nullptr, 0);
  // A staging folder from before the lock (no lock file) goes when its process is gone.
  fs::create_directories(out + "/" + vp::RunFolder::StagingPrefix() + std::to_string(children[1]) + "/x");
  fs::remove(live + "/.lock");
  CommitRun(out, { { "a.stl", "a3" }, { "report.json", "r3" } });
  ExpectExactly(out, { "a.stl", "report.json", Marker });
  fs::remove_all(dir);
}

// Issue 29: a kill inside the commit left frames.csv of one run beside summary.json of the other.
// The commit is one rename; a run killed after it leaves a plan that the next run completes
// before its own. Killed at 16 moments through commits of 500 files (up to one and a half times
// what a commit takes): afterwards every file is of one run, the old or the new, and nothing else
// is left.
TEST(RunFolder, AKillDuringTheCommitLeavesOneWholeRunOnceTheNextBegins)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_kill");
  const std::string out = dir + "/out";
  constexpr int Files = 500;
  const auto writeRun = [&](const std::string& text, bool signalReady, int readyFd) {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    for (int i = 0; i < Files; ++i)
    {
      WriteText(run.File("f" + std::to_string(i) + ".txt"), text);
    }
    WriteText(run.File("report.json"), text);
    if (signalReady)
    {
      (void)!write(readyFd, "x", 1);
    }
    const auto start = std::chrono::steady_clock::now();
    run.Commit();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  };
  const double commitUs = writeRun("0", false, -1);
  std::mt19937 random(29);
  int completedLater = 0, before = 0, after = 0;
  for (int k = 1; k <= 16; ++k)
  {
    const std::string text = std::to_string(k);
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0)
    {
      writeRun(text, true, ready[1]);
      _exit(0);
    }
    char c;
    ASSERT_EQ(read(ready[0], &c, 1), 1);
    close(ready[0]);
    close(ready[1]);
    usleep(static_cast<useconds_t>(std::uniform_real_distribution<double>(0.0, 1.5 * commitUs)(random)));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    completedLater += fs::exists(out + "/" + vp::RunFolder::CommitName()) ? 1 : 0;
    {
      vp::RunFolder next(out, "report.json");
      next.Begin(); // completes what the killed run committed, removes what it had not
    }
    const std::string report = vp::test::Slurp(out + "/report.json");
    int differing = 0;
    for (int i = 0; i < Files; ++i)
    {
      differing += vp::test::Slurp(out + "/f" + std::to_string(i) + ".txt") != report ? 1 : 0;
    }
    EXPECT_EQ(differing, 0) << "kill " << k << ": files of another run than the report's (" << report << ")";
    (report == text ? after : before) += 1;
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(out))
    {
      names.insert(entry.path().filename().string());
    }
    EXPECT_EQ(names.size(), static_cast<std::size_t>(Files + 2)) << "kill " << k << ": the run's files and the marker only";
    // The next kill starts from this run as the previous one.
    writeRun(text, false, -1);
  }
  std::printf("a commit of %d files takes %.1f ms; killed 16: %d before the commit's rename, %d after it (%d of them "
              "completed by the next run)\n",
    Files, commitUs / 1000.0, before, after, completedLater);
  fs::remove_all(dir);
}

TEST(RunFolder, AnInterruptWhileWritingActsOnlyOnceTheRunIsInPlace)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_signal");
  struct sigaction count = {}, previous = {};
  count.sa_handler = CountInterrupt;
  sigemptyset(&count.sa_mask);
  sigaction(SIGINT, &count, &previous);
  Interrupts = 0;
  {
    vp::RunFolder run(dir + "/out", "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "a");
    std::raise(SIGINT);
    EXPECT_EQ(Interrupts, 0) << "held while the files are written";
    WriteText(run.File("report.json"), R"({"files": ["a.stl", "report.json"]})");
    run.Commit();
    EXPECT_EQ(Interrupts, 1) << "acted on after the commit";
  }
  ExpectExactly(dir + "/out", { "a.stl", "report.json", Marker });
  // Without a commit: the run is removed first, then the interrupt acts.
  {
    vp::RunFolder run(dir + "/out2", "report.json");
    run.Begin();
    std::raise(SIGINT);
  }
  EXPECT_EQ(Interrupts, 2);
  EXPECT_FALSE(fs::exists(dir + "/out2"));
  sigaction(SIGINT, &previous, nullptr);
  fs::remove_all(dir);
}

// Issue 29: under nohup, SIGHUP stopped a run that should have ignored it.
TEST(RunFolder, AnIgnoredSignalStaysIgnored)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_ignored");
  struct sigaction ignore = {}, previous = {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGHUP, &ignore, &previous);
  {
    vp::RunFolder run(dir + "/out", "report.json");
    run.Begin();
    std::raise(SIGHUP);
    EXPECT_FALSE(vp::RunFolder::SignalPending()) << "an ignored signal is no reason to stop";
    WriteText(run.File("report.json"), "r");
    run.Commit();
  }
  struct sigaction now = {};
  sigaction(SIGHUP, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN) << "still ignored after the run";
  ExpectExactly(dir + "/out", { "report.json", Marker });
  sigaction(SIGHUP, &previous, nullptr);
  fs::remove_all(dir);
}
