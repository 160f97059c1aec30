#ifndef vtkScalpelSurfaceDistance_h
#define vtkScalpelSurfaceDistance_h

#include "vpProximityResult.h"
#include "vtkExactVesselDistance.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <vector>

class vtkPolyData;

/// The minimum distance from every point of an instrument's surface (not only its tip) to each
/// vessel class: a shaft can touch a vessel before the tip does.
///
/// Exact, like the tip's: the instrument's triangles are grouped once into a bounding-sphere
/// tree in model coordinates; per pose, the tree is searched best first, each node's lower bound
/// being the exact distance from its sphere's centre less its radius (an Embree point query on
/// the vessel tree), and the leaves' triangles are measured triangle to triangle in double
/// precision. Crossing surfaces give 0. Uses the vessel trees of a vtkExactVesselDistance, which
/// must have been built; classes further than its range are reported out of range.
class vtkScalpelSurfaceDistance : public vtkObject
{
public:
  static vtkScalpelSurfaceDistance* New();
  vtkTypeMacro(vtkScalpelSurfaceDistance, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetVesselDistance(vtkExactVesselDistance* engine);
  vtkExactVesselDistance* GetVesselDistance() const { return this->Vessels; }
  /// Surfaces further apart than this are reported out of range. Default 0: the vessel engine's
  /// range. A shorter one (the caution threshold, say) makes each pose much cheaper: a long
  /// instrument among many vessels has many candidates within 50 mm.
  vtkSetMacro(RangeMm, double);
  vtkGetMacro(RangeMm, double);

  /// The instrument surface in model coordinates (polygons; triangulated here).
  void SetToolSurface(vtkPolyData* model);

  /// Per vessel class of the engine, in its order. Thread-safe after the first call.
  void ComputeSurfaceProximity(const std::array<double, 16>& modelToWorld, std::vector<vp::SurfaceProximity>& out) const;

  /// Triangles in the tool surface (after triangulation), 0 before the first use.
  long long GetNumberOfToolTriangles() const;

protected:
  vtkScalpelSurfaceDistance();
  ~vtkScalpelSurfaceDistance() override;

  vtkSmartPointer<vtkExactVesselDistance> Vessels;
  vtkSmartPointer<vtkPolyData> ToolSurface;
  double RangeMm = 0.0;

private:
  vtkScalpelSurfaceDistance(const vtkScalpelSurfaceDistance&) = delete;
  void operator=(const vtkScalpelSurfaceDistance&) = delete;

  struct ToolTree;
  void EnsureTree() const;
  mutable std::shared_ptr<const ToolTree> Tree;
};

#endif
