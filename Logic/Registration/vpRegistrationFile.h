#ifndef vpRegistrationFile_h
#define vpRegistrationFile_h

#include "vpRigidTransform.h"

#include <string>

namespace vp
{
/// The tracker-to-patient transform of a registration result, as `register landmarks` and
/// `register icp` write it: the inverse of its "model_to_world" (the model points in the patient's
/// images, the world points by the tracker, or relative to its reference). Throws InputError
/// naming the file for anything else, and for a transform that is not rigid (within 1e-3).
Matrix4 ReadTrackerToPatient(const std::string& fileName);
} // namespace vp

#endif
