// Pose streams: the two CSV forms and JSON give the same rigid poses; every bad line is refused
// with its line (or pose) number.
#include "vpInputError.h"
#include "vpPoseFile.h"
#include "vpTrackedSequence.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
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

namespace
{
// Issue 31: a file says what its numbers are, by its header's names and its declarations, or
// the front end does; the same poses written every way users write them read as the same poses.
void ExpectSamePoses(const std::vector<vp::TrackedPose>& a, const std::vector<vp::TrackedPose>& b, double tolerance, const std::string& what)
{
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t p = 0; p < a.size(); ++p)
  {
    EXPECT_NEAR(a[p].TimeS, b[p].TimeS, 1e-12) << what << " pose " << p;
    for (int i = 0; i < 16; ++i)
    {
      EXPECT_NEAR(a[p].ModelToWorld[i], b[p].ModelToWorld[i], tolerance) << what << " pose " << p << " entry " << i;
    }
  }
}

// Two poses, in LPS millimetres and seconds: at (10,20,30) turned 90 degrees about z, then at
// (-40,5,12) turned 60 degrees about x.
const double C60 = 0.5, S60 = std::sqrt(0.75), C30 = std::sqrt(0.75), S30 = 0.5;
std::string ScalarFirst(const std::string& header)
{
  char text[400];
  std::snprintf(text, sizeof text, "%s0,10,20,30,%.17g,0,0,%.17g\n0.5,-40,5,12,%.17g,%.17g,0,0\n", header.c_str(), H, H, C30, S30);
  return text;
}
} // namespace

TEST_F(PoseFile, HeaderNamesPlaceTheColumnsInAnyOrder)
{
  const auto first = vp::ReadPoseFile(this->Write("first.csv", ScalarFirst("time,x,y,z,qw,qx,qy,qz\n")));
  char text[400];
  // Scalar last (ROS, Eigen's coefficients), positions named tx..tz, time last.
  std::snprintf(text, sizeof text, "tx,ty,tz,qx,qy,qz,qw,timestamp\n10,20,30,0,0,%.17g,%.17g,0\n-40,5,12,%.17g,0,0,%.17g,0.5\n", H, H,
    S30, C30);
  ExpectSamePoses(vp::ReadPoseFile(this->Write("last.csv", text)), first, 0.0, "scalar last");
  // The matrix by name, its columns shuffled: m33 first.
  std::string header = "m33", row0 = "1", row1 = "1";
  const auto& m0 = first[0].ModelToWorld;
  const auto& m1 = first[1].ModelToWorld;
  for (int k = 0; k < 15; ++k)
  {
    header += ",m" + std::to_string(k / 4) + std::to_string(k % 4);
    row0 += "," + vp::FixedText(m0[k], "%.17g");
    row1 += "," + vp::FixedText(m1[k], "%.17g");
  }
  const auto matrix = vp::ReadPoseFile(this->Write("m.csv", header + ",time\n" + row0 + ",0\n" + row1 + ",0.5\n"));
  ExpectSamePoses(matrix, first, 1e-15, "matrix by name");
  EXPECT_NEAR(first[1].ModelToWorld[5], C60, 1e-12); // 60 degrees about x
  EXPECT_NEAR(first[1].ModelToWorld[9], S60, 1e-12);
}

TEST_F(PoseFile, MetresRasAndMillisecondsReadAsTheSettingsOrTheFileSay)
{
  const auto lps = vp::ReadPoseFile(this->Write("lps.csv", ScalarFirst("time,x,y,z,qw,qx,qy,qz\n")));
  // The same poses in RAS metres with times in ms: x and y negated (rotation too), positions / 1000.
  std::string ras = "time,x,y,z,qw,qx,qy,qz\n";
  for (const vp::TrackedPose& p : lps)
  {
    std::array<double, 16> m = p.ModelToWorld;
    for (int k = 0; k < 8; ++k)
    {
      m[k] = -m[k];
    }
    // The rotation of m as a quaternion, from its largest component (Shepperd): the RAS turn of
    // a pose can be a half turn, where the trace alone divides by zero.
    const double t[4] = { 1.0 + m[0] + m[5] + m[10], 1.0 + m[0] - m[5] - m[10], 1.0 - m[0] + m[5] - m[10], 1.0 - m[0] - m[5] + m[10] };
    double w = 0, x = 0, y = 0, z = 0;
    if (t[0] >= t[1] && t[0] >= t[2] && t[0] >= t[3])
    {
      w = 0.5 * std::sqrt(t[0]), x = (m[9] - m[6]) / (4 * w), y = (m[2] - m[8]) / (4 * w), z = (m[4] - m[1]) / (4 * w);
    }
    else if (t[1] >= t[2] && t[1] >= t[3])
    {
      x = 0.5 * std::sqrt(t[1]), w = (m[9] - m[6]) / (4 * x), y = (m[1] + m[4]) / (4 * x), z = (m[2] + m[8]) / (4 * x);
    }
    else if (t[2] >= t[3])
    {
      y = 0.5 * std::sqrt(t[2]), w = (m[2] - m[8]) / (4 * y), x = (m[1] + m[4]) / (4 * y), z = (m[6] + m[9]) / (4 * y);
    }
    else
    {
      z = 0.5 * std::sqrt(t[3]), w = (m[4] - m[1]) / (4 * z), x = (m[2] + m[8]) / (4 * z), y = (m[6] + m[9]) / (4 * z);
    }
    char line[300];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", 1000.0 * p.TimeS, m[3] / 1000.0,
      m[7] / 1000.0, m[11] / 1000.0, w, x, y, z);
    ras += line;
  }
  vp::PoseReading settings;
  settings.Space = vp::PoseSpace::RAS;
  settings.MillimetresPerUnit = 1000.0;
  settings.SecondsPerUnit = 0.001;
  ExpectSamePoses(vp::ReadPoseFile(this->Write("ras.csv", ras), settings), lps, 1e-9, "settings");
  ExpectSamePoses(vp::ReadPoseFile(this->Write("declared.csv", "# recorded in Slicer\n# pose-space: RAS\n# pose-units = m\n"
                                                                 "# Time-Units: ms\n" + ras)),
    lps, 1e-9, "comment declarations");
  const std::string body = ras.substr(ras.find('\n') + 1);
  std::string json = "{\"space\": \"RAS\", \"units\": \"m\", \"time_units\": \"ms\", \"poses\": [";
  for (std::size_t start = 0, n = 0; start < body.size(); ++n)
  {
    const std::size_t end = body.find('\n', start);
    const std::string row = body.substr(start, end - start);
    std::vector<std::string> f;
    for (std::size_t a = 0, b; (b = row.find(',', a)) != std::string::npos || a <= row.size(); a = b + 1)
    {
      f.push_back(row.substr(a, b == std::string::npos ? std::string::npos : b - a));
      if (b == std::string::npos)
      {
        break;
      }
    }
    json += (n ? "," : "") + std::string("{\"time\": ") + f[0] + ", \"position\": [" + f[1] + "," + f[2] + "," + f[3] +
      "], \"quaternion\": [" + f[4] + "," + f[5] + "," + f[6] + "," + f[7] + "]}";
    start = end + 1;
  }
  ExpectSamePoses(vp::ReadPoseFile(this->Write("declared.json", json + "], \"units\": \"m\"}")), lps, 1e-9, "JSON declarations");
  // Unread, the same file is 1000 times too small and mirrored: the reader cannot know, the scene can (track's warnings).
  EXPECT_NEAR(vp::ReadPoseFile(this->Write("plain.csv", ras))[0].ModelToWorld[3], -0.010, 1e-12);
}

TEST_F(PoseFile, AHeaderOrADeclarationItCannotPlaceIsRefusedNamingTheColumn)
{
  const std::string row = "0,10,20,30,1,0,0,0\n";
  EXPECT_EQ(this->Refusal("unknown.csv", "time,x,y,z,qw,qx,qy,qk\n" + row),
    "header: column 8 'qk' is not a pose column (time; x,y,z or tx,ty,tz; qw,qx,qy,qz in any order; or m00..m33)");
  EXPECT_EQ(this->Refusal("twice.csv", "time,x,y,x,qw,qx,qy,qz\n" + row), "header: column 4 'x' names a value already given");
  EXPECT_EQ(this->Refusal("notime.csv", "x,y,z,qw,qx,qy,qz\n10,20,30,1,0,0,0\n"),
    "header: no time column (time; x,y,z or tx,ty,tz; qw,qx,qy,qz in any order; or m00..m33)");
  EXPECT_EQ(this->Refusal("missing.csv", "time,x,y,z,qw,qx,qy,m00\n" + row),
    "header: both a matrix and a position or quaternion (time; x,y,z or tx,ty,tz; qw,qx,qy,qz in any order; or m00..m33)");
  EXPECT_EQ(this->Refusal("short.csv", "time,x,y,z,qw,qx,qy,tx\n" + row), "header: column 8 'tx' names a value already given");
  EXPECT_EQ(this->Refusal("unit.csv", "# pose-units: inch\n" + row), "declares pose-units 'inch'; expected mm or m");
  EXPECT_EQ(this->Refusal("late.json", "{\"poses\": [{\"time\": 0, \"position\": [1, 2, 3], \"quaternion\": [1, 0, 0, 0]}], "
                                       "\"units\": \"m\"}"),
    "declares its units after its poses, which were read otherwise: put the declaration before \"poses\"");
  // A setting the file contradicts names the setting (the front end spells it as its flag).
  const std::string declared = this->Write("ras.csv", "# pose-space: RAS\n" + row);
  vp::PoseReading lps;
  lps.Space = vp::PoseSpace::LPS;
  try
  {
    vp::ReadPoseFile(declared, lps);
    ADD_FAILURE() << "LPS was taken for a file that says RAS";
  }
  catch (const vp::ParameterError& e)
  {
    EXPECT_EQ(e.GetParameter(), "PoseSpace");
    EXPECT_EQ(e.GetProblem(), "LPS, but " + declared + " declares RAS");
  }
}

namespace
{
// The transforms of a PLUS sequence as the test reads them itself: per frame, name -> 16 numbers.
std::map<int, std::map<std::string, std::array<double, 16>>> RawTransforms(const std::string& path)
{
  std::map<int, std::map<std::string, std::array<double, 16>>> frames;
  std::ifstream in(path, std::ios::binary);
  const std::regex field(R"(^Seq_Frame(\d+)_(\w+)Transform = (.*)$)");
  for (std::string line; std::getline(in, line) && line.rfind("ElementDataFile", 0) != 0;)
  {
    std::smatch m;
    if (std::regex_match(line, m, field))
    {
      std::istringstream numbers(m[3].str());
      std::array<double, 16> matrix{};
      for (double& v : matrix)
      {
        numbers >> v;
      }
      frames[std::stoi(m[1].str())][m[2].str()] = matrix;
    }
  }
  return frames;
}

std::array<double, 16> Times(const std::array<double, 16>& a, const std::array<double, 16>& b)
{
  std::array<double, 16> r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        r[4 * i + j] += a[4 * i + k] * b[4 * k + j];
  return r;
}

// A rigid transform's inverse, by the adjugate of its rotation (not the transpose the reader uses).
std::array<double, 16> Inverse(const std::array<double, 16>& m)
{
  const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
  std::array<double, 16> r{};
  r[0] = (m[5] * m[10] - m[6] * m[9]) / det, r[1] = (m[2] * m[9] - m[1] * m[10]) / det, r[2] = (m[1] * m[6] - m[2] * m[5]) / det;
  r[4] = (m[6] * m[8] - m[4] * m[10]) / det, r[5] = (m[0] * m[10] - m[2] * m[8]) / det, r[6] = (m[2] * m[4] - m[0] * m[6]) / det;
  r[8] = (m[4] * m[9] - m[5] * m[8]) / det, r[9] = (m[1] * m[8] - m[0] * m[9]) / det, r[10] = (m[0] * m[5] - m[1] * m[4]) / det;
  for (int a = 0; a < 3; ++a)
  {
    r[4 * a + 3] = -(r[4 * a] * m[3] + r[4 * a + 1] * m[7] + r[4 * a + 2] * m[11]);
  }
  r[15] = 1.0;
  return r;
}
} // namespace

TEST(TrackedSequence, PlusRecordingsGiveEveryFrameWhereItsTransformsPutIt)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: the PLUS recordings are in ../shared/data/plus";
  }
  // 20 synthetic frames: the file's own matrices, its own times.
  const std::string synthetic = data + "/plus/SyntheticTrackerBuffer20.igs.mha";
  const auto raw = RawTransforms(synthetic);
  const auto poses = vp::ReadPoseFile(synthetic);
  ASSERT_EQ(poses.size(), 20u);
  for (std::size_t f = 0; f < poses.size(); ++f)
  {
    for (int i = 0; i < 16; ++i)
    {
      EXPECT_EQ(poses[f].ModelToWorld[i], raw.at(static_cast<int>(f)).at("ToolToTracker")[i]) << f << " " << i;
    }
  }
  EXPECT_DOUBLE_EQ(poses[1].TimeS, 1.5);
  // The real recording: 1000 frames of a stylus and a reference, the stylus tip (StylusTipToStylus
  // of PLUS's device set) in reference coordinates, as PLUS composes them.
  const std::string landmarks = data + "/plus/EightLandmarkPointsTrackedForPhantomRegistration.igs.mha";
  vp::PoseReading reading;
  reading.ToolName = "Stylus";
  reading.ReferenceName = "Reference";
  const auto relative = vp::ReadPoseFile(landmarks, reading);
  const auto frames = RawTransforms(landmarks);
  ASSERT_EQ(relative.size(), 1000u);
  const std::array<double, 16> tipToStylus = { 0.997175, -0.0713837, -0.0233796, 108.565, 0.0714032, 0.997448, 0, 7.77385,
    0.0233199, -0.00166938, 0.999727, 2.5389, 0, 0, 0, 1 };
  double worst = 0.0;
  for (std::size_t f = 0; f < relative.size(); ++f)
  {
    const auto& stylus = frames.at(static_cast<int>(f)).at("StylusToTracker");
    const auto& reference = frames.at(static_cast<int>(f)).at("ReferenceToTracker");
    const auto expected = Times(Times(Inverse(reference), stylus), tipToStylus);
    const auto got = Times(relative[f].ModelToWorld, tipToStylus);
    for (int a = 0; a < 3; ++a)
    {
      worst = std::max(worst, std::abs(got[4 * a + 3] - expected[4 * a + 3]));
    }
  }
  EXPECT_LT(worst, 1e-6) << "tips in reference coordinates, mm";
  EXPECT_GT(relative.back().TimeS, relative.front().TimeS + 60.0) << "about 15 Hz over 1000 frames";
}

// The same recording as an NRRD sequence header (.igs.nrrd, as 3D Slicer's Sequences writes its
// fields, "key:=value"): the same poses, bit for bit, and the same times.
TEST_F(PoseFile, ANrrdSequenceHeaderIsReadAsItsMetaImageTwin)
{
  const std::string data = vp::test::TestDataDir();
  if (data.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set: the PLUS recordings are in ../shared/data/plus";
  }
  const std::string mha = data + "/plus/EightLandmarkPointsTrackedForPhantomRegistration.igs.mha";
  std::istringstream in(vp::test::Slurp(mha));
  std::string nrrd = "NRRD0004\n# the PLUS recording's fields, as an NRRD header\ntype: uchar\ndimension: 3\nsizes: 0 0 1000\n";
  int fields = 0;
  for (std::string line; std::getline(in, line) && line.rfind("ElementDataFile", 0) != 0;)
  {
    const auto equals = line.find(" = ");
    if (equals != std::string::npos && (line.rfind("Seq_", 0) == 0 || line.rfind("DefaultFrameTransformName", 0) == 0))
    {
      nrrd += line.substr(0, equals) + ":=" + line.substr(equals + 3) + "\n";
      ++fields;
    }
  }
  ASSERT_GT(fields, 4000) << "1000 frames, each with two transforms, their statuses and a time";
  vp::PoseReading reading;
  reading.ToolName = "Stylus";
  reading.ReferenceName = "Reference";
  const auto expected = vp::ReadPoseFile(mha, reading);
  const auto got = vp::ReadPoseFile(this->Write("landmarks.igs.nrrd", nrrd + "\n"), reading);
  ASSERT_EQ(got.size(), expected.size());
  ASSERT_EQ(got.size(), 1000u);
  for (std::size_t f = 0; f < got.size(); ++f)
  {
    EXPECT_EQ(got[f].TimeS, expected[f].TimeS) << f;
    EXPECT_EQ(got[f].Lost, expected[f].Lost) << f;
    EXPECT_EQ(got[f].ModelToWorld, expected[f].ModelToWorld) << f;
  }
}

TEST_F(PoseFile, ASequenceSaysWhichToolAndWhenTheTrackerLostIt)
{
  std::string text;
  for (int f = 0; f < 6; ++f)
  {
    char line[400];
    std::snprintf(line, sizeof line,
      "Seq_Frame%04d_ToolToTrackerTransform = 1 0 0 %d  0 1 0 20  0 0 1 30  0 0 0 1\nSeq_Frame%04d_ToolToTrackerTransformStatus = %s\n"
      "Seq_Frame%04d_ReferenceToTrackerTransform = 1 0 0 0  0 1 0 0  0 0 1 5  0 0 0 1\nSeq_Frame%04d_Timestamp = %g\n",
      f, 10 + f, f, f == 2 || f == 3 ? "INVALID" : "OK", f, f, 0.1 * f);
    text += line;
  }
  const std::string header = "ObjectType = Image\nNDims = 3\nDimSize = 0 0 6\n";
  const std::string file = this->Write("lost.igs.mha", header + text + "ElementDataFile = LOCAL\n");
  vp::PoseReading tool;
  tool.ToolName = "Tool";
  vp::PoseStream stream(file, 0, tool);
  std::vector<vp::TrackedPose> all;
  for (vp::TrackedPose p; stream.Next(p);)
  {
    all.push_back(p);
  }
  ASSERT_EQ(all.size(), 6u);
  EXPECT_TRUE(all[2].Lost && all[3].Lost);
  EXPECT_FALSE(all[4].Lost);
  EXPECT_EQ(all[4].ModelToWorld[3], 14.0) << "frame 4's own pose, not frame 1's";
  EXPECT_EQ(vp::ReadPoseFile(file, tool).size(), 4u) << "a list keeps what was seen";
  tool.ReferenceName = "Reference";
  EXPECT_EQ(vp::ReadPoseFile(file, tool)[0].ModelToWorld[11], 25.0) << "tool to reference";
  // Two transforms and no default: which one is the tool is said, never guessed.
  EXPECT_EQ(this->Refusal("two.igs.mha", header + text), "several transforms (ReferenceToTracker, ToolToTracker): say which is the tool");
  EXPECT_EQ(this->Refusal("short.igs.mha", header + "Seq_Frame0000_ToolToTrackerTransform = 1 0 0\nSeq_Frame0000_Timestamp = 0\n"),
    "line 4: ToolToTrackerTransform is not 16 finite numbers");
  EXPECT_EQ(this->Refusal("status.igs.mha", header + "Seq_Frame0000_ToolToTrackerTransformStatus = MAYBE\n"),
    "line 4: the status 'MAYBE' is none of OK, INVALID, MISSING, OUT_OF_VIEW");
  EXPECT_EQ(this->Refusal("empty.igs.mha", header + "ElementDataFile = LOCAL\n"),
    "no tracked frames (no Seq_FrameNNNN_<From>To<To>Transform fields): not a tracked sequence");
  // A lost frame's time is all it says: it must follow the frame before, as any frame's.
  EXPECT_EQ(this->Refusal("back.igs.mha", header + "Seq_Frame0000_ToolToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                                                   "Seq_Frame0000_Timestamp = 1\nSeq_Frame0001_ToolToTrackerTransformStatus = MISSING\n"
                                                   "Seq_Frame0001_Timestamp = 0.5\n"),
    "frame 1: time 0.5 is not after the previous 1");
  EXPECT_EQ(this->Refusal("notime.igs.mha", header + "Seq_Frame0000_ToolToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"),
    "frame 0: no Timestamp");
}
