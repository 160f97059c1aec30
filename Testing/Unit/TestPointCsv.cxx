#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <fstream>

TEST(PointCsv, HeaderCommentsBlankLinesAndSpaces)
{
  const std::string path = vp::test::MakeTempDir("csv") + "/tips.csv";
  std::ofstream(path) << "x,y,z\n1, 2 ,3\n\n# note\n-4.5,5e1,6\r\n";
  const auto points = vp::ReadPointCsv(path);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1][0], -4.5);
  EXPECT_EQ(points[1][1], 50.0);
  EXPECT_EQ(points[1][2], 6.0);
}

TEST(PointCsv, ErrorsNameTheLine)
{
  const std::string dir = vp::test::MakeTempDir("csvbad");
  const std::pair<std::string, std::string> cases[] = {
    { "1,2,3\nx,y,z\n", "line 2:" },
    { "1,2,3,4\n", "line 1: expected x,y,z (3 numbers), got 4" },
    { "x,y,z\n", "nothing in it: expected a point list" },
    { "1,2,inf\n", "line 1: NaN or infinite value" },
  };
  int i = 0;
  for (const auto& c : cases)
  {
    const std::string path = dir + "/c" + std::to_string(i++) + ".csv";
    std::ofstream(path) << c.first;
    try
    {
      vp::ReadPointCsv(path);
      ADD_FAILURE() << "no error for " << c.first;
    }
    catch (const vp::InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(path + ": " + c.second), std::string::npos) << e.what();
    }
  }
}
