#include "vpPoseFile.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpJsonPoseReader.h"
#include "vpNumericCsv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vp
{
namespace
{
bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The problem with a model-to-world matrix, or "" when it is a rigid pose.
std::string RigidProblem(const std::array<double, 16>& m)
{
  if (std::abs(m[12]) > 1e-6 || std::abs(m[13]) > 1e-6 || std::abs(m[14]) > 1e-6 || std::abs(m[15] - 1.0) > 1e-6)
  {
    return "the last matrix row is not 0 0 0 1";
  }
  double worst = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      // (R^T R)_ab: columns a and b of R.
      const double dot = m[a] * m[b] + m[4 + a] * m[4 + b] + m[8 + a] * m[8 + b];
      worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  }
  if (worst > 1e-3)
  {
    return "the rotation is not orthonormal (|R^T R - I| = " + NumberText(worst) + ")";
  }
  const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
    m[2] * (m[4] * m[9] - m[5] * m[8]);
  if (det < 0.0)
  {
    return "the rotation is a reflection (determinant -1)";
  }
  return "";
}

// A pose from the numbers after the time: 16 (matrix) or 7 (position, quaternion); "" or the problem.
std::string MakePose(const double* values, std::size_t count, TrackedPose& pose)
{
  if (count == 16)
  {
    std::copy(values, values + 16, pose.ModelToWorld.begin());
  }
  else
  {
    const double norm = std::sqrt(values[3] * values[3] + values[4] * values[4] + values[5] * values[5] + values[6] * values[6]);
    if (!(std::abs(norm - 1.0) <= 1e-3))
    {
      return "the quaternion is not of unit length (|q| = " + NumberText(norm) + ")";
    }
    // Normalised, so that a quaternion written to 4 decimals still gives an orthonormal rotation.
    pose.ModelToWorld = PoseFromQuaternion(
      { values[0], values[1], values[2] }, { values[3] / norm, values[4] / norm, values[5] / norm, values[6] / norm });
  }
  return RigidProblem(pose.ModelToWorld);
}

// Makes the pose at time from the numbers after the time (16: matrix; 7: position and
// quaternion), after the previous pose (null for the first), or throws naming fileName and where
// (the line or pose).
TrackedPose CheckedPose(double time, const double* values, std::size_t count, const TrackedPose* previous,
  const std::string& fileName, const std::string& where)
{
  TrackedPose pose;
  pose.TimeS = time;
  std::string problem = MagnitudeProblem(time, limits::TimeS, "s");
  problem = problem.empty() ? MakePose(values, count, pose) : "time " + problem;
  for (int a = 0; a < 3 && problem.empty(); ++a)
  {
    const std::string far = MagnitudeProblem(pose.ModelToWorld[4 * a + 3], limits::CoordinateMm, "mm");
    problem = far.empty() ? far : "position " + far + " (a patient lies within metres of the origin)";
  }
  if (problem.empty() && previous && !(pose.TimeS > previous->TimeS))
  {
    problem = "time " + NumberText(pose.TimeS) + " is not after the previous " + NumberText(previous->TimeS);
  }
  if (!problem.empty())
  {
    throw InputError(fileName, where + problem);
  }
  return pose;
}

// The pose of one CSV row, after the previous (null for the first, whose columns every row must have).
TrackedPose CsvPose(const NumericRow& row, std::size_t columns, const TrackedPose* previous, const std::string& fileName)
{
  const std::string where = "line " + std::to_string(row.Line) + ": ";
  if (row.Values.size() != 17 && row.Values.size() != 8)
  {
    throw InputError(fileName, where + "expected 17 numbers (time and a 4x4 matrix) or 8 (time, x,y,z, qw,qx,qy,qz), got " +
        std::to_string(row.Values.size()));
  }
  if (row.Values.size() != columns)
  {
    throw InputError(fileName, where + std::to_string(row.Values.size()) + " numbers where the first pose has " +
        std::to_string(columns));
  }
  return CheckedPose(row.Values[0], row.Values.data() + 1, row.Values.size() - 1, previous, fileName, where);
}

constexpr const char* CsvWhat = "a pose list (time,m00..m33 or time,x,y,z,qw,qx,qy,qz per line)";

} // namespace

std::array<double, 16> PoseFromQuaternion(const std::array<double, 3>& p, const std::array<double, 4>& q)
{
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y), p[0], //
    2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x), p[1],         //
    2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y), p[2],         //
    0, 0, 0, 1 };
}

PoseStream::PoseStream(const std::string& fileName, std::size_t expected)
  : Name(fileName)
  , Expected(expected)
{
  if (EndsWith(fileName, ".json"))
  {
    this->Json = std::make_unique<JsonPoseReader>(fileName);
  }
  else
  {
    this->Csv = std::make_unique<NumericCsvReader>(fileName, CsvWhat);
  }
}

PoseStream::~PoseStream() = default;

std::size_t PoseStream::CountPoses(const std::string& fileName)
{
  PoseStream check(fileName);
  for (TrackedPose pose; check.Next(pose);)
  {
  }
  return check.PosesRead();
}

bool PoseStream::Next(TrackedPose& pose)
{
  if (this->Json)
  {
    JsonPoseReader::Item item;
    if (!this->Json->Next(item))
    {
      return false;
    }
    const std::string where = "pose " + std::to_string(this->Read + 1) + ": ";
    pose = CheckedPose(item.Time, item.Values.data(), item.Values.size(), this->Read ? &this->Previous : nullptr, this->Name, where);
    this->Previous = pose;
    ++this->Read;
    return true;
  }
  NumericRow row;
  if (!this->Csv->Next(row))
  {
    return false;
  }
  if (this->Read == 0)
  {
    this->Columns = row.Values.size();
  }
  pose = CsvPose(row, this->Columns, this->Read > 0 ? &this->Previous : nullptr, this->Name);
  this->Previous = pose;
  ++this->Read;
  return true;
}

std::vector<TrackedPose> ReadPoseFile(const std::string& fileName)
{
  PoseStream stream(fileName);
  std::vector<TrackedPose> poses;
  TrackedPose pose;
  while (stream.Next(pose))
  {
    poses.push_back(pose);
  }
  return poses;
}

std::string FormatPoseCsv(const std::vector<TrackedPose>& poses)
{
  std::string csv = "time";
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      csv += ",m" + std::to_string(r) + std::to_string(c);
    }
  }
  csv += "\n";
  char number[32];
  for (const TrackedPose& pose : poses)
  {
    std::snprintf(number, sizeof(number), "%.17g", pose.TimeS);
    csv += number;
    for (double v : pose.ModelToWorld)
    {
      std::snprintf(number, sizeof(number), ",%.17g", v);
      csv += number;
    }
    csv += "\n";
  }
  return csv;
}
} // namespace vp
