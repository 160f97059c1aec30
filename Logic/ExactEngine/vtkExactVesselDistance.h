#ifndef vtkExactVesselDistance_h
#define vtkExactVesselDistance_h

#include "vtkVesselDistanceEngine.h"

#include <functional>
#include <memory>
#include <optional>

namespace vp
{
class InsideVoteField;
}

/// Exact distance from a point to each vessel class, answered from a bounding volume hierarchy
/// built once per mesh (Embree's BVH and its point queries; Embree is the well-kept library
/// the ray-tracing world relies on, in Debian as libembree).
///
/// Embree keeps vertices in single precision, so its tree only proposes candidate triangles:
/// every distance is computed in double from the original coordinates, and the search sphere is
/// widened by the float rounding of the tree (a few micrometres) so no triangle that could be
/// closer is skipped. The result equals the brute-force reference to rounding.
///
/// The search starts with the engine's range as its radius, or, when the previous answer for a
/// moving tip is passed in, with previous distance + displacement (the triangle inequality), so
/// a tracked tip costs a few node visits. ComputeProximity() is thread-safe after Build().
///
/// Inside: on a closed surface, the angle-weighted pseudonormal at the closest point (exact).
/// On one that is not closed (VesselSurface::Defects()), vp::InsideVote over Embree's rays: the
/// majority of the crossing parities along five fixed rays; when they disagree InsideUncertain
/// says so, and the danger level is a breach.
class vtkExactVesselDistance : public vtkVesselDistanceEngine
{
public:
  static vtkExactVesselDistance* New();
  /// The exact engine that serves beside engine (the whole instrument, the comparison): engine
  /// itself when it is an exact one; else, when needed, a new one with engine's range; else null.
  static vtkSmartPointer<vtkExactVesselDistance> ServingBeside(vtkVesselDistanceEngine* engine, bool needed);
  vtkTypeMacro(vtkExactVesselDistance, vtkVesselDistanceEngine);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void ComputeProximity(const double tip[3], const double* axis, vp::ProximityResult& result,
    const vp::ProximityResult* previous = nullptr) const override;
  const char* GetMethodName() const override { return "exact"; }
  bool IsExact() const override { return true; }
  /// Whether inside is decided on a surface that is not closed, by the vote of rays (default
  /// on). Off: it stays empty there, as before the vote, for callers that need only distances
  /// and for the bench's measure of what the vote costs.
  vtkSetMacro(VoteOnOpenSurfaces, bool);
  vtkGetMacro(VoteOnOpenSurfaces, bool);
  /// The cell edge of each open surface's inside vote field (vp::InsideVoteField), which answers
  /// most votes without a ray (grown where the field would hold more than 2^24 cells, a byte
  /// each; built with the tree when votes are on; set before Build()). Default 0, none: every
  /// vote casts its rays, as the brute force does, so that this engine's answers stay the brute
  /// force's to the flag (the field differs from the rays in thin bands behind folds of the
  /// surface, vp::InsideVoteField). The z-buffer's vote engine sets 1 mm (vtkZBufferVesselDistance::SetVoteFieldCellMm).
  vtkSetMacro(VoteFieldCellMm, double);
  vtkGetMacro(VoteFieldCellMm, double);
  /// Class classIndex's inside vote field, or null (a closed surface, votes off, or no field).
  const vp::InsideVoteField* GetVoteField(int classIndex) const;
  std::string GetDeviceDescription() override { return "cpu (Embree BVH)"; }

  /// Receives a triangle of the class (its index in GetSurface()) that may lie within the search
  /// sphere, and returns the radius still worth searching: never more than before, so each
  /// closer find prunes the rest of the tree.
  using TriangleVisitor = std::function<double(long long triangle)>;
  /// Calls visit for every triangle of class classIndex whose tree node meets the sphere of
  /// radiusMm about centre (after Build()). Candidates only: the visitor computes the distance.
  /// For queries other than the tip's, such as the whole instrument surface.
  void VisitTrianglesNear(int classIndex, const double centre[3], double radiusMm, const TriangleVisitor& visit) const;
  /// Distance from point to the nearest triangle of class classIndex, or +infinity when none lies
  /// within radiusMm. inside (may be null) receives whether point is inside the class's surface
  /// (empty for an open surface, or when nothing lies within radiusMm). When a triangle lies
  /// within radiusMm, wallPoint (may be null) receives the nearest point of the surface and
  /// outwardNormal (may be null; closed surfaces) the surface's outward direction there: from the
  /// point to the wall for a point inside, away from it for one outside, the triangle's own
  /// normal for a point on it.
  double NearestDistanceWithin(int classIndex, const double point[3], double radiusMm,
    std::optional<bool>* inside = nullptr, double wallPoint[3] = nullptr, double outwardNormal[3] = nullptr) const;
  /// The distance from point to class classIndex's surface to a tolerance: at least the truth
  /// and at most toleranceMm more. Deep inside a vessel many triangles are nearly equidistant (at
  /// a sphere's centre, all), and the exact search reads them all; this one skips every tree node
  /// that cannot beat the best by more than the tolerance. knownWithinMm: a distance the surface
  /// is known to lie within (a neighbour's distance plus the step between them), searched in one
  /// sphere; +infinity when none is known (+infinity is returned when none lies within it). No
  /// inside: the triangle found need not be the nearest. wallPoint (may be null) receives the
  /// point of the surface at the distance returned.
  double DistanceUpperBoundWithin(int classIndex, const double point[3], double knownWithinMm, double toleranceMm,
    double wallPoint[3] = nullptr) const;
  /// The inside vote (vp::InsideVote) of class classIndex at point, whatever its surface, for an
  /// engine that cannot decide inside on a surface that is not closed (the z-buffer's one ray).
  /// distanceMm is the point's distance to the surface (a point on it is outside).
  bool VoteInside(int classIndex, const double point[3], double distanceMm, bool& uncertain) const;
  /// For a tip whose class has no surface within the range: whether the tip is inside the class
  /// (or may be: the votes disagreed), and then out gets the whole answer, in range, with the
  /// true depth however far the wall (the nearest triangle searched without a limit). A tip
  /// inside a vessel is a breach whatever the range. out is left as it was otherwise.
  bool FindDepthBeyondRange(int classIndex, const double tip[3], vp::ClassProximity& out) const;

protected:
  bool VoteOnOpenSurfaces = true;
  double VoteFieldCellMm = 0.0;
  vtkExactVesselDistance();
  ~vtkExactVesselDistance() override;
  void BuildInternal() override;

private:
  vtkExactVesselDistance(const vtkExactVesselDistance&) = delete;
  void operator=(const vtkExactVesselDistance&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
