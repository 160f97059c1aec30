// Files a user brings from other programs, as they come: byte order marks, a point list that
// states its coordinate system twice, a manifest that is no regular file or names a case after
// the cohort's own files; and the cohort's cap on cases at once.
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
