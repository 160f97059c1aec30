#ifndef vtkFclSurfaceDistance_h
#define vtkFclSurfaceDistance_h

#include "vpProximityResult.h"
#include "vtkScalpelSurfaceDistance.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <mutex>
#include <vector>

class vtkPolyData;

/// The whole-instrument distance answered by FCL (the Flexible Collision Library, Debian's
/// libfcl-dev; what MoveIt and Drake use for mesh-mesh distance): OBB-RSS bounding volume trees
/// of the instrument and of every vessel class, built once, and one fcl::distance per class and
/// pose with the pose as a transform (nothing is rebuilt when the tool moves).
///
/// The module's exact whole-instrument path. Two things make it cheaper than FCL used plainly,
/// with the same answers: the traversal starts from the engine's range (nothing farther is
/// searched) and, for a tracked tool, from the previous frame's closest pair measured at the new
/// pose (a tight upper bound from the first node pair on).
class vtkFclSurfaceDistance : public vtkScalpelSurfaceDistance
{
public:
  static vtkFclSurfaceDistance* New();
  vtkTypeMacro(vtkFclSurfaceDistance, vtkScalpelSurfaceDistance);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Builds the trees now (the first query builds them otherwise, and again after the tool or the
  /// vessel engine changed); GetBuildTimeMs() says how long the last build took.
  void Build();
  double GetBuildTimeMs() const { return this->BuildTimeMs; }

  /// Whether the previous frame's closest pair starts the search (default true). Off, FCL runs
  /// as it comes: the anchor in bench --engines replay.
  vtkSetMacro(WarmStart, bool);
  vtkGetMacro(WarmStart, bool);
  vtkBooleanMacro(WarmStart, bool);

  void ComputeSurfaceProximity(const std::array<double, 16>& modelToWorld, std::vector<vp::SurfaceProximity>& out,
    const std::vector<vp::SurfaceProximity>* previous = nullptr) const override;
  const char* GetMethodName() const override { return "fcl"; }
  long long GetNumberOfToolTriangles() const override;

protected:
  vtkFclSurfaceDistance();
  ~vtkFclSurfaceDistance() override;

  double BuildTimeMs = 0.0;
  bool WarmStart = true;

private:
  vtkFclSurfaceDistance(const vtkFclSurfaceDistance&) = delete;
  void operator=(const vtkFclSurfaceDistance&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
  std::mutex BuildLock;
};

#endif
