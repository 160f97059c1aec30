// Issue 16's hostile inputs, each through the command a user reaches it with, in a child process
// whose own time and peak memory the test measures (wait4): one line naming the file, exit 1,
// nothing written, within seconds and megabytes. Before, some crashed, some took the machine's
// memory, some never ended.
#include "vpAnalyticShapes.h"
#include "vpModelTestSupport.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <filesystem>
#include <sstream>
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
/// The command line as one line, for messages.
std::string CommandLine(const std::string& program, const std::vector<std::string>& arguments)
{
  std::string line = std::filesystem::path(program).filename().string();
  for (const std::string& a : arguments)
  {
    line += " " + (a.size() > 120 ? a.substr(0, 120) + "..." : a);
  }
  return line;
}

/// A hostile case run in its own process: one line on stderr holding expected, exit 1, nothing
/// on stdout (but a Slicer CLI's progress tags) and nothing at out, within 10 s and 400 MB.
void ExpectRefusedInOneLine(const std::string& dir, const std::string& program, const std::vector<std::string>& arguments,
  const std::string& expected, const std::string& out)
{
  const std::string line = CommandLine(program, arguments);
  const BoundedRun r = RunBounded(dir, program, arguments, 20.0);
  std::printf("%5.2f s %7ld kB  %s\n", r.Seconds, r.PeakKb, line.c_str());
  EXPECT_FALSE(r.TimedOut) << line;
  EXPECT_EQ(r.ExitCode, 1) << line << "\n" << r.Err;
  EXPECT_NE(r.Err.find(expected), std::string::npos) << line << "\n  stderr: " << r.Err;
  EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << "one line: " << r.Err;
  // Nothing on stdout but Slicer's progress tags (<filter-...>: how far the run came, no result).
  std::string printed;
  std::istringstream lines(r.Out);
  for (std::string l; std::getline(lines, l);)
  {
    printed += l.rfind("<filter-", 0) == 0 ? "" : l + "\n";
  }
  EXPECT_EQ(printed, "") << line;
  EXPECT_LT(r.Seconds, 10.0) << line;
#ifndef VP_UNDER_ASAN
  EXPECT_LT(r.PeakKb, 400L * 1024L) << "kB, " << line;
#endif
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written: " << line;
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
    ExpectRefusedInOneLine(dir, program, arguments, expected, out);
  }
  std::filesystem::remove_all(dir);
}

namespace
{
/// A sphere of radius 10 about the origin with this many rings and segments.
std::string SphereFile(const std::string& dir, const std::string& name, double radiusMm = 10.0, int rings = 16, int segments = 32)
{
  const double c[3] = { 0, 0, 0 };
  return vp::test::WriteMeshFile(dir, name, vp::MakeSphere(c, radiusMm, rings, segments));
}
} // namespace

// Issue 29's second hostile round, each case through the command a user reaches it with, in its
// own process, measured: a one-line error naming the input (exit 1), within seconds and a few
// hundred megabytes, nothing written; or, where there is one, the correct answer.
TEST(HostileInputs, TheSecondRoundIsRefusedInOneLineOrAnsweredCorrectly)
{
  namespace fs = std::filesystem;
  const std::string dir = vp::test::MakeTempDir("hostile2");
  using vp::test::WriteBytes;
  const std::string sphere = SphereFile(dir, "sphere.stl");
  const std::string tool = SphereFile(dir, "tool.stl", 1.5, 8, 16);
  const std::string poses = WriteBytes(dir, "poses.csv", "time,x,y,z,qw,qx,qy,qz\n0,0,0,30,1,0,0,0\n0.1,0,0,29,1,0,0,0\n");
  const std::string out = dir + "/never";
  const std::vector<std::string> track = { "track", "--vessels", "portal_vein=" + sphere, "--scalpel", tool, "-o", out };
  const auto with = [](std::vector<std::string> a, const std::vector<std::string>& more) {
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  const auto pointsFile = [&](const std::string& name, const std::string& line, int count) {
    std::string text;
    for (int i = 0; i < count; ++i)
    {
      text += line + "\n";
    }
    return WriteBytes(dir, name, text);
  };
  std::string collinear;
  for (int i = 0; i < 7; ++i)
  {
    collinear += std::to_string(i) + ",0,0\n";
  }
  const std::string cube1e20 = WriteBytes(dir, "far.obj",
    "v 1e20 1e20 1e20\nv 1.000001e20 1e20 1e20\nv 1e20 1.000001e20 1e20\nv 1e20 1e20 1.000001e20\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto nrrd = [&](const std::string& name, const std::string& directions) {
    return WriteBytes(dir, name, "NRRD0004\ntype: uint8\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 2 2\n"
                                 "space directions: " + directions + "\nspace origin: (0,0,0)\nencoding: raw\n\n" +
        std::string("\x01\x01\x01\x01\x00\x00\x00\x00", 8));
  };
  const std::string fifo = dir + "/pipe.json";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // A scalpel whose definition beside it is a pipe.
  const std::string piped = dir + "/piped/tool.stl";
  fs::create_directories(dir + "/piped");
  fs::copy_file(tool, piped);
  ASSERT_EQ(mkfifo((dir + "/piped/tool.json").c_str(), 0600), 0);
  const std::string bigMember = WriteBytes(dir, "member.json", "{\"notes\": \"" + std::string(3 << 20, 'x') +
      "\", \"poses\": [{\"time\": 0, \"position\": [0, 0, 30], \"quaternion\": [1, 0, 0, 0]}]}");
  const std::string bigNumber = WriteBytes(dir, "number.json", "{\"poses\": [{\"time\": 1" + std::string(3 << 20, '0') + "}]}");
  const std::string longLine = WriteBytes(dir, "line.csv", "0," + std::string(1 << 20, '1') + "\n");
  const std::string landmarks = pointsFile("landmarks.csv", "0,0,0\n10,0,0\n0,10,0\n0,0,10", 1);
  // A binary STL of 10 million triangles (sparse: 500 MB that take no disk).
  const std::uint32_t tenMillion = 10000000;
  const std::string tenMillionStl = WriteBytes(dir, "ten_million.stl",
    std::string(80, 'x') + std::string(reinterpret_cast<const char*>(&tenMillion), 4));
  ASSERT_EQ(truncate(tenMillionStl.c_str(), off_t(84) + off_t(50) * tenMillion), 0);

  struct Case
  {
    std::string Program;
    std::vector<std::string> Arguments;
    std::string Expected; // in the one line on stderr
  };
  const std::string vp = VP_EXECUTABLE;
  const std::string shell = "/bin/sh";
  const std::vector<Case> refused = {
    { vp, { "register", "icp", "--model", sphere, "--points", pointsFile("same.csv", "1,2,3", 7), "-o", out + "/r.json" },
      "ICP: the measured points lie on one line" },
    { vp, { "register", "icp", "--model", sphere, "--points", WriteBytes(dir, "line7.csv", collinear), "-o", out + "/r.json" },
      "ICP: the measured points lie on one line" },
    { vp, { "register", "icp", "--model", sphere, "--points", pointsFile("far.csv", "1e300,0,0", 7), "-o", out + "/r.json" },
      "far.csv: line 1: coordinate 1e+300 mm is beyond ±1e+06 mm" },
    { vp, { "distance", "--vessels", "portal_vein=" + cube1e20, "--tip", "0,0,0" }, cube1e20 + ": a coordinate of 1e+20 mm" },
    { vp, { "track", "--vessels", "portal_vein=" + tenMillionStl, "--scalpel", tool, "--poses", poses, "-o", out },
      tenMillionStl + ": binary STL of 10000000 triangles: a model holds at most 5e+06" },
    { vp, { "distance", "--vessels", "portal_vein=" + sphere, "--tip", "1e19,0,0" }, "--tip: the point: coordinate 1e+19 mm is beyond" },
    { vp, with(track, { "--poses", WriteBytes(dir, "far_pose.csv", "0,1e19,0,0,1,0,0,0\n") }), "far_pose.csv: line 1: position 1e+19 mm" },
    { vp, with(track, { "--poses", WriteBytes(dir, "late.csv", "0,0,0,30,1,0,0,0\n1.7e308,0,0,30,1,0,0,0\n") }),
      "late.csv: line 2: time 1.7e+308 s is beyond" },
    { vp, with(track, { "--poses", WriteBytes(dir, "early.csv", "-1.7e308,0,0,30,1,0,0,0\n") }), "early.csv: line 1: time -1.7e+308 s" },
    { vp, { "distance", "--vessels", "portal_vein=" + sphere, "--tip", "0,0,20", "--method", "zbuffer", "--cell", "1e-8" },
      "--cell: must be from 0.001 to 1000 millimetres" },
    { vp, { "distance", "--vessels", "portal_vein=" + sphere, "--tip", "0,0,20", "--range", "1e10" }, "--range: must be at most 2000" },
    { vp, { "models", nrrd("long.nrrd", "(1e155,0,0) (0,1,0) (0,0,1)"), "-o", out }, "gives a voxel axis 1e+155 mm long" },
    { vp, { "models", nrrd("nan.nrrd", "(nan,0,0) (0,1,0) (0,0,1)"), "-o", out }, "with a NaN or infinite value" },
    { vp, { "models", nrrd("small.nrrd", "(1e-300,0,0) (0,1,0) (0,0,1)"), "-o", out }, "gives a voxel axis 1e-300 mm long" },
    { vp, { "models", nrrd("labels.nrrd", "(1,0,0) (0,1,0) (0,0,1)"), "--labels", "/dev/zero", "-o", out },
      "/dev/zero: is not a regular file" },
    { vp, { "models", nrrd("labels.nrrd", "(1,0,0) (0,1,0) (0,0,1)"), "--labels", "/dev/urandom", "-o", out },
      "/dev/urandom: is not a regular file" },
    { vp, { "models", nrrd("labels.nrrd", "(1,0,0) (0,1,0) (0,0,1)"), "--labels", fifo, "-o", out }, fifo + ": is not a regular file" },
    { VP_CLI_MODELS, { "--labelTable", "/dev/zero", nrrd("labels.nrrd", "(1,0,0) (0,1,0) (0,0,1)"), "--outputDirectory", out },
      "/dev/zero: is not a regular file" },
    { vp, with(track, { "--poses", bigMember }), bigMember + ": a value of more than 1048576 characters" },
    { vp, with(track, { "--poses", bigNumber }), bigNumber + ": a value of more than 1048576 characters" },
    { vp, with(track, { "--poses", longLine }), longLine + ": line 1: longer than 65536 characters" },
    { vp, { "distance", "--vessels", "portal\nvein=" + sphere, "--tip", "0,0,20" },
      "--vessels: 'portal\\nvein': a class name holds letters, digits, '_' and '-' only" },
    { vp, { "track", "--vessels", "nearest=" + sphere, "--scalpel", tool, "--poses", poses, "-o", out },
      "--vessels: the class names give frames.csv two columns named 'nearest_mm'" },
    { vp, { "track", "--vessels", "x=" + sphere + ",x_surface=" + sphere, "--scalpel", tool, "--poses", poses, "-o", out },
      "two columns named 'x_surface_mm'" },
    { vp, { "track", "--vessels", "portal_vein=" + sphere, "--scalpel", piped, "--poses", poses, "-o", out },
      dir + "/piped/tool.json: is not a regular file" },
    { shell, { "-c", "TMPDIR=/nonexistent exec " + vp + " selftest --no-screenshots" }, "TMPDIR /nonexistent: is not a folder" },
    { vp, { "register", "landmarks", "--model-points", landmarks, "--world-points", landmarks, "-o", "/dev/full" },
      "/dev/full: write failed: No space left on device" },
    { vp, { "register", "landmarks", "--model-points", landmarks, "--world-points", landmarks, "-o", fifo },
      fifo + ": cannot write: no process reads this pipe" },
    { shell, { "-c", "exec " + vp + " distance --vessels portal_vein=" + sphere + " --tip 0,0,20 --json > /dev/full" },
      "vesselproximity: error: standard output: cannot write (No space left on device)" },
    { VP_CLI_DISTANCE, { "--portalVein", sphere, "--tip", "0,0,20", "--returnparameterfile", "/dev/full" },
      "/dev/full: write failed: No space left on device" },
    { VP_CLI_DISTANCE, { "--portalVein", sphere, "--tip", "0,0,20", "--report", "/dev/full" },
      "/dev/full: write failed: No space left on device" },
  };
  for (const auto& [program, arguments, expected] : refused)
  {
    ExpectRefusedInOneLine(dir, program, arguments, expected, out);
  }
  EXPECT_TRUE(fs::is_fifo(fifo)) << "the pipe was written through, not replaced";
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  fs::remove_all(dir);
}

// Issue 29: a tip deeper inside a vessel than the range read "out of range", every frame safe.
TEST(HostileInputs, ATipDeeperInsideThanTheRangeIsABreach)
{
  const std::string dir = vp::test::MakeTempDir("deep_inside");
  const std::string sphere = SphereFile(dir, "sphere.stl", 30.0, 32, 64);
  const std::string tool = SphereFile(dir, "tool.stl", 1.0, 8, 16);
  // The tip 25 mm from the wall (inside), a range of 12 mm (above the 10 mm caution threshold).
  for (const char* method : { "exact", "zbuffer", "both", "brute" })
  {
    const vp::test::ToolRun r = vp::test::RunTool(dir, std::string("distance --vessels portal_vein=") + sphere + " --tip 0,0,5 --range 12 --json --method " + method);
    ASSERT_EQ(r.ExitCode, 0) << method << ": " << r.Err;
    const auto c = nlohmann::json::parse(r.Out)["results"][0]["classes"]["portal_vein"];
    EXPECT_EQ(c["inside"], true) << method;
    EXPECT_EQ(c["in_range"], true) << method << ": inside is in range whatever the range";
    EXPECT_NEAR(c["distance_mm"].get<double>(), 25.0, 0.1) << method << ": the depth, however far the wall";
  }
  const BoundedRun cli = RunBounded(dir, VP_CLI_DISTANCE, { "--portalVein", sphere, "--tip", "0,0,5", "--rangeMm", "5" }, 20.0);
  ASSERT_EQ(cli.ExitCode, 0) << cli.Err;
  EXPECT_NE(cli.Out.find("nearestInside = true"), std::string::npos) << cli.Out;
  EXPECT_NE(cli.Out.find("nearestClass = portal_vein"), std::string::npos) << cli.Out;
  const std::string poses = vp::test::WriteBytes(dir, "poses.csv", "0,0,0,5,1,0,0,0\n0.1,0,0,6,1,0,0,0\n");
  for (const char* method : { "exact", "zbuffer" })
  {
    const std::string out = dir + "/track_" + method;
    const vp::test::ToolRun t = vp::test::RunTool(dir, "track --vessels portal_vein=" + sphere + " --scalpel " + tool + " --tip 0,0,0 --poses " +
        poses + " --range 12 --method " + method + " -o " + out);
    ASSERT_EQ(t.ExitCode, 0) << t.Err;
    const auto summary = nlohmann::json::parse(vp::test::Slurp(out + "/summary.json"));
    EXPECT_EQ(summary["worst_level"], "breach") << method;
    const std::string frames = vp::test::Slurp(out + "/frames.csv");
    EXPECT_EQ(std::count(frames.begin(), frames.end(), '\n'), 3) << frames;
    EXPECT_NE(frames.find(",breach,"), std::string::npos) << frames;
    EXPECT_EQ(frames.find(",safe,"), std::string::npos) << method << ": no frame safe\n" << frames;
  }
  std::filesystem::remove_all(dir);
}

// Issue 29, the answers that were wrong or lost without a word: a byte order mark ate the first
// row, an ignored SIGHUP still stopped a run, a million tips with --json took 3.5 GB.
TEST(HostileInputs, TheSecondRoundsQuietLossesAreGone)
{
  namespace fs = std::filesystem;
  const std::string dir = vp::test::MakeTempDir("hostile2_answers");
  const std::string sphere = SphereFile(dir, "sphere.stl");
  const std::string tool = SphereFile(dir, "tool.stl", 1.0, 8, 16);
  const std::string bom = "\xEF\xBB\xBF";
  std::string poseRows, tipRows;
  for (int i = 0; i < 10; ++i)
  {
    poseRows += std::to_string(0.1 * i) + ",0,0," + std::to_string(30 - i) + ",1,0,0,0\n";
  }
  const std::string poses = vp::test::WriteBytes(dir, "bom_poses.csv", bom + poseRows);
  const std::string tips = vp::test::WriteBytes(dir, "bom_tips.csv", bom + "0,0,20\n0,0,30\n0,0,40\n");
  const vp::test::ToolRun t = vp::test::RunTool(dir, "track --vessels portal_vein=" + sphere + " --scalpel " + tool +
      " --tip 0,0,0 --poses " + poses + " -o " + dir + "/bom");
  ASSERT_EQ(t.ExitCode, 0) << t.Err;
  EXPECT_EQ(nlohmann::json::parse(vp::test::Slurp(dir + "/bom/summary.json"))["frames"], 10) << "the first row is a pose";
  const vp::test::ToolRun d = vp::test::RunTool(dir, "distance --vessels portal_vein=" + sphere + " --tips " + tips + " --json");
  ASSERT_EQ(d.ExitCode, 0) << d.Err;
  const auto results = nlohmann::json::parse(d.Out)["results"];
  ASSERT_EQ(results.size(), 3u);
  EXPECT_NEAR(results[0]["classes"]["portal_vein"]["distance_mm"].get<double>(), 10.0, 0.1);

  // nohup: SIGHUP is ignored, and a run given one goes on to its end.
  std::string many;
  for (int i = 0; i < 20000; ++i)
  {
    many += std::to_string(0.01 * i) + ",0,0," + std::to_string(30.0 - 0.001 * i) + ",1,0,0,0\n";
  }
  const std::string longPoses = vp::test::WriteBytes(dir, "long.csv", many);
  const std::string hupOut = dir + "/hup";
  const pid_t child = vp::test::StartProgram("/bin/sh", { "-c", "trap '' HUP; exec " + std::string(VP_EXECUTABLE) +
      " track --vessels portal_vein=" + sphere + " --scalpel " + tool + " --tip 0,0,0 --no-surface --poses " + longPoses + " -o " + hupOut });
  ASSERT_GT(child, 0);
  for (int k = 0; k < 20; ++k)
  {
    usleep(50000);
    kill(child, SIGHUP);
  }
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
  EXPECT_EQ(nlohmann::json::parse(vp::test::Slurp(hupOut + "/summary.json"))["frames"], 20000);

  // 200,000 tips as JSON: memory follows a chunk of them, not all (3.5 GB for a million before).
  std::string lots = "x,y,z\n";
  for (int i = 0; i < 200000; ++i)
  {
    lots += std::to_string(-40 + (i % 80)) + "," + std::to_string(-40 + (i / 80) % 80) + "," + std::to_string(-20 + i % 7) + "\n";
  }
  const std::string lotsFile = vp::test::WriteBytes(dir, "lots.csv", lots);
  const BoundedRun big = RunBounded(dir, VP_EXECUTABLE, { "distance", "--vessels", "portal_vein=" + sphere, "--tips", lotsFile, "--json" }, 60.0);
  ASSERT_EQ(big.ExitCode, 0) << big.Err;
  EXPECT_EQ(nlohmann::json::parse(big.Out)["results"].size(), 200000u);
  std::printf("200,000 tips as JSON: %.2f s, %ld kB, %zu bytes out\n", big.Seconds, big.PeakKb, big.Out.size());
#ifndef VP_UNDER_ASAN
  EXPECT_LT(big.PeakKb, 150L * 1024L) << "kB for 200,000 tips";
#endif
  fs::remove_all(dir);
}

// Issue 29, the data lost: track with its inputs inside a previous run's folder and -o that
// folder deleted them; a run killed with SIGKILL left its staging folder for ever; outputs that
// were links were replaced by files.
TEST(HostileInputs, NothingTheRunDidNotWriteIsRemovedOrReplaced)
{
  namespace fs = std::filesystem;
  const std::string dir = vp::test::MakeTempDir("hostile2_loss");
  const std::string out = dir + "/run";
  fs::create_directories(out + "/models");
  const std::string sphere = SphereFile(out + "/models", "portal_vein.stl");
  const std::string tool = SphereFile(out, "tool.stl", 1.0, 8, 16);
  std::string rows;
  for (int i = 0; i < 3000; ++i)
  {
    rows += std::to_string(0.01 * i) + ",0,0," + std::to_string(30.0 - 0.001 * i) + ",1,0,0,0\n";
  }
  const std::string poses = vp::test::WriteBytes(out, "poses.csv", rows);
  vp::test::WriteBytes(out, "extra.txt", "the earlier run's own");
  // As the demo leaves its folder: the models, the scalpel and the poses are its own files.
  vp::test::RecordAsRun(out, { "models/", "tool.stl", "poses.csv", "extra.txt" });
  const std::string command = "track --vessels portal_vein=" + sphere + " --scalpel " + tool + " --tip 0,0,0 --poses " + poses + " -o " + out;
  const vp::test::ToolRun t = vp::test::RunTool(dir, command);
  ASSERT_EQ(t.ExitCode, 0) << t.Err;
  for (const std::string& input : { sphere, tool, poses })
  {
    EXPECT_TRUE(fs::exists(input)) << input << ": an input of the run";
  }
  EXPECT_FALSE(fs::exists(out + "/extra.txt")) << "the earlier run's file that is no input goes";
  EXPECT_TRUE(fs::exists(out + "/frames.csv"));

  // Killed with SIGKILL in the middle: the next run removes the staging folder it left.
  const pid_t child = vp::test::StartTool({ "track", "--vessels", "portal_vein=" + sphere, "--scalpel", tool, "--tip", "0,0,0",
    "--poses", poses, "-o", dir + "/killed" });
  ASSERT_GT(child, 0);
  bool staged = false;
  for (int k = 0; k < 400 && !staged; ++k)
  {
    usleep(10000);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir + "/killed", ec))
    {
      staged = staged || entry.path().filename().string().rfind(".vesselproximity-partial-", 0) == 0;
    }
  }
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  ASSERT_TRUE(staged) << "the run never staged anything";
  const vp::test::ToolRun again = vp::test::RunTool(dir, "track --vessels portal_vein=" + sphere + " --scalpel " + tool +
      " --tip 0,0,0 --poses " + poses + " -o " + dir + "/killed");
  ASSERT_EQ(again.ExitCode, 0) << again.Err;
  for (const auto& entry : fs::directory_iterator(dir + "/killed"))
  {
    EXPECT_EQ(entry.path().filename().string().rfind(".vesselproximity-", 0) == 0,
      entry.path().filename().string() == ".vesselproximity-run.json") << entry.path();
  }

  // An output that is a link: written through, the link kept.
  const std::string landmarks = vp::test::WriteBytes(dir, "landmarks.csv", "0,0,0\n10,0,0\n0,10,0\n0,0,10\n");
  vp::test::WriteBytes(dir, "target.json", "old");
  fs::create_symlink(dir + "/target.json", dir + "/link.json");
  const vp::test::ToolRun reg = vp::test::RunTool(dir, "register landmarks --model-points " + landmarks + " --world-points " +
      landmarks + " -o " + dir + "/link.json");
  ASSERT_EQ(reg.ExitCode, 0) << reg.Err;
  EXPECT_TRUE(fs::is_symlink(dir + "/link.json"));
  EXPECT_NE(vp::test::Slurp(dir + "/target.json").find("model_to_world"), std::string::npos);
  fs::remove_all(dir);
}

#ifndef VP_UNDER_ASAN
// Issue 29: a 10M-triangle vessel with the whole instrument ran FCL out of memory, and then the
// program crashed. Here a million triangles under an address-space limit that cannot hold FCL's
// tree: one line, no crash. (Not under the sanitizers: their shadow memory needs no limit.)
TEST(HostileInputs, AVesselTooLargeForTheMemoryLeftIsRefusedInOneLine)
{
  const std::string dir = vp::test::MakeTempDir("hostile2_memory");
  const std::string sphere = SphereFile(dir, "big.stl", 30.0, 500, 1000);
  const std::string tool = SphereFile(dir, "tool.stl", 1.0, 8, 16);
  const std::string poses = vp::test::WriteBytes(dir, "poses.csv", "0,0,0,60,1,0,0,0\n0.1,0,0,59,1,0,0,0\n");
  const BoundedRun r = RunBounded(dir, "/bin/sh", { "-c", "ulimit -v 1000000; exec " + std::string(VP_EXECUTABLE) +
    " track --vessels portal_vein=" + sphere + " --scalpel " + tool + " --tip 0,0,0 --poses " + poses + " -o " + dir + "/out" }, 60.0);
  std::printf("%.2f s, %ld kB: %s", r.Seconds, r.PeakKb, r.Err.c_str());
  EXPECT_EQ(r.ExitCode, 1) << r.Err;
  EXPECT_NE(r.Err.find("portal_vein: FCL's tree of its 998000 triangles"), std::string::npos) << r.Err;
  EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << r.Err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  std::filesystem::remove_all(dir);
}
#endif
