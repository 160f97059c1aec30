#ifndef vpPoseFile_h
#define vpPoseFile_h

#include "vpPoseReading.h"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace vp
{
/// One tracked pose of an instrument: when, and where its model is (model-to-world, 4x4
/// row-major, millimetres; the rotation is orthonormal and proper).
struct TrackedPose
{
  double TimeS = 0.0;
  std::array<double, 16> ModelToWorld{};
  /// The tracker did not see the tool at this time (a sequence's status not OK): no pose, and no
  /// distance may be computed from an earlier one.
  bool Lost = false;
  /// The time stamp the pose's source gave it (an OpenIGTLink header's: seconds since 1970, UTC),
  /// 0 when it gave none (3D Slicer sends 0): what the results are stamped with.
  double SourceClockS = 0.0;
};

/// Reads a pose stream.
///  - CSV (any name but *.json): one pose per line. A header names the columns, in any order:
///    `time`; `x,y,z` (or `tx,ty,tz`) and `qw,qx,qy,qz` (so scalar-last files are read as
///    written), or `m00`..`m33`; a column it cannot place is refused. Without a header a line is
///    `time,m00,...,m33` (17 numbers) or `time,x,y,z,qw,qx,qy,qz` (8: scalar first; reported
///    as SettledReading::QuaternionOrderAssumed). Comment
///    lines before the first pose may say how it is read ("# pose-space: RAS", "# pose-units: m",
///    "# time-units: ms").
///  - JSON: {"space": "RAS", "units": "m", "time_units": "ms" (each optional, before "poses"),
///    "poses": [{"time": t, "matrix": [16 numbers]} or {"time": t, "position": [x,y,z],
///    "quaternion": [w,x,y,z]}, ...]}.
/// Positions become millimetres and the world LPS, times seconds, as reading and the file say
/// (vp::PoseReading). Refused with one line naming the file and the line (CSV) or pose (JSON): a
/// wrong number of columns, NaN or infinity, a time not after the previous one, a rotation that
/// is not orthonormal (|R^T R - I| > 1e-3) or is a reflection, a quaternion not of unit length
/// (within 1e-3), a matrix whose last row is not 0 0 0 1, a header or declaration the reader
/// cannot place, and a file without poses. Throws vp::InputError (ParameterError naming the
/// setting when a setting given contradicts the file).
std::vector<TrackedPose> ReadPoseFile(const std::string& fileName, const PoseReading& reading = {});

class NumericCsvReader;
class JsonPoseReader;
struct TrackedSequence;

/// Where a tracking session's poses come from, one at a time: a recorded file (PoseStream), and
/// later a live stream. Next() throws vp::InputError naming the source on a bad pose.
class PoseSource
{
public:
  virtual ~PoseSource() = default;
  /// The next pose; false after the last.
  virtual bool Next(TrackedPose& pose) = 0;
  /// The poses returned so far.
  virtual std::size_t PosesRead() const = 0;
  /// The poses there will be in all, for progress; 0 when unknown (a live stream).
  virtual std::size_t PosesExpected() const { return 0; }
  /// The source as reports name it (the file name).
  virtual const std::string& GetName() const = 0;
  /// How its numbers were read (settled at the first pose); none before it, or for poses that
  /// came as numbers in the patient's frame.
  virtual const SettledReading* GetSettledReading() const { return nullptr; }
  /// Whether a held signal (Ctrl-C) is the source's own end, as for a live stream, rather than an
  /// interruption of the run.
  virtual bool EndsOnSignal() const { return false; }
};

/// The poses of a pose file one at a time, with ReadPoseFile's checks and messages: a CSV file
/// is read a line at a time, so an hour of tracking need not fit in memory; a JSON file is read
/// whole (it is one document). A caller that must refuse a bad file before computing anything
/// reads it through once first.
class PoseStream : public PoseSource
{
public:
  /// Opens the file; throws vp::InputError naming it when it cannot be read. expected: the
  /// poses it holds when the caller counted them (PosesExpected()).
  explicit PoseStream(const std::string& fileName, std::size_t expected = 0, const PoseReading& reading = {});
  ~PoseStream() override;
  PoseStream(const PoseStream&) = delete;
  PoseStream& operator=(const PoseStream&) = delete;
  /// The next pose; false after the last. Throws vp::InputError on a bad line or pose, and on a
  /// file without poses.
  bool Next(TrackedPose& pose) override;
  std::size_t PosesRead() const override { return this->Read; }
  std::size_t PosesExpected() const override { return this->Expected; }
  const std::string& GetName() const override { return this->Name; }
  const SettledReading* GetSettledReading() const override;
  /// Reads a file through once, with every check, and returns how many poses it holds: a bad
  /// file is refused before anything is computed.
  static std::size_t CountPoses(const std::string& fileName, const PoseReading& reading = {});

private:
  std::string Name;
  std::unique_ptr<NumericCsvReader> Csv;
  std::unique_ptr<JsonPoseReader> Json;
  std::unique_ptr<TrackedSequence> Sequence;
  std::string SequenceTool, SequenceReference;
  bool HasPrevious = false; ///< a sequence's last pose that was seen (lost ones are no pose)
  /// The next frame of a tracked sequence: the tool's pose (relative to the reference), or a lost frame.
  bool NextOfSequence(TrackedPose& pose);
  std::size_t Read = 0;
  std::size_t Expected = 0;
  PoseReading Given;
  /// How the numbers are read, settled at the first pose (the header and declarations known).
  struct Format;
  std::unique_ptr<Format> Layout;
  TrackedPose Previous;
};

/// Poses already in memory (a designed trajectory), as a session's source.
class PoseListSource : public PoseSource
{
public:
  /// name: what reports call the poses (the file they were also written to, if any).
  PoseListSource(const std::vector<TrackedPose>& poses, std::string name)
    : Poses(poses)
    , Name(std::move(name))
  {
  }
  bool Next(TrackedPose& pose) override
  {
    if (this->Read == this->Poses.size())
    {
      return false;
    }
    pose = this->Poses[this->Read++];
    return true;
  }
  std::size_t PosesRead() const override { return this->Read; }
  std::size_t PosesExpected() const override { return this->Poses.size(); }
  const std::string& GetName() const override { return this->Name; }

private:
  const std::vector<TrackedPose>& Poses;
  std::string Name;
  std::size_t Read = 0;
};

/// The CSV form ReadPoseFile reads, `time,m00,...,m33` with a header line, each number to 17
/// significant digits so a pose read back is the pose written.
std::string FormatPoseCsv(const std::vector<TrackedPose>& poses);

/// How a source that declares nothing (a live stream) is read: the settings given, else the
/// defaults (the registration's tracker space, LPS; mm; s).
SettledReading SettlePoseReading(const PoseReading& given);

/// A pose from its numbers: 16 (model-to-world, row-major) or 7 (position, then the quaternion
/// w,x,y,z), read as reading says (units, frame, registration), with every check a pose file's
/// pose gets but its time's: orthonormal and proper, a unit quaternion, the position within
/// limits::CoordinateMm. Returns "" or the problem in a few words (the pose is then not to be used).
std::string MakeTrackedPose(const double* values, std::size_t count, const SettledReading& reading, TrackedPose& pose);

/// The rotation matrix of a unit quaternion (w, x, y, z), as a model-to-world matrix with the
/// given translation.
std::array<double, 16> PoseFromQuaternion(const std::array<double, 3>& positionMm, const std::array<double, 4>& wxyz);
} // namespace vp

#endif
