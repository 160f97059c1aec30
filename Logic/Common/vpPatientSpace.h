#ifndef vpPatientSpace_h
#define vpPatientSpace_h

#include <array>

namespace vp
{
/// The frame a point's or a pose's world coordinates are in: LPS (DICOM's patient frame, ours)
/// or RAS (3D Slicer's), x and y negated between them.
enum class PoseSpace
{
  LPS,
  RAS
};

/// "LPS", "RAS".
inline const char* PoseSpaceName(PoseSpace space)
{
  return space == PoseSpace::RAS ? "RAS" : "LPS";
}

/// LPS (DICOM's patient frame, the logic's) <-> RAS (Slicer's view) when ras, the point as it is
/// otherwise: x and y negated, so the conversion is its own inverse (points given in RAS come in
/// through it, answers go out through it).
inline std::array<double, 3> ConvertSpace(const std::array<double, 3>& p, bool ras)
{
  return ras ? std::array<double, 3>{ -p[0], -p[1], p[2] } : p;
}
} // namespace vp

#endif
