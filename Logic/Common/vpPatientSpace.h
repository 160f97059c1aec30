#ifndef vpPatientSpace_h
#define vpPatientSpace_h

#include <array>

namespace vp
{
/// LPS (DICOM's patient frame, the logic's) <-> RAS (Slicer's view): x and y negated, so the
/// conversion is its own inverse.
inline std::array<double, 3> ConvertLpsRas(const std::array<double, 3>& p)
{
  return { -p[0], -p[1], p[2] };
}
} // namespace vp

#endif
