#ifndef vpRegistrationFile_h
#define vpRegistrationFile_h

#include "vpRigidTransform.h"

#include <string>

namespace vp
{
/// The "model_to_world" of a registration result (16 finite numbers, row-major), as register
/// writes it; what names the file's role in messages ("an initial transform"). Throws InputError
/// naming the file otherwise.
Matrix4 ReadModelToWorld(const std::string& fileName, const std::string& what);

/// The tracker-to-patient transform of a registration result, as `register landmarks` and
/// `register icp` write it: the inverse of its "model_to_world" (the model points in the patient's
/// images, the world points by the tracker, or relative to its reference). Throws InputError
/// naming the file for anything else, and for a transform that is not rigid (RigidTransformProblem).
Matrix4 ReadTrackerToPatient(const std::string& fileName);
} // namespace vp

#endif
