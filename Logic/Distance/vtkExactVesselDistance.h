#ifndef vtkExactVesselDistance_h
#define vtkExactVesselDistance_h

#include "vtkVesselDistanceEngine.h"

#include <memory>

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
class vtkExactVesselDistance : public vtkVesselDistanceEngine
{
public:
  static vtkExactVesselDistance* New();
  vtkTypeMacro(vtkExactVesselDistance, vtkVesselDistanceEngine);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void ComputeProximity(const double tip[3], const double* axis, vp::ProximityResult& result,
    const vp::ProximityResult* previous = nullptr) const override;
  const char* GetMethodName() const override { return "exact"; }

protected:
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
