#ifndef vpSurfaceIcpRegistration_h
#define vpSurfaceIcpRegistration_h

#include "vpRigidTransform.h"

#include <array>
#include <vector>

class vtkPolyData;

namespace vp
{
/// The result of fitting a model surface to measured points.
struct SurfaceRegistration
{
  std::array<double, 16> ModelToWorld{}; ///< row-major
  double MeanResidualMm = 0.0;           ///< mean distance from each measured point to the placed surface
  double MedianResidualMm = 0.0;         ///< their median
  double P95ResidualMm = 0.0;            ///< and 95th percentile
  std::vector<double> ResidualsMm;       ///< each measured point's, in their order
  /// The fraction of the points farther than FarResidualFactor times the median residual from
  /// the placed surface. A fit that explains the points leaves noise only, whose tail is thin (a
  /// normal error: 0.7%); a wrong minimum leaves a part of the instrument off by millimetres.
  double FarFraction = 0.0;
  int Iterations = 0;
  int Starts = 1;                        ///< the starts tried (multi-start)

  static constexpr double FarResidualFactor = 4.0;
  /// Measured on the PLUS scalpel, the Straizys holder and the PLUS pointer, 400 points with
  /// 0.1 mm noise, multi-start fits from 10 mm and 10 degrees off: 45 right ones (within 0.31
  /// degrees and 0.09 mm) left at most 3% of the points far, the 3 wrong ones (1 to 9 degrees,
  /// 0.9 to 7.4 mm off) 4.5% or more.
  static constexpr double MaximumFarFraction = 0.0375;
  /// A stylus digitises a surface within a few tenths of a millimetre: a median residual above
  /// this is not noise (points measured on another instrument, a fit gone astray).
  static constexpr double MaximumMedianResidualMm = 1.0;
  /// Whether the fit explains the points: FarFraction at most MaximumFarFraction and the median
  /// residual at most MaximumMedianResidualMm.
  bool ExplainsThePoints() const
  {
    return this->FarFraction <= MaximumFarFraction && this->MedianResidualMm <= MaximumMedianResidualMm;
  }
};

/// Rigid ICP of a model surface (model coordinates) to points measured on it in world
/// coordinates, from an initial model-to-world guess (from landmarks, say). Point-to-plane
/// (Chen and Medioni), linearised and solved each iteration, until the fit moves less than 0.1
/// micrometre or maximumIterations. ICP converges to the nearest fit, so the guess must be within
/// a few millimetres and degrees. Throws vp::InputError for fewer than 6 points or an empty
/// surface (which must be triangles).
SurfaceRegistration RegisterSurfaceIcp(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& initialModelToWorld, int maximumIterations = 100);

/// Multi-start ICP for instruments a single ICP cannot fit from a rough guess (a thin blade
/// slides along its own shaft into a wrong minimum from 10 mm off): ICP from each of IcpStarts
/// (the guess; turned 10 and 20 degrees either way, shifted 5 and 10 mm either way: 25 starts)
/// for 30 iterations on a hundred of the points, the three with the least mean residual refined
/// to convergence on all of them. Then it hops: the same from 25 starts turned 2 and 4 degrees
/// and shifted 1.5 and 3 mm around the best fit (10 iterations, the best one refined), taken
/// while it lowers the mean residual by 1%, at most four times; the wide starts alone can stop in
/// a minimum a millimetre or a degree beside the right one. Measured on the PLUS scalpel and the
/// Straizys holder, 80 trials from 10 mm and 10 degrees off: all within 0.37 degrees and 0.18 mm
/// (the wide starts alone: 2 wrong). Whether the answer explains the points is still the
/// caller's to ask (SurfaceRegistration::ExplainsThePoints).
SurfaceRegistration RegisterSurfaceIcpMultiStart(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& guessModelToWorld);

/// The starts of a multi-start ICP around a guess: the guess itself, and the guess turned by
/// each of turnsDeg about each principal axis of the measured points (through their centroid),
/// and shifted by each of shiftsMm along each.
std::vector<Matrix4> IcpStarts(const std::vector<Point3>& worldPoints, const Matrix4& guess, const std::vector<double>& turnsDeg,
  const std::vector<double>& shiftsMm);
} // namespace vp

#endif
