#ifndef vpPoseReading_h
#define vpPoseReading_h

#include "vpPatientSpace.h"
#include "vpRegistrationFile.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vp
{
/// How a pose file's numbers are read. Each setting a front end leaves unset is what the file
/// declares (a "# pose-space: RAS" comment before a CSV's first row, a top-level "space" field of
/// a JSON file before its "poses"), else LPS, millimetres and seconds. A setting given that the
/// file contradicts is refused (ParameterError naming the setting and the file): a unit or a frame
/// is never guessed between two sources that disagree.
struct PoseReading
{
  /// PoseSpace: the world frame of the positions and rotations.
  std::optional<PoseSpace> Space;
  /// PoseUnits: millimetres per unit of the positions (1: mm, 1000: m).
  std::optional<double> MillimetresPerUnit;
  /// TimeUnits: seconds per unit of the times (1: s, 0.001: ms).
  std::optional<double> SecondsPerUnit;
  /// A tracked sequence's (PLUS .igs.mha) transforms: ToolName, the tool's ("Stylus" for
  /// StylusToTracker, or a whole name; empty: the sequence's default or only one), and
  /// ReferenceName, a reference the poses are taken relative to (tool-to-reference, as PLUS
  /// composes them; empty: none).
  std::string ToolName;
  std::string ReferenceName;
  /// Registration: tracker (or reference) to patient, applied to every pose after its units and
  /// frame (ReadTrackerRegistration reads register's result or a 3D Slicer transform); its
  /// TrackerSpace is the poses' frame when neither Space nor the file says. Unset: the poses are
  /// the patient's.
  std::optional<TrackerRegistration> Registration;
};

/// How a source's numbers were read once the settings, the file's declarations and the defaults
/// were settled: what reports say, so that a default is never a silent one.
struct SettledReading
{
  PoseSpace Space = PoseSpace::LPS;
  double MillimetresPerUnit = 1.0;
  double SecondsPerUnit = 1.0;
  std::optional<TrackerRegistration> Registration;
  /// A CSV without a header whose rows hold a position and a quaternion: their order was taken
  /// as documented (time,x,y,z,qw,qx,qy,qz), since nothing in the numbers tells scalar-first from
  /// scalar-last; reports say so.
  bool QuaternionOrderAssumed = false;
};

/// A declaration of how to read a file's numbers, from one line of text: "pose-space: RAS",
/// "pose-units = m", "time-units: ms" (also "space", "units"; any case; ':' or '='). Lines that
/// declare nothing (any other comment) leave reading as it is; a known key with a value it cannot
/// take throws InputError(source, ...).
void ApplyPoseDeclaration(const std::string& line, const std::string& source, PoseReading& declared);
/// Whether a key declares how poses are read (ApplyPoseDeclaration's keys, any case).
bool IsPoseDeclarationKey(const std::string& key);
} // namespace vp

#endif
