#ifndef vtkBruteForceVesselDistance_h
#define vtkBruteForceVesselDistance_h

#include "vtkVesselDistanceEngine.h"

/// The CPU algorithm of Noborio et al. (the paper's Steps 1-8), kept as the reference the other
/// engines are tested and benchmarked against: for every triangle, the distance to its plane when
/// the foot of the perpendicular lies inside it, else the distance to its edges and vertices; the
/// minimum over all triangles. O(triangles) per query, no acceleration structure, one thread.
/// The directional distance likewise tests the axis ray against every triangle.
class vtkBruteForceVesselDistance : public vtkVesselDistanceEngine
{
public:
  static vtkBruteForceVesselDistance* New();
  vtkTypeMacro(vtkBruteForceVesselDistance, vtkVesselDistanceEngine);

  void ComputeProximity(const double tip[3], const double* axis, vp::ProximityResult& result,
    const vp::ProximityResult* previous = nullptr) const override;
  std::string GetDeviceDescription() override { return "cpu (every triangle, one thread)"; }
  const char* GetMethodName() const override { return "brute"; }
  bool IsExact() const override { return true; }

protected:
  vtkBruteForceVesselDistance();
  ~vtkBruteForceVesselDistance() override;
  void BuildInternal() override {}

private:
  vtkBruteForceVesselDistance(const vtkBruteForceVesselDistance&) = delete;
  void operator=(const vtkBruteForceVesselDistance&) = delete;
};

#endif
