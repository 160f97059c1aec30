#ifndef vpProximityResult_h
#define vpProximityResult_h

#include <optional>
#include <string>
#include <vector>

namespace vp
{
/// The answer for one vessel class at one tip position.
struct ClassProximity
{
  std::string ClassName;
  /// False when the class has no surface within the engine's range of the tip; the distance and
  /// the point are then meaningless and reported as null.
  bool InRange = false;
  /// Unsigned distance from the tip to the nearest surface point of the class; with Inside true
  /// it is the penetration depth.
  double DistanceMm = 0.0;
  double ClosestPoint[3] = { 0.0, 0.0, 0.0 };
  /// Triangle holding ClosestPoint, -1 when out of range.
  long long TriangleId = -1;
  /// Whether the tip is inside the class's surface. On a surface that is not closed (holes,
  /// non-manifold edges, pieces wound the wrong way, duplicated sheets), the engines that can
  /// still decide it by votes do so; empty when the engine cannot decide it.
  std::optional<bool> Inside;
  /// The votes on a surface that is not closed disagreed (vp::InsideVote): Inside is the
  /// majority's, and the danger level takes the answer as a breach, the more dangerous side.
  bool InsideUncertain = false;
  /// Distance from the tip along the axis to the first surface of the class; empty when no axis
  /// was given or nothing is hit within range.
  std::optional<double> DirectionalMm;
};

/// The answer for all vessel classes at one tip position.
struct ProximityResult
{
  double Tip[3] = { 0.0, 0.0, 0.0 };
  /// The engine's bound on |reported - exact| for every distance below; 0 for exact engines.
  double ErrorBoundMm = 0.0;
  std::vector<ClassProximity> Classes;

  /// Index into Classes of the nearest in-range class, -1 when none is in range.
  int NearestIndex() const
  {
    int best = -1;
    for (int i = 0; i < static_cast<int>(this->Classes.size()); ++i)
    {
      if (this->Classes[i].InRange && (best < 0 || this->Classes[i].DistanceMm < this->Classes[best].DistanceMm))
      {
        best = i;
      }
    }
    return best;
  }
};

/// How far the instrument is inside one vessel class: its volume inside the class and the depth of
/// its deepest point, each within a stated bound (both 0 when nothing overlaps).
struct Penetration
{
  /// False when it could not be decided (an open vessel or instrument surface has no inside).
  bool Known = true;
  double DepthMm = 0.0;        ///< deepest instrument point inside, distance to the vessel wall
  double DepthBoundMm = 0.0;   ///< |DepthMm - exact| is at most this
  double VolumeMm3 = 0.0;      ///< instrument volume inside the class
  double VolumeBoundMm3 = 0.0; ///< |VolumeMm3 - exact| is at most this
  /// How many vessel-wall queries the answer took, and whether the walk's budget ended it (the
  /// bounds then carry what was left unsplit; vtkScalpelPenetration::SetQueryBudget).
  long long WallQueries = 0;
  bool BudgetReached = false;
};

/// The closest approach of the whole instrument surface (not only its tip) to one vessel class.
struct SurfaceProximity
{
  bool InRange = false;
  double DistanceMm = 0.0; ///< 0 when the surfaces touch or cross
  double PointOnToolMm[3] = { 0, 0, 0 };
  double PointOnVesselMm[3] = { 0, 0, 0 };
  /// The truth lies between DistanceMm and DistanceMm plus this (an approximate answer is the low
  /// end: it may overstate proximity, never understate it); 0 for the exact calculators.
  double ErrorBoundMm = 0.0;
  /// The closest pair's triangles (the calculator's own numbering; -1 when unknown): the next
  /// pose's search starts from them.
  long long ToolTriangle = -1;
  long long VesselTriangle = -1;
};
} // namespace vp

#endif
