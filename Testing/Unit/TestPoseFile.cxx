// Pose streams: the two CSV forms and JSON give the same rigid poses; every bad line is refused
// with its line (or pose) number.
#include "vpInputError.h"
#include "vpPoseFile.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

namespace
{
class PoseFile : public ::testing::Test
{
protected:
  void SetUp() override { this->Dir = vp::test::MakeTempDir("poses"); }

  std::string Write(const std::string& name, const std::string& text)
  {
    const std::string path = this->Dir + "/" + name;
    std::ofstream(path) << text;
    return path;
  }

  // The one-line refusal of a pose file.
  std::string Refusal(const std::string& name, const std::string& text)
  {
    const std::string path = this->Write(name, text);
    try
    {
      vp::ReadPoseFile(path);
    }
    catch (const vp::InputError& e)
    {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      return message.substr(path.size() + 2);
    }
    return "read";
  }

  std::string Dir;
};

// 90 degrees about z: x -> y. As a quaternion (w, x, y, z) = (cos 45, 0, 0, sin 45).
const std::string RotZ90 = "0,-1,0,10, 1,0,0,20, 0,0,1,30, 0,0,0,1";
const double H = std::sqrt(0.5);

TEST_F(PoseFile, MatrixQuaternionAndJsonFormsAgree)
{
  const auto matrix = vp::ReadPoseFile(this->Write("m.csv", "time,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33\n"
                                                               "0.0," + RotZ90 + "\n# a comment\n\n0.5," + RotZ90 + "\n"));
  const auto quaternion = vp::ReadPoseFile(this->Write("q.csv", "t,x,y,z,qw,qx,qy,qz\n0,10,20,30,0.7071,0,0,0.7071\n"));
  const auto json = vp::ReadPoseFile(this->Write("p.json",
    "{\"poses\": [{\"time\": 0, \"position\": [10, 20, 30], \"quaternion\": [" + std::to_string(H) + ", 0, 0, " +
      std::to_string(H) + "]}, {\"time\": 1, \"matrix\": [" + RotZ90 + "]}]}"));
  ASSERT_EQ(matrix.size(), 2u);
  ASSERT_EQ(quaternion.size(), 1u);
  ASSERT_EQ(json.size(), 2u);
  EXPECT_DOUBLE_EQ(matrix[1].TimeS, 0.5);
  for (int i = 0; i < 16; ++i)
  {
    EXPECT_NEAR(quaternion[0].ModelToWorld[i], matrix[0].ModelToWorld[i], 1e-6) << i;
    EXPECT_NEAR(json[0].ModelToWorld[i], matrix[0].ModelToWorld[i], 1e-6) << i;
    EXPECT_NEAR(json[1].ModelToWorld[i], matrix[0].ModelToWorld[i], 1e-12) << i;
  }
}

TEST_F(PoseFile, EachBadLineIsNamed)
{
  const std::string q = "0,0,0,0,1,0,0,0\n";
  EXPECT_EQ(this->Refusal("columns.csv", q + "1,0,0,0,1,0,0\n"),
    "line 2: expected 17 numbers (time and a 4x4 matrix) or 8 (time, x,y,z, qw,qx,qy,qz), got 7");
  EXPECT_EQ(this->Refusal("nan.csv", "t,x,y,z,qw,qx,qy,qz\n" + q + "1,nan,0,0,1,0,0,0\n"), "line 3: NaN or infinite value");
  EXPECT_EQ(this->Refusal("time.csv", q + "1,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n"), "line 3: time 1 is not after the previous 1");
  EXPECT_EQ(this->Refusal("back.csv", q + "-1,0,0,0,1,0,0,0\n"), "line 2: time -1 is not after the previous 0");
  EXPECT_EQ(this->Refusal("unit.csv", "0,0,0,0,0.9,0,0,0\n"), "line 1: the quaternion is not of unit length (|q| = 0.9)");
  EXPECT_EQ(this->Refusal("scaled.csv", "0,2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1\n"),
    "line 1: the rotation is not orthonormal (|R^T R - I| = 3)");
  EXPECT_EQ(this->Refusal("mirror.csv", "0,-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1\n"),
    "line 1: the rotation is a reflection (determinant -1)");
  EXPECT_EQ(this->Refusal("row.csv", "0,1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1\n"), "line 1: the last matrix row is not 0 0 0 1");
  EXPECT_EQ(this->Refusal("mixed.csv", q + "1," + RotZ90 + "\n"), "line 2: 17 numbers where the first pose has 8");
  EXPECT_EQ(this->Refusal("text.csv", q + "1,0,0,zero,1,0,0,0\n"), "line 2: '1,0,0,zero,1,0,0,0' is not a list of numbers");
  EXPECT_EQ(this->Refusal("empty.csv", "t,x,y,z,qw,qx,qy,qz\n"),
    "nothing in it: expected a pose list (time,m00..m33 or time,x,y,z,qw,qx,qy,qz per line)");
  EXPECT_EQ(this->Refusal("missing.json", "{\"poses\": []}"),
    "no poses: expected {\"poses\": [{\"time\": ..., \"matrix\": [...]}, ...]}");
  EXPECT_EQ(this->Refusal("bad.json", "{\"poses\": [{\"time\": 0, \"matrix\": [" + RotZ90 +
      "]}, {\"time\": 1, \"position\": [0, 0, 0], \"quaternion\": [1, 1, 0, 0]}]}"),
    "pose 2: the quaternion is not of unit length (|q| = 1.41421)");
  EXPECT_EQ(this->Refusal("short.json", "{\"poses\": [{\"time\": 0, \"matrix\": [1, 0, 0]}]}"),
    "pose 1: \"matrix\" is not an array of 16 numbers");
  EXPECT_EQ(this->Refusal("late.json", "{\"poses\": [{\"time\": 2, \"matrix\": [" + RotZ90 + "]}, {\"time\": 1, \"matrix\": [" +
      RotZ90 + "]}]}"),
    "pose 2: time 1 is not after the previous 2");
  EXPECT_NE(this->Refusal("broken.json", "{\"poses\": [").find("not valid JSON"), std::string::npos);
  EXPECT_EQ(vp::ReadPoseFile(this->Write("ok.csv", q)).size(), 1u);
}
} // namespace
