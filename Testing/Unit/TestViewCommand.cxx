// vesselproximity view, scripted: keys move the scalpel, --screenshot renders off-screen.
#include "vpTestSupport.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <gtest/gtest.h>

#include <filesystem>

namespace
{
std::string PhantomVessels(const std::string& dir)
{
  return "--vessels portal_vein=" + dir + "/portal_vein.stl,hepatic_artery=" + dir + "/hepatic_artery.stl,hepatic_vein=" + dir +
    "/hepatic_vein.stl";
}
} // namespace

TEST(ViewCommand, KeysMoveTheScalpelAndAScreenshotIsWritten)
{
  const std::string tmp = vp::test::MakeTempDir("view");
  ASSERT_EQ(vp::test::RunTool(tmp, "phantom -o " + tmp).ExitCode, 0);
  // The default start: 30 mm anterior of the vessels' centre, pointing posterior. Five presses
  // of 'i' advance the tip 5 mm along its axis (+y); Shift is not pressed, so 1 mm each.
  auto still = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --size 320x240 --screenshot " + tmp + "/a.png");
  ASSERT_EQ(still.ExitCode, 0) << still.Err;
  auto moved = vp::test::RunTool(
    tmp, "view " + PhantomVessels(tmp) + " --size 320x240 --keys i,i,i,i,i --screenshot " + tmp + "/b.png");
  ASSERT_EQ(moved.ExitCode, 0) << moved.Err;
  double a[3], b[3];
  ASSERT_EQ(std::sscanf(still.Out.c_str(), "wrote %*s tip %lf, %lf, %lf", &a[0], &a[1], &a[2]), 3) << still.Out;
  ASSERT_EQ(std::sscanf(moved.Out.c_str(), "wrote %*s tip %lf, %lf, %lf", &b[0], &b[1], &b[2]), 3) << moved.Out;
  EXPECT_NEAR(b[0] - a[0], 0.0, 1e-6);
  EXPECT_NEAR(b[1] - a[1], 5.0, 1e-6);
  EXPECT_NEAR(b[2] - a[2], 0.0, 1e-6);
  vtkNew<vtkPNGReader> png;
  png->SetFileName((tmp + "/b.png").c_str());
  png->Update();
  int dims[3];
  png->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[0], 320);
  EXPECT_EQ(dims[1], 240);
  std::filesystem::remove_all(tmp);
}

TEST(ViewCommand, BadInputGivesOneLineAndNoScreenshot)
{
  const std::string tmp = vp::test::MakeTempDir("view_bad");
  ASSERT_EQ(vp::test::RunTool(tmp, "phantom -o " + tmp).ExitCode, 0);
  for (const std::string& bad : { std::string("--size 10x10"), std::string("--poses ") + tmp + "/missing.csv",
         std::string("--method brute"), std::string("--danger-mm 2,5,10") })
  {
    auto run = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " " + bad + " --screenshot " + tmp + "/x.png");
    EXPECT_EQ(run.ExitCode, 1) << bad;
    EXPECT_EQ(std::count(run.Err.begin(), run.Err.end(), '\n'), 1) << bad << ": " << run.Err;
    EXPECT_FALSE(vp::test::FileExists(tmp + "/x.png")) << bad;
  }
  // Issue 29: a screenshot is written as every output is: through a link (kept), never replacing
  // a device; /dev/full says it is full.
  const auto full = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --size 320x240 --screenshot /dev/full");
  EXPECT_EQ(full.ExitCode, 1);
  EXPECT_NE(full.Err.find("/dev/full: write failed: No space left on device"), std::string::npos) << full.Err;
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));
  vp::test::WriteBytes(tmp, "target.png", "an older picture");
  std::filesystem::create_symlink(tmp + "/target.png", tmp + "/link.png");
  const auto linked = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --size 320x240 --screenshot " + tmp + "/link.png");
  EXPECT_EQ(linked.ExitCode, 0) << linked.Err;
  EXPECT_TRUE(std::filesystem::is_symlink(tmp + "/link.png"));
  EXPECT_EQ(vp::test::Slurp(tmp + "/target.png").substr(1, 3), "PNG");
  // No display and no --screenshot: the window cannot open, and the message says so.
  auto run = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp), "env -u DISPLAY");
  EXPECT_EQ(run.ExitCode, 1);
  EXPECT_NE(run.Err.find("no display"), std::string::npos) << run.Err;
  std::filesystem::remove_all(tmp);
}

TEST(ViewCommand, SaysTheFrameTimesAndTheFramesOverTheBudget)
{
  const std::string tmp = vp::test::MakeTempDir("view_budget");
  ASSERT_EQ(vp::test::RunTool(tmp, "phantom -o " + tmp).ExitCode, 0);
  std::string poses = "time,x,y,z,qw,qx,qy,qz\n";
  for (int i = 0; i < 12; ++i)
  {
    poses += std::to_string(0.1 * i) + ",0,-40," + std::to_string(i) + ",1,0,0,0\n";
  }
  const std::string file = vp::test::WriteBytes(tmp, "poses.csv", poses);
  // --pose 7 shows poses 0 to 7 on the way: 8 frames. A budget no frame meets counts them all.
  auto over = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --poses " + file +
      " --pose 7 --frame-budget-ms 0.000001 --size 320x240 --screenshot " + tmp + "/a.png");
  ASSERT_EQ(over.ExitCode, 0) << over.Err;
  double median = -1, p95 = -1, max = -1;
  int late = -1, frames = -1;
  const std::size_t line = over.Out.find("frame median");
  ASSERT_NE(line, std::string::npos) << over.Out;
  ASSERT_EQ(std::sscanf(over.Out.c_str() + line, "frame median %lf ms, p95 %lf ms, max %lf ms; %d of %d frames over the 1e-06 ms budget",
              &median, &p95, &max, &late, &frames),
    5)
    << over.Out;
  EXPECT_EQ(frames, 8);
  EXPECT_EQ(late, 8);
  EXPECT_GT(median, 0.0);
  EXPECT_LE(median, p95);
  EXPECT_LE(p95, max);
  // The default budget (16.7 ms) and none at all.
  auto normal = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --poses " + file + " --pose 3 --size 320x240 --screenshot " +
      tmp + "/b.png");
  ASSERT_EQ(normal.ExitCode, 0) << normal.Err;
  EXPECT_NE(normal.Out.find(" of 4 frames over the 16.7 ms budget"), std::string::npos) << normal.Out;
  auto none = vp::test::RunTool(tmp, "view " + PhantomVessels(tmp) + " --poses " + file +
      " --pose 3 --frame-budget-ms 0 --size 320x240 --screenshot " + tmp + "/c.png");
  ASSERT_EQ(none.ExitCode, 0) << none.Err;
  EXPECT_NE(none.Out.find("; no frame budget"), std::string::npos) << none.Out;
  std::filesystem::remove_all(tmp);
}
