#ifndef vpApproachGeometry_h
#define vpApproachGeometry_h

#include <array>
#include <vector>

class vtkOBBTree;
class vtkPolyData;

namespace vp
{
/// The geometry of a straight approach: where a line meets the target, which way the instrument
/// is turned, the directions of a cone. LPS mm; directions unit unless said.
using Vector3 = std::array<double, 3>;

/// The centre of the volume a closed surface encloses (the sum of the signed tetrahedra from its
/// triangles); its points' mean when it encloses none (a flat or open surface).
Vector3 EnclosedVolumeCentre(vtkPolyData* surface);

/// The distances along the line origin + t * direction, t in [0, lengthMm], at which it crosses
/// the surface (tree: built on it), in increasing order; a crossing at a shared edge counted once.
std::vector<double> LineCrossings(vtkOBBTree* tree, const Vector3& originMm, const Vector3& direction, double lengthMm);

/// The unit quaternion (w, x, y, z) of the shortest turn taking unit vector from onto unit vector
/// to; for opposite vectors, a half turn about an axis perpendicular to from.
std::array<double, 4> QuaternionTurning(const Vector3& from, const Vector3& to);

/// How far from pointMm, going along direction, the box (xmin, xmax, ymin, ymax, zmin, zmax) is
/// left; 0 when the point lies outside it.
double DistanceOutOfBox(const Vector3& pointMm, const Vector3& direction, const std::array<double, 6>& box);

/// A direction of a cone and its angle from the axis.
struct ConeDirection
{
  Vector3 Direction{};
  double AngleDeg = 0.0;
};

/// The directions within maxDeg of axis (unit), the axis itself excluded: on rings stepDeg apart
/// (and a last ring at maxDeg), each ring's directions about stepDeg apart around it (at least 6),
/// nearest rings first.
std::vector<ConeDirection> ConeDirections(const Vector3& axis, double maxDeg, double stepDeg);

Vector3 Normalized(const Vector3& v);
double Length(const Vector3& v);
} // namespace vp

#endif
