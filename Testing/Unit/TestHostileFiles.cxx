// Files a user brings from other programs, as they come: byte order marks, a point list that
// states its coordinate system twice, a manifest that is no regular file or names a case after
// the cohort's own files; and the cohort's cap on cases at once.
#include "vpCliDescription.h"
#include "vpCohortManifest.h"
#include "vpCohortRun.h"
#include "vpColorTableFile.h"
#include "vpInputError.h"
#include "vpMarkupsFile.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
const std::string Bom = "\xEF\xBB\xBF";

std::string Refusal(const std::function<void()>& read)
{
  try
  {
    read();
  }
  catch (const vp::InputError& e)
  {
    return e.what();
  }
  return std::string();
}
} // namespace

TEST(HostileFiles, AFcsvThatStatesItsCoordinateSystemTwiceDifferentlyIsRefused)
{
  const std::string head = "# Markups fiducial file version = 4.11\n";
  const std::string point = "vtkMRMLMarkupsFiducialNode_0,10,20,30,0,0,0,1,1,1,0,F-1,,\n";
  const std::string both = head + "# CoordinateSystem = LPS\n# CoordinateSystem = RAS\n" + point;
  EXPECT_NE(Refusal([&] { vp::ParseMarkupsPoints(both, true, "p.fcsv"); }).find("a second CoordinateSystem (RAS) that contradicts"),
    std::string::npos);
  // Stated twice alike, and with a byte order mark: read as one.
  const auto same = vp::ParseMarkupsPoints(Bom + head + "# CoordinateSystem = RAS\n# CoordinateSystem = RAS\n" + point, true, "p.fcsv");
  ASSERT_EQ(same.size(), 1u);
  EXPECT_DOUBLE_EQ(same[0].PositionLps[0], -10.0) << "RAS read into LPS";
  EXPECT_DOUBLE_EQ(same[0].PositionLps[2], 30.0);
}

TEST(HostileFiles, AColourTableWithAByteOrderMarkIsRead)
{
  const auto names = vp::ParseColorTableNames(Bom + "# Color table file\n5 Liver 200 100 100 255\n", "t.ctbl");
  ASSERT_EQ(names.count(5), 1u);
  EXPECT_EQ(names.at(5), "Liver");
}

TEST(HostileFiles, AManifestIsARegularCsvFileAndItsCasesAreNotTheCohortsFiles)
{
  const std::string dir = vp::test::MakeTempDir("manifest");
  std::ofstream(dir + "/excel.csv") << Bom << "case,segmentation\r\np1,seg1\r\n";
  const auto cases = vp::ReadCohortManifest(dir + "/excel.csv");
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_EQ(cases[0].Name, "p1");
  ASSERT_EQ(mkfifo((dir + "/fifo.csv").c_str(), 0600), 0);
  EXPECT_NE(Refusal([&] { vp::ReadCohortManifest(dir + "/fifo.csv"); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(Refusal([&] { vp::ReadCohortManifest("/dev/zero"); }).find("not a regular file"), std::string::npos);
  for (const char* name : { "cohort.png", "COHORT.csv", "cohort-1-of-2.csv" })
  {
    std::ofstream(dir + "/named.csv") << "case,segmentation\n" << name << ",seg\n";
    EXPECT_NE(Refusal([&] { vp::ReadCohortManifest(dir + "/named.csv"); }).find("one of the cohort's own files"), std::string::npos)
      << name;
  }
  std::filesystem::remove_all(dir);
}

TEST(HostileFiles, CasesAtOnceAreCappedAtTheCoresAndSaySo)
{
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string why;
  EXPECT_EQ(vp::CohortJobsFor(256, 1000, why), std::min(cores, vp::CohortJobsFor(cores, 1000, why)));
  EXPECT_LE(vp::CohortJobsFor(256, 1000, why), cores);
  EXPECT_NE(why.find("-j 256 capped at"), std::string::npos) << why;
  EXPECT_EQ(vp::CohortJobsFor(1, 1000, why), 1);
  EXPECT_EQ(why, "");
  EXPECT_EQ(vp::CohortJobsFor(64, 1, why), 1) << "one case: one at once, nothing to say";
  EXPECT_EQ(why, "");
}

// No output replaces an input: a command line whose output file is one of its inputs (by device
// and inode, through a hard link or a list entry "NAME=FILE" too), is a symbolic link, or is named
// twice, is refused at parsing, before any work.
TEST(HostileFiles, NoOutputFileNamesAnInput)
{
  using vp::cli::Channel;
  using vp::cli::Parameter;
  using vp::cli::ParameterType;
  vp::cli::ModuleDescription d;
  d.Program = "Guarded";
  d.Title = d.Description = d.Version = d.Category = "x";
  vp::cli::ParameterGroup g{ "io", "io", {} };
  g.Parameters.push_back(Parameter(ParameterType::String, "vessels").SetLongFlag("vessels").SetLabel("V").SetDescription("x"));
  g.Parameters.push_back(Parameter(ParameterType::File, "table").SetLongFlag("table").SetChannel(Channel::Output).SetLabel("T").SetDescription("x"));
  g.Parameters.push_back(Parameter(ParameterType::File, "report").SetLongFlag("report").SetChannel(Channel::Output).SetLabel("R").SetDescription("x"));
  d.Groups.push_back(g);
  const std::string dir = vp::test::MakeTempDir("guard");
  std::ofstream(dir + "/vein.stl") << "solid";
  std::filesystem::create_hard_link(dir + "/vein.stl", dir + "/alias.csv");
  std::filesystem::create_symlink(dir + "/elsewhere.txt", dir + "/link.csv");
  const std::string vessels = "portal_vein=" + dir + "/vein.stl,hepatic_vein=" + dir + "/none.stl";
  const auto refusal = [&](const std::vector<std::string>& args) { return Refusal([&] { vp::cli::ParseArguments(d, args); }); };
  EXPECT_NE(refusal({ "--vessels", vessels, "--table", dir + "/vein.stl" }).find("--table: '" + dir + "/vein.stl' is also an input (--vessels"),
    std::string::npos);
  EXPECT_NE(refusal({ "--vessels", vessels, "--table", dir + "/alias.csv" }).find("is also an input"), std::string::npos) << "a hard link";
  EXPECT_EQ(refusal({ "--vessels", vessels, "--table", dir + "/link.csv" }), "") << "our own link, to a new file";
  std::filesystem::create_symlink(dir + "/vein.stl", dir + "/to_input.csv");
  EXPECT_NE(refusal({ "--vessels", vessels, "--table", dir + "/to_input.csv" }).find("is also an input"), std::string::npos)
    << "a link to an input";
  std::ofstream(dir + "/old.csv") << "x";
  EXPECT_NE(refusal({ "--table", dir + "/old.csv", "--report", dir + "/old.csv" }).find("named by another output"), std::string::npos);
  EXPECT_NE(refusal({ "--vessels", vessels, "--table", dir + "/t.csv", "--returnparameterfile", dir + "/vein.stl" })
              .find("--returnparameterfile: '" + dir + "/vein.stl' is also an input"),
    std::string::npos);
  EXPECT_EQ(refusal({ "--vessels", vessels, "--table", dir + "/old.csv", "--report", dir + "/new.json" }), "") << "writing over an old output";
  EXPECT_FALSE(std::filesystem::exists(dir + "/elsewhere.txt"));
  EXPECT_EQ(std::filesystem::file_size(dir + "/vein.stl"), 5u);
  std::filesystem::remove_all(dir);
}

// The real commands: bench's report over a vessel model, view's screenshot over one, and a
// cohort case whose poses file is named as the cohort's picture in OUTDIR: each one line, exit 1,
// the input intact.
TEST(HostileFiles, CommandsRefuseAnOutputOverAnInput)
{
  const std::string dir = vp::test::MakeTempDir("guard_commands");
  ASSERT_EQ(vp::test::RunTool(dir, "phantom -o " + dir).ExitCode, 0);
  const std::string vein = dir + "/portal_vein.stl";
  const auto size = std::filesystem::file_size(vein);
  const std::string vessels = " --vessels portal_vein=" + vein + ",hepatic_vein=" + dir + "/hepatic_vein.stl";
  for (const std::string& command : { "bench --engines exact" + vessels + " -o " + vein, "view" + vessels + " --screenshot " + vein })
  {
    const vp::test::ToolRun r = vp::test::RunTool(dir, command);
    EXPECT_EQ(r.ExitCode, 1) << command;
    EXPECT_NE(r.Err.find("'" + vein + "' is also an input (--vessels"), std::string::npos) << r.Err;
    EXPECT_EQ(std::count(r.Err.begin(), r.Err.end(), '\n'), 1) << r.Err;
    EXPECT_EQ(std::filesystem::file_size(vein), size);
  }
  // A Slicer CLI as Slicer would never call it, but a script might: its frames table over its poses.
  const std::string poses = dir + "/p.csv";
  std::ofstream(poses) << "time,x,y,z,qw,qx,qy,qz\n0,0,0,40,1,0,0,0\n";
  const std::string cli = std::string(VP_CLI_TRACK) + " --portalVein " + vein + " --poses " + poses + " --framesTable " + poses +
    " >" + dir + "/cli.out 2>" + dir + "/cli.err";
  EXPECT_EQ(WEXITSTATUS(std::system(cli.c_str())), 1);
  EXPECT_NE(vp::test::Slurp(dir + "/cli.err").find("--framesTable: '" + poses + "' is also an input (--poses"), std::string::npos)
    << vp::test::Slurp(dir + "/cli.err");
  EXPECT_EQ(vp::test::Slurp(poses).substr(0, 4), "time");
  // As root too, a link another user made at a file that is not theirs is not written through.
  if (::geteuid() == 0)
  {
    std::ofstream(dir + "/roots.txt") << "root's";
    std::filesystem::create_symlink(dir + "/roots.txt", dir + "/planted.json");
    ASSERT_EQ(::lchown((dir + "/planted.json").c_str(), 65534, 65534), 0);
    const vp::test::ToolRun planted = vp::test::RunTool(dir, "bench --engines exact" + vessels + " -o " + dir + "/planted.json");
    EXPECT_EQ(planted.ExitCode, 1);
    EXPECT_NE(planted.Err.find("a symbolic link made by another user"), std::string::npos) << planted.Err;
    EXPECT_EQ(vp::test::Slurp(dir + "/roots.txt"), "root's");
  }
  std::filesystem::create_directories(dir + "/out");
  std::ofstream(dir + "/out/cohort.png") << "time,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n";
  std::filesystem::create_directories(dir + "/plan");
  std::ofstream(dir + "/plan/manifest.csv") << "case,segmentation,poses\np1," << dir << "/seg," << dir << "/out/cohort.png\n";
  const vp::test::ToolRun batch = vp::test::RunTool(dir, "batch " + dir + "/plan/manifest.csv -o " + dir + "/out");
  EXPECT_EQ(batch.ExitCode, 1);
  EXPECT_NE(batch.Err.find("case 'p1' reads " + dir + "/out/cohort.png, a file the cohort writes"), std::string::npos) << batch.Err;
  EXPECT_EQ(vp::test::Slurp(dir + "/out/cohort.png").substr(0, 4), "time");
  std::filesystem::remove_all(dir);
}
