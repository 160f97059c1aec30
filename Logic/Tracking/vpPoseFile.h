#ifndef vpPoseFile_h
#define vpPoseFile_h

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
};

/// Reads a pose stream.
///  - CSV (any name but *.json): one pose per line, header allowed, either
///    `time,m00,m01,...,m33` (17 numbers) or `time,x,y,z,qw,qx,qy,qz` (8 numbers: position in mm,
///    unit quaternion, scalar first). All lines use the same form.
///  - JSON: {"poses": [{"time": t, "matrix": [16 numbers]} or
///    {"time": t, "position": [x,y,z], "quaternion": [w,x,y,z]}, ...]}.
/// Refused with one line naming the file and the line (CSV) or pose (JSON): a wrong number of
/// columns, NaN or infinity, a time not after the previous one, a rotation that is not
/// orthonormal (|R^T R - I| > 1e-3) or is a reflection, a quaternion not of unit length (within
/// 1e-3), a matrix whose last row is not 0 0 0 1, and a file without poses. Throws vp::InputError.
std::vector<TrackedPose> ReadPoseFile(const std::string& fileName);

class NumericCsvReader;

/// The poses of a pose file one at a time, with ReadPoseFile's checks and messages: a CSV file
/// is read a line at a time, so an hour of tracking need not fit in memory; a JSON file is read
/// whole (it is one document). A caller that must refuse a bad file before computing anything
/// reads it through once first.
class PoseStream
{
public:
  /// Opens the file; throws vp::InputError naming it when it cannot be read.
  explicit PoseStream(const std::string& fileName);
  ~PoseStream();
  PoseStream(const PoseStream&) = delete;
  PoseStream& operator=(const PoseStream&) = delete;
  /// The next pose; false after the last. Throws vp::InputError on a bad line or pose, and on a
  /// file without poses.
  bool Next(TrackedPose& pose);
  /// The poses returned so far.
  std::size_t PosesRead() const { return this->Read; }

private:
  std::string Name;
  std::unique_ptr<NumericCsvReader> Csv;
  std::vector<TrackedPose> Poses; // a JSON file's
  std::size_t Read = 0;
  std::size_t Columns = 0;
  TrackedPose Previous;
};

/// The CSV form ReadPoseFile reads, `time,m00,...,m33` with a header line, each number to 17
/// significant digits so a pose read back is the pose written.
std::string FormatPoseCsv(const std::vector<TrackedPose>& poses);

/// The rotation matrix of a unit quaternion (w, x, y, z), as a model-to-world matrix with the
/// given translation.
std::array<double, 16> PoseFromQuaternion(const std::array<double, 3>& positionMm, const std::array<double, 4>& wxyz);
} // namespace vp

#endif
