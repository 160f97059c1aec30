// vp::RunFolder (issue 16): an output folder holds one run, whole. A new run replaces the files
// of the previous one (and removes those it does not write again), never touches files of
// others, leaves the previous run exactly as it was when it fails, and holds SIGINT until its
// files are in place.
#include "vpRunFolder.h"
#include "vpInputError.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>

namespace
{
namespace fs = std::filesystem;

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

// Nothing but the given names (no staging folder, no temporary file).
void ExpectExactly(const std::string& folder, std::set<std::string> names)
{
  std::set<std::string> found;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    found.insert(entry.path().filename().string());
  }
  EXPECT_EQ(found, names) << folder;
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
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "a1");
    WriteText(run.File("b.stl"), "b1");
    WriteText(run.File("report.json"), R"({"files": ["a.stl", "b.stl", "report.json"]})");
    run.Commit();
  }
  WriteText(out + "/notes.txt", "the user's own");
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "a2");
    EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "a1") << "nothing changes before the commit";
    WriteText(run.File("report.json"), R"({"files": ["a.stl", "report.json"]})");
    run.Commit();
  }
  ExpectExactly(out, { "a.stl", "report.json", "notes.txt" });
  EXPECT_EQ(vp::test::Slurp(out + "/a.stl"), "a2");
  EXPECT_EQ(vp::test::Slurp(out + "/notes.txt"), "the user's own");
  // A models.json names its files under "structures".
  WriteText(out + "/models.json", R"({"structures": [{"file": "a.stl"}, {"file": "../outside"}]})");
  WriteText(dir + "/outside", "not in the folder");
  {
    vp::RunFolder run(out, "models.json");
    run.Begin();
    WriteText(run.File("models.json"), R"({"structures": []})");
    run.Commit();
  }
  ExpectExactly(out, { "models.json", "report.json", "notes.txt" });
  EXPECT_TRUE(fs::exists(dir + "/outside")) << "a report names files in its folder only";
  fs::remove_all(dir);
}

TEST(RunFolder, AFailedRunLeavesThePreviousOneExactlyAsItWas)
{
  const std::string dir = vp::test::MakeTempDir("runfolder_failed");
  const std::string out = dir + "/out";
  fs::create_directories(out);
  WriteText(out + "/a.stl", "a1");
  WriteText(out + "/report.json", R"({"files": ["a.stl", "report.json"]})");
  {
    vp::RunFolder run(out, "report.json");
    run.Begin();
    WriteText(run.File("a.stl"), "half");
    // destroyed without Commit(): an exception on the way, say
  }
  ExpectExactly(out, { "a.stl", "report.json" });
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
  ExpectExactly(dir + "/out", { "a.stl", "report.json" });
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
