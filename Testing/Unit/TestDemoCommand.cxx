// vesselproximity demo and selftest refuse bad arguments with one line and write nothing. Their
// full runs are the ctest ModuleSelfTest.
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

TEST(DemoCommand, BadArgumentsGiveOneLineAndWriteNothing)
{
  const std::string tmp = vp::test::MakeTempDir("demo_bad");
  // A file where the output folder should be: it cannot be created.
  std::ofstream(tmp + "/taken") << "a file\n";
  for (const std::string& command : { std::string("demo -o ") + tmp + "/taken/out", std::string("demo stray -o ") + tmp + "/a",
         std::string("selftest stray -o ") + tmp + "/b", std::string("demo --frobnicate -o ") + tmp + "/c" })
  {
    const auto run = vp::test::RunTool(tmp, command);
    EXPECT_EQ(run.ExitCode, 1) << command;
    EXPECT_EQ(std::count(run.Err.begin(), run.Err.end(), '\n'), 1) << command << ": " << run.Err;
    EXPECT_EQ(run.Out, "") << command;
  }
  for (const char* folder : { "/taken/out", "/a", "/b", "/c" })
  {
    EXPECT_FALSE(vp::test::FileExists(tmp + folder)) << folder;
  }
  std::filesystem::remove_all(tmp);
}
