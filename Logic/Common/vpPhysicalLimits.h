#ifndef vpPhysicalLimits_h
#define vpPhysicalLimits_h

#include "vpInputError.h"

#include <cmath>
#include <string>

namespace vp
{
/// The bounds every number from an input is held to before anything is computed or allocated
/// from it: what a patient, a scanner and a tracker can give, far beyond any real case and far
/// inside what the engines' arithmetic holds. A number past them is a unit error, a corrupt
/// file or an attack, and is refused with its source named.
namespace limits
{
/// Coordinates (mm), of meshes, tips, poses and image origins: 1 km. A patient lies within a
/// metre or two of any scanner's or tracker's origin; Embree and the z-buffer hold coordinates in
/// float relative to the scene, which at 1e6 mm still resolves 0.06 mm, while at 1e18 Embree's
/// own checks abort and at 1e20 a tip 1 mm inside a cube read out of range.
constexpr double CoordinateMm = 1e6;
/// A voxel's size (mm), along each axis: 1 micrometre to 1 metre (PixelSpacing 1e-300 gave a
/// model of no volume, an NRRD direction of 1e155 was built at 1 mm).
constexpr double MinVoxelMm = 1e-3;
constexpr double MaxVoxelMm = 1e3;
/// Time stamps (s): 1e12 s (31,000 years) holds Unix times and any recording's clock, and the
/// difference of two such stamps is still exact to a microsecond (±1.7e308 gave "over inf s").
constexpr double TimeS = 1e12;
/// The engines' range (mm): 2 m, more than any body. A range of 1e10 made every search cover
/// everything (300 frames took over a minute).
constexpr double MaxRangeMm = 2000.0;
/// Triangles in one model file: 5 million, more than any segmentation's surface (the models of a
/// 0.5 mm CT have a few hundred thousand) and the largest the z-buffer was measured with (4.5M a
/// class). A 10M-triangle vessel took 8 GB with the whole instrument (FCL's tree), or crashed.
constexpr double MaxModelTriangles = 5e6;
} // namespace limits

/// "" when |value| <= limit (and finite), else the problem in a few words.
inline std::string MagnitudeProblem(double value, double limit, const char* unit)
{
  if (std::isfinite(value) && std::fabs(value) <= limit)
  {
    return std::string();
  }
  return (std::isfinite(value) ? NumberText(value) : std::string("a NaN or infinite value")) + " " + unit +
    " is beyond " + "±" + NumberText(limit) + " " + unit;
}

/// Throws InputError(source, where + ": ...") when a point's coordinate (mm) is beyond
/// limits::CoordinateMm.
inline void CheckCoordinates(const double p[3], const std::string& source, const std::string& where)
{
  for (int a = 0; a < 3; ++a)
  {
    const std::string problem = MagnitudeProblem(p[a], limits::CoordinateMm, "mm");
    if (!problem.empty())
    {
      throw InputError(source, where + ": coordinate " + problem + " (a patient lies within metres of the origin)");
    }
  }
}
} // namespace vp

#endif
