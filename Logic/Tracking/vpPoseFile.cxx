#include "vpPoseFile.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpJsonPoseReader.h"
#include "vpNumericCsv.h"
#include "vpPoseReading.h"
#include "vpRigidTransform.h"
#include "vpText.h"
#include "vpTrackedSequence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vp
{
namespace
{
/// The settings a front end gave over what the file declares, each else its default; a setting
/// the file contradicts is refused, naming both.
SettledReading Resolve(const PoseReading& given, const PoseReading& declared, const std::string& fileName)
{
  auto unitName = [](double mmPerUnit) { return std::string(mmPerUnit == 1000.0 ? "m" : "mm"); };
  auto timeName = [](double sPerUnit) { return std::string(sPerUnit == 0.001 ? "ms" : "s"); };
  if (given.Space && declared.Space && *given.Space != *declared.Space)
  {
    throw ParameterError("PoseSpace", std::string(PoseSpaceName(*given.Space)) + ", but " + fileName + " declares " +
        PoseSpaceName(*declared.Space));
  }
  if (given.MillimetresPerUnit && declared.MillimetresPerUnit && *given.MillimetresPerUnit != *declared.MillimetresPerUnit)
  {
    throw ParameterError("PoseUnits", unitName(*given.MillimetresPerUnit) + ", but " + fileName + " declares " +
        unitName(*declared.MillimetresPerUnit));
  }
  if (given.SecondsPerUnit && declared.SecondsPerUnit && *given.SecondsPerUnit != *declared.SecondsPerUnit)
  {
    throw ParameterError("TimeUnits", timeName(*given.SecondsPerUnit) + ", but " + fileName + " declares " +
        timeName(*declared.SecondsPerUnit));
  }
  SettledReading r;
  const PoseSpace fallback = given.Registration ? given.Registration->TrackerSpace : PoseSpace::LPS;
  r.Space = given.Space ? *given.Space : declared.Space.value_or(fallback);
  r.MillimetresPerUnit = given.MillimetresPerUnit ? *given.MillimetresPerUnit : declared.MillimetresPerUnit.value_or(1.0);
  r.SecondsPerUnit = given.SecondsPerUnit ? *given.SecondsPerUnit : declared.SecondsPerUnit.value_or(1.0);
  r.Registration = given.Registration;
  return r;
}

/// Declarations that came after the poses they would have changed: refused unless they say what
/// the poses were read as.
void CheckLateDeclarations(const PoseReading& late, const SettledReading& used, const std::string& fileName)
{
  const bool space = late.Space && *late.Space != used.Space;
  const bool units = late.MillimetresPerUnit && *late.MillimetresPerUnit != used.MillimetresPerUnit;
  const bool time = late.SecondsPerUnit && *late.SecondsPerUnit != used.SecondsPerUnit;
  if (space || units || time)
  {
    throw InputError(fileName, std::string("declares ") + (space ? "its space" : units ? "its units" : "its time units") +
        " after its poses, which were read otherwise: put the declaration before \"poses\"");
  }
}

constexpr const char* ColumnNames = "time; x,y,z or tx,ty,tz; qw,qx,qy,qz in any order; or m00..m33";

/// Where the numbers of a pose sit in a CSV row: the time, then the pose's values in the order
/// MakePose takes them (16 matrix entries row-major, or x,y,z and qw,qx,qy,qz).
struct PoseColumns
{
  std::size_t Count = 0;
  std::size_t Time = 0;
  std::vector<std::size_t> Pose;
  bool Named = false; ///< from a header's names, not by position
};

/// Refuses a row whose count of numbers no pose has: a time and 16 (a matrix) or 7 (a position and
/// a quaternion), whatever order a header puts them in.
void CheckPoseNumberCount(std::size_t count, std::size_t line, const std::string& fileName)
{
  if (count != 17 && count != 8)
  {
    throw InputError(fileName, "line " + std::to_string(line) +
        ": expected 17 numbers (time and a 4x4 matrix) or 8 (time, x,y,z, qw,qx,qy,qz), got " + std::to_string(count));
  }
}

/// A file without a header: time then 16 (a matrix, row-major) or 7 (x,y,z, qw,qx,qy,qz) numbers.
PoseColumns ColumnsByPosition(std::size_t count, std::size_t line, const std::string& fileName)
{
  CheckPoseNumberCount(count, line, fileName);
  PoseColumns columns;
  columns.Count = count;
  for (std::size_t k = 1; k < count; ++k)
  {
    columns.Pose.push_back(k);
  }
  return columns;
}

/// The place of one header name in a pose: 0 time, 1..16 matrix m00..m33, 17..19 x,y,z,
/// 20..23 qw,qx,qy,qz; -1 when it names nothing of a pose.
int PoseFieldOf(const std::string& header)
{
  const std::string name = LowerCase(header);
  if (name == "time" || name == "t" || name == "timestamp")
  {
    return 0;
  }
  if (name.size() == 3 && name[0] == 'm' && name[1] >= '0' && name[1] <= '3' && name[2] >= '0' && name[2] <= '3')
  {
    return 1 + 4 * (name[1] - '0') + (name[2] - '0');
  }
  const std::string axes[3][2] = { { "x", "tx" }, { "y", "ty" }, { "z", "tz" } };
  for (int a = 0; a < 3; ++a)
  {
    if (name == axes[a][0] || name == axes[a][1])
    {
      return 17 + a;
    }
  }
  const char* quaternion[4] = { "qw", "qx", "qy", "qz" };
  for (int k = 0; k < 4; ++k)
  {
    if (name == quaternion[k])
    {
      return 20 + k;
    }
  }
  return -1;
}

/// The columns a header names: a time and either the 16 matrix entries or a position and a
/// quaternion, each once, nothing else.
PoseColumns ColumnsByName(const std::vector<std::string>& header, const std::string& fileName)
{
  std::vector<int> at(24, -1);
  for (std::size_t c = 0; c < header.size(); ++c)
  {
    const int field = PoseFieldOf(header[c]);
    const std::string column = "column " + std::to_string(c + 1) + " '" + Printable(header[c]) + "'";
    if (field < 0)
    {
      throw InputError(fileName, "header: " + column + " is not a pose column (" + ColumnNames + ")");
    }
    if (at[static_cast<std::size_t>(field)] >= 0)
    {
      throw InputError(fileName, "header: " + column + " names a value already given");
    }
    at[static_cast<std::size_t>(field)] = static_cast<int>(c);
  }
  const bool matrix = std::any_of(at.begin() + 1, at.begin() + 17, [](int c) { return c >= 0; });
  const bool position = std::any_of(at.begin() + 17, at.end(), [](int c) { return c >= 0; });
  if (at[0] < 0 || matrix == position)
  {
    throw InputError(fileName, std::string("header: ") +
        (at[0] < 0 ? "no time column" : matrix ? "both a matrix and a position or quaternion" : "no pose columns") + " (" +
        ColumnNames + ")");
  }
  static const char* names[24] = { "time", "m00", "m01", "m02", "m03", "m10", "m11", "m12", "m13", "m20", "m21", "m22", "m23",
    "m30", "m31", "m32", "m33", "x", "y", "z", "qw", "qx", "qy", "qz" };
  PoseColumns columns;
  columns.Count = header.size();
  columns.Time = static_cast<std::size_t>(at[0]);
  columns.Named = true;
  for (int field = matrix ? 1 : 17; field < (matrix ? 17 : 24); ++field)
  {
    if (at[static_cast<std::size_t>(field)] < 0)
    {
      throw InputError(fileName, std::string("header: no column ") + names[field] + " (" + ColumnNames + ")");
    }
    columns.Pose.push_back(static_cast<std::size_t>(at[static_cast<std::size_t>(field)]));
  }
  return columns;
}

// Makes the pose at time from the numbers after the time (16: matrix; 7: position and
// quaternion), after the previous pose (null for the first), or throws naming fileName and where
// (the line or pose).
TrackedPose CheckedPose(double time, const double* values, std::size_t count, const TrackedPose* previous,
  const SettledReading& reading, const std::string& fileName, const std::string& where)
{
  TrackedPose pose;
  pose.TimeS = time * reading.SecondsPerUnit;
  std::string problem = MagnitudeProblem(pose.TimeS, limits::TimeS, "s");
  problem = problem.empty() ? MakeTrackedPose(values, count, reading, pose) : "time " + problem;
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

// The pose of one CSV row through the file's columns, after the previous (null for the first).
TrackedPose CsvPose(const NumericRow& row, const PoseColumns& columns, const TrackedPose* previous, const SettledReading& reading,
  const std::string& fileName)
{
  const std::string where = "line " + std::to_string(row.Line) + ": ";
  CheckPoseNumberCount(row.Values.size(), row.Line, fileName);
  if (row.Values.size() != columns.Count)
  {
    throw InputError(fileName, where + std::to_string(row.Values.size()) + " numbers where " +
        (columns.Named ? "the header names " : "the first pose has ") + std::to_string(columns.Count));
  }
  std::vector<double> values;
  for (std::size_t index : columns.Pose)
  {
    values.push_back(row.Values[index]);
  }
  return CheckedPose(row.Values[columns.Time], values.data(), values.size(), previous, reading, fileName, where);
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

struct PoseStream::Format
{
  SettledReading Reading;
  PoseColumns Columns;
};

SettledReading SettlePoseReading(const PoseReading& given)
{
  return Resolve(given, PoseReading(), std::string());
}

std::string MakeTrackedPose(const double* values, std::size_t count, const SettledReading& reading, TrackedPose& pose)
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
  std::string problem = RigidTransformProblem(pose.ModelToWorld);
  for (int a = 0; a < 3; ++a)
  {
    pose.ModelToWorld[4 * a + 3] *= reading.MillimetresPerUnit;
  }
  if (reading.Space == PoseSpace::RAS)
  {
    // World RAS to LPS: x and y negated, a half turn about the superior axis (still a rotation).
    for (int k = 0; k < 8; ++k)
    {
      pose.ModelToWorld[k] = -pose.ModelToWorld[k];
    }
  }
  if (reading.Registration)
  {
    pose.ModelToWorld = MultiplyTransforms(reading.Registration->TrackerToPatient, pose.ModelToWorld);
  }
  for (int a = 0; a < 3 && problem.empty(); ++a)
  {
    const std::string far = MagnitudeProblem(pose.ModelToWorld[4 * a + 3], limits::CoordinateMm, "mm");
    problem = far.empty() ? far : "position " + far + " (a patient lies within metres of the origin)";
  }
  return problem;
}


PoseStream::PoseStream(const std::string& fileName, std::size_t expected, const PoseReading& reading)
  : Name(fileName)
  , Expected(expected)
  , Given(reading)
{
  if (EndsWith(fileName, ".json"))
  {
    this->Json = std::make_unique<JsonPoseReader>(fileName);
  }
  else if (IsSequenceFileName(fileName))
  {
    this->Sequence = std::make_unique<TrackedSequence>(ReadTrackedSequence(fileName));
    this->SequenceTool = this->Sequence->Resolve(reading.ToolName, fileName, "tool");
    if (!reading.ReferenceName.empty())
    {
      this->SequenceReference = this->Sequence->Resolve(reading.ReferenceName, fileName, "reference");
    }
  }
  else
  {
    this->Csv = std::make_unique<NumericCsvReader>(fileName, CsvWhat);
  }
}

PoseStream::~PoseStream() = default;

const SettledReading* PoseStream::GetSettledReading() const
{
  return this->Layout ? &this->Layout->Reading : nullptr;
}

std::size_t PoseStream::CountPoses(const std::string& fileName, const PoseReading& reading)
{
  PoseStream check(fileName, 0, reading);
  for (TrackedPose pose; check.Next(pose);)
  {
  }
  return check.PosesRead();
}

bool PoseStream::Next(TrackedPose& pose)
{
  if (this->Sequence)
  {
    return this->NextOfSequence(pose);
  }
  if (this->Json)
  {
    JsonPoseReader::Item item;
    if (!this->Json->Next(item))
    {
      if (this->Layout)
      {
        CheckLateDeclarations(this->Json->LateDeclarations(), this->Layout->Reading, this->Name);
      }
      return false;
    }
    if (!this->Layout)
    {
      this->Layout = std::make_unique<Format>();
      this->Layout->Reading = Resolve(this->Given, this->Json->Declarations(), this->Name);
    }
    const std::string where = "pose " + std::to_string(this->Read + 1) + ": ";
    pose = CheckedPose(item.Time, item.Values.data(), item.Values.size(), this->Read ? &this->Previous : nullptr,
      this->Layout->Reading, this->Name, where);
    this->Previous = pose;
    ++this->Read;
    return true;
  }
  NumericRow row;
  if (!this->Csv->Next(row))
  {
    return false;
  }
  if (!this->Layout)
  {
    this->Layout = std::make_unique<Format>();
    PoseReading declared;
    for (const std::string& comment : this->Csv->LeadingComments())
    {
      ApplyPoseDeclaration(comment, this->Name, declared);
    }
    this->Layout->Reading = Resolve(this->Given, declared, this->Name);
    this->Layout->Columns = this->Csv->Header().empty() ? ColumnsByPosition(row.Values.size(), row.Line, this->Name)
                                                         : ColumnsByName(this->Csv->Header(), this->Name);
    this->Layout->Reading.QuaternionOrderAssumed = this->Csv->Header().empty() && this->Layout->Columns.Count == 8;
  }
  pose = CsvPose(row, this->Layout->Columns, this->Read > 0 ? &this->Previous : nullptr, this->Layout->Reading, this->Name);
  this->Previous = pose;
  ++this->Read;
  return true;
}

bool PoseStream::NextOfSequence(TrackedPose& pose)
{
  if (this->Read == this->Sequence->Frames.size())
  {
    return false;
  }
  const TrackedSequence::Frame& frame = this->Sequence->Frames[this->Read];
  const std::string where = "frame " + std::to_string(this->Read) + ": ";
  if (!frame.HasTime)
  {
    throw InputError(this->Name, where + "no Timestamp");
  }
  // Every frame's time follows the one before, a lost frame's too: its time is all it says.
  if (this->Read > 0 && !(frame.TimeS > this->Sequence->Frames[this->Read - 1].TimeS))
  {
    throw InputError(this->Name, where + "time " + NumberText(frame.TimeS) + " is not after the previous " +
        NumberText(this->Sequence->Frames[this->Read - 1].TimeS));
  }
  if (!this->Layout)
  {
    this->Layout = std::make_unique<Format>();
    this->Layout->Reading = Resolve(this->Given, PoseReading(), this->Name);
  }
  const auto seen = [&](const std::string& name) {
    const auto status = frame.Valid.find(name);
    return frame.Transforms.count(name) && (status == frame.Valid.end() || status->second);
  };
  if (!seen(this->SequenceTool) || (!this->SequenceReference.empty() && !seen(this->SequenceReference)))
  {
    // Tracking lost: a time and nothing else, never the last pose again.
    pose = TrackedPose();
    pose.TimeS = frame.TimeS * this->Layout->Reading.SecondsPerUnit;
    pose.Lost = true;
    ++this->Read;
    return true;
  }
  std::array<double, 16> m = frame.Transforms.at(this->SequenceTool);
  if (!this->SequenceReference.empty())
  {
    const std::array<double, 16>& reference = frame.Transforms.at(this->SequenceReference);
    const std::string problem = RigidTransformProblem(reference);
    if (!problem.empty())
    {
      throw InputError(this->Name, where + this->SequenceReference + "Transform: " + problem);
    }
    // Tool to reference, with the exact inverse (VTK's, as PLUS composes them): a recorded rotation
    // is orthonormal only to the tracker's rounding.
    m = MultiplyTransforms(InvertTransform(reference), m);
  }
  pose = CheckedPose(frame.TimeS, m.data(), 16, this->HasPrevious ? &this->Previous : nullptr, this->Layout->Reading, this->Name, where);
  this->Previous = pose;
  this->HasPrevious = true;
  ++this->Read;
  return true;
}

std::vector<TrackedPose> ReadPoseFile(const std::string& fileName, const PoseReading& reading)
{
  PoseStream stream(fileName, 0, reading);
  std::vector<TrackedPose> poses;
  TrackedPose pose;
  while (stream.Next(pose))
  {
    if (!pose.Lost) // a list of poses has no place for the times the tool was not seen
    {
      poses.push_back(pose);
    }
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
