#ifndef vtkVesselProximityLogic_h
#define vtkVesselProximityLogic_h

#include "vpProximityResult.h"
#include "vpSceneRequest.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityParameters.h"

#include <vtkCommand.h>
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
class vtkTumourMarginDistance;
class vtkVesselDistanceEngine;

/// The module's logic: the scene (vessel surfaces per class, the scalpel) and everything computed
/// for a tracked pose. What vtkSlicerVesselProximityModuleLogic would be inside Slicer: a widget
/// or a command opens the scene (OpenScene, from a vp::SceneRequest), runs its poses through a
/// vp::TrackingSession and reads the frames; observers of GetTrackingLogic() hear of each frame
/// and of each change of danger level.
///
/// What it computes from lives in its parameter set (vtkVesselProximityParameters, the part a
/// MRML node plays in Slicer), which it observes; the setters below are shorthands that write
/// there. Engines and locators are built once, in Build() (or on the first pose), and again only
/// when the parameter set's scene changes (vessels, scalpel, engine, which engines are wanted);
/// never because the scalpel moved, nor for a new threshold. Unlike SlicerIGT's BreachWarning,
/// which rebuilds its locator whenever the tool moves.
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

  enum
  {
    /// A stage of opening or building the scene starts; call data: its name (const char*,
    /// "reading the vessels", "building the exact engine", ...), for a front end's progress.
    StageStartedEvent = vtkCommand::UserEvent + 1301
  };

  /// Opens the scene a front end asks for and leaves the logic ready to track: the engine made
  /// first (its Vulkan device opened before any file is read), the vessels read and repaired as
  /// asked, the liver read, the scalpel loaded and its tip defined, every setting written to the
  /// parameter set, the engines built and the settings checked against the engine (ValidateSettings
  /// of the tracking logic); the next pose is frame 0. One message per problem: throws
  /// ParameterError naming the setting, InputError naming the file, DeviceError for the device.
  vp::OpenedScene OpenScene(const vp::SceneRequest& request);

  /// The parameter set the logic computes from (one of its own until another is set), observed
  /// for ModifiedEvent. Not null.
  void SetParameters(vtkVesselProximityParameters* parameters);
  vtkVesselProximityParameters* GetParameters() const { return this->Parameters; }

  /// Adds or replaces the surface of a vessel class (LPS mm, closed for inside/outside).
  void AddVessel(const std::string& className, vtkPolyData* surface);
  void RemoveAllVessels();
  int GetNumberOfVessels() const;
  const std::string& GetVesselClassName(int i) const;
  vtkPolyData* GetVesselSurface(int i) const;
  /// The box around every vessel surface (xmin, xmax, ymin, ymax, zmin, zmax; LPS mm); false,
  /// with bounds untouched, when there is no vessel.
  bool GetVesselBounds(double bounds[6]) const;

  void SetScalpel(vtkScalpelModel* scalpel);
  vtkScalpelModel* GetScalpel() const;

  /// The engine that answers every frame (default: a vtkExactVesselDistance made here).
  void SetDistanceEngine(vtkVesselDistanceEngine* engine);
  vtkVesselDistanceEngine* GetDistanceEngine() const;

  /// Whether every frame is also answered by the exact engine (TrackedFrame::Exact), for the
  /// accuracy check (default false; pointless when the engine is the exact one).
  void SetCompareWithExact(bool compare);
  bool GetCompareWithExact() const;
  /// Whether the whole instrument surface is measured beside the tip (default true), with the
  /// instrument's penetration volume and depth in each class.
  void SetComputeSurfaceDistance(bool compute);
  bool GetComputeSurfaceDistance() const;

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

  vtkSmartPointer<vtkVesselProximityParameters> Parameters;
  unsigned long ParametersObserver = 0;
  vtkMTimeType AppliedSceneMTime = 0;
  vtkSmartPointer<vtkExactVesselDistance> Exact;
  vtkSmartPointer<vtkScalpelSurfaceDistance> Surface;
  vtkSmartPointer<vtkScalpelPenetration> Penetration;
  vtkSmartPointer<vtkTumourMarginDistance> TumourMargin;
  vtkSmartPointer<vtkScalpelTrackingLogic> Tracking;
  bool SceneChanged = true;
  int NumberOfBuilds = 0;

private:
  vtkVesselProximityLogic(const vtkVesselProximityLogic&) = delete;
  bool WantsSurfaceDistance() const;
  /// The whole instrument's calculator and its penetration, as the parameter set asks.
  void BuildInstrument(vtkVesselDistanceEngine* engine);
  /// The tumours' trees (with the instrument's surface when it is measured), or none.
  void BuildTumourMargin(bool surface);
  /// What a change of the parameter set invalidates: the built engines (scene), or only the
  /// tracking logic's per-frame settings.
  void ApplyParameters();
  /// StageStartedEvent with the stage's name.
  void StartStage(const std::string& stage);
  void operator=(const vtkVesselProximityLogic&) = delete;
};

#endif
