#ifndef vpItkTransformFile_h
#define vpItkTransformFile_h

#include "vpRigidTransform.h"

#include <string>

namespace vp
{
/// The one linear transform of an ITK transform file, as ITK and 3D Slicer write them: HDF5
/// (.h5, .hdf5) or the Insight text format (.tfm, .txt); any linear type (affine,
/// Euler, versor, similarity, translation), double or float, or a CompositeTransform of them
/// (applied in reverse order, as ITK composes). The
/// matrix is ITK's: LPS, and a resampling transform, taking a point of the parent frame to the
/// child's (Slicer's "transform from parent"), 4x4 row-major. Throws InputError naming the file
/// for anything else: a file ITK cannot read, a list of several transforms (Slicer refuses them
/// too: a list is not a composition), a non-linear transform, a dimension other than 3, a
/// transform without its parameters or with counts its type cannot hold (checked before ITK
/// parses the file, which takes the first as the identity and may crash on the second).
Matrix4 ReadItkLinearTransform(const std::string& fileName);

/// Writes m (LPS, "from parent", 4x4 row-major with a last row 0 0 0 1) as the one
/// AffineTransform_double_3_3 of an ITK transform file, the format chosen by the extension as
/// ReadItkLinearTransform reads it: what 3D Slicer writes for a linear transform node and loads as
/// one. Throws InputError naming the file when it cannot be written.
void WriteItkLinearTransform(const std::string& fileName, const Matrix4& m);

/// Whether fileName's extension is one of an ITK transform file (.h5, .hdf5, .tfm, .txt; any
/// case). Matlab's .mat, which Slicer reads but does not write, is not taken.
bool IsItkTransformFileName(const std::string& fileName);
} // namespace vp

#endif
