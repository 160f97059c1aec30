#ifndef vpRegistrationFile_h
#define vpRegistrationFile_h

#include "vpPatientSpace.h"
#include "vpRigidTransform.h"

#include <string>

namespace vp
{
/// The "model_to_world" of a registration result (16 finite numbers, row-major, the translation
/// within limits::CoordinateMm), as register writes it; what names the file's role in messages
/// ("an initial transform"). Throws InputError naming the file otherwise.
Matrix4 ReadModelToWorld(const std::string& fileName, const std::string& what);

/// A fixed registration of the tracker (or its reference) to the patient's images.
struct TrackerRegistration
{
  /// From the tracker's coordinates, once in the LPS convention (see TrackerSpace), to the
  /// patient's LPS, in mm; rigid.
  Matrix4 TrackerToPatient{};
  /// The frame a tracker's numbers are in when nothing else says: LPS for register's result
  /// (it took them as they came), RAS for a 3D Slicer transform (Slicer holds every frame, a
  /// tracker's raw numbers too, as RAS).
  PoseSpace TrackerSpace = PoseSpace::LPS;
  /// What the file was, for messages and reports: "register's result", "a 3D Slicer transform".
  std::string Kind;
  std::string FileName;
};

/// The registration in fileName:
///  - register's RESULT.json (landmarks, icp): the inverse of its "model_to_world" (the model
///    points were the patient's, the world points the tracker's);
///  - a 3D Slicer transform, as Slicer saves a transform node (.h5, .tfm, .txt; ITK's
///    format: LPS, and "from parent", the inverse of the tracker-to-RAS matrix Slicer shows): the
///    inverse of the file's matrix, which takes the tracker's LPS-converted numbers to the
///    patient's LPS, so the tracker's raw numbers are read as RAS unless a setting or the pose
///    file says otherwise.
/// Throws InputError naming the file for anything else, and for a transform that is not rigid
/// (RigidTransformProblem): a scaled or mirroring registration is never applied silently.
TrackerRegistration ReadTrackerRegistration(const std::string& fileName);
} // namespace vp

#endif
