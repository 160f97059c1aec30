#ifndef vtkVesselProximityLogic_h
#define vtkVesselProximityLogic_h

#include "vpProximityResult.h"
#include "vtkScalpelTrackingLogic.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

class vtkExactVesselDistance;
class vtkPolyData;
class vtkScalpelModel;
class vtkScalpelSurfaceDistance;
class vtkScalpelPenetration;
class vtkVesselDistanceEngine;

/// The module's logic: the scene (vessel surfaces per class, the scalpel) and everything computed
/// for a tracked pose. What vtkSlicerVesselProximityModuleLogic would be inside Slicer: a widget
/// or a command sets the scene, calls ProcessPose() per pose and reads the frame; observers of
/// GetTrackingLogic() hear of each frame and of each change of danger level.
///
/// Engines and locators are built once, in Build() (or on the first pose), and again only when
/// the vessels, the scalpel model or the engine change; never because the scalpel moved. Unlike
/// SlicerIGT's BreachWarning, which rebuilds its locator whenever the tool moves.
///
/// Defaults: the exact engine answers; the whole instrument surface is measured too (exactly, by
/// FCL; from the layers, within their bound, when the engine is the z-buffer with its fixed box);
/// answers are not compared with the exact engine (switch it on with an approximate engine).
class vtkVesselProximityLogic : public vtkObject
{
public:
  static vtkVesselProximityLogic* New();
  vtkTypeMacro(vtkVesselProximityLogic, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds or replaces the surface of a vessel class (LPS mm, closed for inside/outside).
  void AddVessel(const std::string& className, vtkPolyData* surface);
  void RemoveAllVessels();
  int GetNumberOfVessels() const { return static_cast<int>(this->Vessels.size()); }
  const std::string& GetVesselClassName(int i) const { return this->Vessels[i].first; }
  vtkPolyData* GetVesselSurface(int i) const { return this->Vessels[i].second; }
  /// The box around every vessel surface (xmin, xmax, ymin, ymax, zmin, zmax; LPS mm); false,
  /// with bounds untouched, when there is no vessel.
  bool GetVesselBounds(double bounds[6]) const;

  void SetScalpel(vtkScalpelModel* scalpel);
  vtkScalpelModel* GetScalpel() const;

  /// The engine that answers every frame (default: a vtkExactVesselDistance made here).
  void SetDistanceEngine(vtkVesselDistanceEngine* engine);
  vtkVesselDistanceEngine* GetDistanceEngine() const { return this->Engine; }

  /// Whether every frame is also answered by the exact engine, for GetLastExactProximity() and
  /// the accuracy check (default false; pointless when the engine is the exact one).
  vtkSetMacro(CompareWithExact, bool);
  vtkGetMacro(CompareWithExact, bool);
  vtkBooleanMacro(CompareWithExact, bool);
  /// Whether the whole instrument surface is measured beside the tip (default true), with the
  /// instrument's penetration volume and depth in each class.
  vtkSetMacro(ComputeSurfaceDistance, bool);
  vtkGetMacro(ComputeSurfaceDistance, bool);
  vtkBooleanMacro(ComputeSurfaceDistance, bool);

  void SetDangerThresholds(const vp::DangerThresholds& thresholds);
  const vp::DangerThresholds& GetDangerThresholds() const;

  /// Builds what is out of date. Throws vp::InputError naming a class whose mesh is unusable.
  void Build();
  /// How many times Build() did work: stays put while only the scalpel moves.
  int GetNumberOfBuilds() const { return this->NumberOfBuilds; }

  /// Computes the frame for a pose (building first if needed); observers of the tracking logic
  /// are told. The reference is valid until the next call.
  const vp::TrackedFrame& ProcessPose(const vp::TrackedPose& pose);
  const vp::TrackedFrame& GetLastFrame() const;
  /// The exact engine's answer for the last frame (CompareWithExact on), or that frame's own
  /// answer when the engine is the exact one.
  const vp::ProximityResult& GetLastExactProximity() const;
  /// Starts a new tracking session: the next pose is frame 0, from the safe level.
  void ResetTracking();

  /// Observe this for FrameProcessedEvent and DangerLevelChangedEvent.
  vtkScalpelTrackingLogic* GetTrackingLogic() const { return this->Tracking; }
  /// The exact engine serving the comparison and the surface distance: the distance engine
  /// itself when it is exact; null before Build() and when neither is wanted.
  vtkExactVesselDistance* GetExactDistance() const { return this->Exact; }

protected:
  vtkVesselProximityLogic();
  ~vtkVesselProximityLogic() override;

  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Vessels;
  vtkSmartPointer<vtkVesselDistanceEngine> Engine;
  vtkSmartPointer<vtkExactVesselDistance> Exact;
  vtkSmartPointer<vtkScalpelSurfaceDistance> Surface;
  vtkSmartPointer<vtkScalpelPenetration> Penetration;
  vtkSmartPointer<vtkScalpelTrackingLogic> Tracking;
  bool CompareWithExact = false;
  bool ComputeSurfaceDistance = true;
  bool SceneChanged = true;
  int NumberOfBuilds = 0;
  vp::ProximityResult LastExact;

private:
  vtkVesselProximityLogic(const vtkVesselProximityLogic&) = delete;
  bool WantsSurfaceDistance() const;
  void operator=(const vtkVesselProximityLogic&) = delete;
};

#endif
