// Issue 16's hostile inputs, each through the command a user reaches it with, in a child process
// whose own time and peak memory the test measures (wait4): one line naming the file, exit 1,
// nothing written, within seconds and megabytes. Before, some crashed, some took the machine's
// memory, some never ended.
#include "vpAnalyticShapes.h"
#include "vpModelTestSupport.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <filesystem>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
struct BoundedRun
{
  int ExitCode = -1;
  bool TimedOut = false;
  double Seconds = 0.0;
  long PeakKb = 0;
  std::string Out, Err;
};

/// The program on arguments in its own process, killed after limitS; its exit, its time, its peak
/// resident memory (its own, from wait4), and what it printed.
BoundedRun RunBounded(const std::string& dir, const std::string& program, const std::vector<std::string>& arguments, double limitS)
{
  const std::string out = dir + "/bounded_out.txt", err = dir + "/bounded_err.txt";
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = vp::test::StartProgram(program, arguments, out, err);
  BoundedRun run;
  int status = 0;
  struct rusage usage = {};
  while (wait4(child, &status, WNOHANG, &usage) == 0)
  {
    run.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (run.Seconds > limitS)
    {
      run.TimedOut = true;
      kill(child, SIGKILL);
      wait4(child, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.ExitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.PeakKb = usage.ru_maxrss;
  run.Out = vp::test::Slurp(out);
  run.Err = vp::test::Slurp(err);
  return run;
}
} // namespace

TEST(HostileInputs, EachIsRefusedInOneLineWithinSecondsAndMegabytes)
{
  const std::string dir = vp::test::MakeTempDir("hostile");
  using vp::test::WriteBytes;
  const double c[3] = { 0, 0, 0 };
  const std::string sphere = vp::test::WriteMeshFile(dir, "sphere.stl", vp::MakeSphere(c, 10.0, 16, 32));
  const std::string poses = WriteBytes(dir, "poses.csv", "time,x,y,z,qw,qx,qy,qz\n0,0,0,30,1,0,0,0\n0.1,0,0,29,1,0,0,0\n");
  const std::string fifo = dir + "/pipe.stl";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string gigabyte = dir + "/zeros.stl";
  std::ofstream(gigabyte).close();
  ASSERT_EQ(truncate(gigabyte.c_str(), off_t(1) << 30), 0); // sparse: no disk taken
  const std::vector<std::pair<std::string, std::string>> meshes = {
    { WriteBytes(dir, "far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999\n"), "line 4: face names vertex 99999999" },
    { WriteBytes(dir, "before.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n"), "line 4: face names vertex -5" },
    { WriteBytes(dir, "far.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
                                 "POLYGONS 1 4\n3 0 1 7000000\n"),
      "polygon 1 names point 7000000 of 3" },
    { WriteBytes(dir, "huge.vtk", "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET POLYDATA\nPOINTS 2000000000 float\n" +
                                    std::string(53, ' ')),
      "POINTS declares 2000000000 values" },
    { "/dev/zero", "is not a regular file" },
    { "/dev/urandom", "is not a regular file" },
    { fifo, "is not a regular file" },
    { gigabyte, "STL file has no triangles" },
  };
  struct Case
  {
    std::string Program;
    std::vector<std::string> Arguments;
    std::string Expected;
  };
  std::vector<Case> cases;
  for (const auto& [file, problem] : meshes)
  {
    cases.push_back({ VP_EXECUTABLE, { "distance", "--vessels", "portal_vein=" + file, "--tip", "0,0,0" }, file + ": " + problem });
  }
  cases.push_back({ VP_CLI_DISTANCE, { "--portalVein", meshes[0].first, "--tip", "0,0,0" }, meshes[0].first + ": " + meshes[0].second });
  const std::string out = dir + "/never";
  const std::vector<std::string> track = { "track", "--vessels", "a=" + sphere, "-o", out };
  const auto trackWith = [&](std::vector<std::string> more) {
    more.insert(more.begin(), track.begin(), track.end());
    return more;
  };
  cases.push_back({ VP_EXECUTABLE, trackWith({ "--scalpel", meshes[0].first, "--poses", poses }), meshes[0].first + ": " + meshes[0].second });
  cases.push_back({ VP_EXECUTABLE, trackWith({ "--scalpel", sphere, "--poses", "/dev/zero" }), "/dev/zero: is not a regular file" });
  cases.push_back({ VP_EXECUTABLE, trackWith({ "--scalpel", sphere, "--poses", fifo }), fifo + ": " });
  for (const auto& [program, arguments, expected] : cases)
  {
    std::string line = std::filesystem::path(program).filename().string();
    for (const std::string& a : arguments)
    {
      line += " " + a;
    }
    const BoundedRun r = RunBounded(dir, program, arguments, 20.0);
    std::printf("%5.2f s %7ld kB  %s\n", r.Seconds, r.PeakKb, line.c_str());
    EXPECT_FALSE(r.TimedOut) << line;
    EXPECT_EQ(r.ExitCode, 1) << line << "\n" << r.Err;
    EXPECT_NE(r.Err.find(expected), std::string::npos) << line << "\n  stderr: " << r.Err;
    EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << "one line: " << r.Err;
    EXPECT_EQ(r.Out, "") << line;
    EXPECT_LT(r.Seconds, 10.0) << line;
#ifndef VP_UNDER_ASAN
    EXPECT_LT(r.PeakKb, 400L * 1024L) << "kB, " << line;
#endif
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written: " << line;
  }
  std::filesystem::remove_all(dir);
}
