#ifndef vpBreachBenchmark_h
#define vpBreachBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpDistanceEngineSettings.h"
#include "vpVesselMeshSet.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelPenetration.h"
#include "vpPoseFile.h"

#include <vtkSmartPointer.h>

namespace vp
{
/// The breach: an instrument pushed into a patient's vessels, where the overlap (and with it an
/// unbounded walk) is largest.
struct BreachBenchSettings
{
  /// Surface points per class, chosen by area with the seed; each gives three poses: the tip
  /// 2 mm outside, pushed in along the inward normal, and withdrawn half way.
  int PointsPerClass = 40;
  /// The deepest push (mm): the points' pushes rise evenly to it.
  double MaxPushMm = 10.0;
  unsigned Seed = 1;
  /// The fine reference's lattice cell (mm): the volume and depth every engine is held to.
  double ReferenceCellMm = 0.2;
  /// The penetration's query budget for the engines measured (vtkScalpelPenetration's default
  /// unless set); the exact engine also runs without one beside, the walk before the budget.
  long long QueryBudget = vtkScalpelPenetration::DefaultQueryBudget;
};

/// The breach's poses (scalpel: its tip and axis place them): per class and surface point, the
/// tip 2 mm outside, pushed in along the inward normal, and withdrawn half way.
std::vector<TrackedPose> BreachPoses(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const BreachBenchSettings& settings);

/// The handpiece (scalpel: null for the built-in CUSA handpiece, else its model, tip and axis)
/// pushed into each class of the vessels: every frame through the logic (tip, whole instrument,
/// penetration), exact and (zbuffer not null) z-buffer, median and p95 over the run, over its
/// penetrating frames and per overlap band (< 100, 100-1,000, > 1,000 mm³ against the reference),
/// each frame's volume and depth against a fine reference (the exact walk without a budget at
/// ReferenceCellMm), the exact engine without a budget beside, and FCL's whole-instrument
/// distance on the same poses as the anchor.
BenchJson BenchBreach(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const BreachBenchSettings& settings,
  const DistanceEngineSettings* zbuffer);
} // namespace vp

#endif
