#ifndef vpSquaredDistanceTransform_h
#define vpSquaredDistanceTransform_h

#include <vector>

namespace vp
{
/// The one-dimensional squared Euclidean distance transform of Felzenszwalb and Huttenlocher
/// (2012): in place along a line of n values spaced spacingMm apart, f(p) becomes
/// min over q of f(q) + (spacingMm (p - q))^2, in linear time (the lower envelope of parabolas).
/// Infinite values never win. Applied along each axis in turn it gives the exact squared distance
/// to the zero cells of a grid; the distance fields of the z-buffer's layers are built so.
/// Keeps its work space between lines: one per thread.
class SquaredDistanceTransform
{
public:
  void Line(double* f, int n, double spacingMm);

private:
  std::vector<double> Values;
  std::vector<double> Cuts;
  std::vector<int> Parabolas;
};
} // namespace vp

#endif
