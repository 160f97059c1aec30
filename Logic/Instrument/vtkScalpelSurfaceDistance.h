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
///
/// Written here before FCL was measured beside it: FCL's OBB-RSS tree pairs answer the demo's
/// frames 7x faster at the median and 30x at p95 (bench --engines replay), so the module uses
/// vtkFclSurfaceDistance and keeps this one as the independent exact reference the tests and the
/// bench check FCL against (it equals brute force over all triangle pairs).
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

  /// Per vessel class of the engine, in its order. Thread-safe after the first call. previous (may
  /// be null) is this calculator's answer for an earlier pose, which subclasses may use to start
  /// their search (this one does not: its cost lies in proving the minimum, not in finding it).
  virtual void ComputeSurfaceProximity(const std::array<double, 16>& modelToWorld, std::vector<vp::SurfaceProximity>& out,
    const std::vector<vp::SurfaceProximity>* previous = nullptr) const;

  /// Short name for reports: "spheres" here.
  virtual const char* GetMethodName() const { return "spheres"; }

  /// Triangles in the tool surface as searched (after triangulation and splitting), 0 before the
  /// first use.
  virtual long long GetNumberOfToolTriangles() const;

protected:
  vtkScalpelSurfaceDistance();
  ~vtkScalpelSurfaceDistance() override;

  /// The range searched: RangeMm, or the vessel engine's when that is shorter or RangeMm is 0.
  double SearchRangeMm() const;

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
