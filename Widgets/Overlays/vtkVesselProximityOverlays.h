#ifndef vtkVesselProximityOverlays_h
#define vtkVesselProximityOverlays_h

#include "vtkScalpelTrackingLogic.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkCallbackCommand;
class vtkClosestPointLineRepresentation;
class vtkDistancePlotRepresentation;
class vtkPolyData;
class vtkProximityReadoutRepresentation;
class vtkRenderer;
class vtkScalpelDangerRepresentation;
class vtkVesselModelsRepresentation;
class vtkVesselProximityLogic;

/// The module's widget representation: everything drawn over a 3D view for one
/// vtkVesselProximityLogic, driven by its tracking events.
///
/// - vessels coloured by class (label table);
/// - the scalpel at its pose, coloured by danger level: recoloured on DangerLevelChangedEvent
///   only, moved (a user matrix) on FrameProcessedEvent;
/// - a line from the tip to the closest vessel point, labelled with the distance;
/// - one readout line per vessel class and the overall level;
/// - the distance-over-time plot.
///
/// Nothing the logic builds (locators, z-buffer layers) is touched here; a pose costs a matrix,
/// two line points, changed text and a plot redraw.
class vtkVesselProximityOverlays : public vtkObject
{
public:
  static vtkVesselProximityOverlays* New();
  vtkTypeMacro(vtkVesselProximityOverlays, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Observes the logic's tracking events (and stops observing the previous logic), and takes
  /// its vessels and scalpel surface.
  void SetLogic(vtkVesselProximityLogic* logic);
  vtkVesselProximityLogic* GetLogic() const;
  /// Re-reads the vessels, the scalpel surface and the thresholds from the logic: call after
  /// changing the scene.
  void UpdateFromScene();
  /// The liver surface, drawn translucent (optional; not part of the distance computation).
  void SetLiverSurface(vtkPolyData* liver);

  /// Adds every overlay to the renderer (one renderer at a time).
  void SetRenderer(vtkRenderer* renderer);
  vtkRenderer* GetRenderer() const { return this->Renderer; }

  /// Shows a frame; called for each FrameProcessedEvent, public for a viewer that replays
  /// recorded frames without the logic.
  void ShowFrame(const vp::TrackedFrame& frame);
  /// A live stream gave no pose for sinceMs: the readout says so and shows no distance, and the
  /// closest-point line is hidden, until the next frame.
  void ShowTrackingLost(double sinceMs);

  vtkVesselModelsRepresentation* GetVessels() const;
  vtkScalpelDangerRepresentation* GetScalpel() const;
  vtkClosestPointLineRepresentation* GetClosestPointLine() const;
  vtkProximityReadoutRepresentation* GetReadout() const;
  vtkDistancePlotRepresentation* GetPlot() const;

protected:
  vtkVesselProximityOverlays();
  ~vtkVesselProximityOverlays() override;

  vtkSmartPointer<vtkVesselProximityLogic> Logic;
  vtkRenderer* Renderer = nullptr; // not owned: the render window owns it and us
  vtkSmartPointer<vtkVesselModelsRepresentation> Vessels;
  vtkSmartPointer<vtkScalpelDangerRepresentation> Scalpel;
  vtkSmartPointer<vtkClosestPointLineRepresentation> ClosestLine;
  vtkSmartPointer<vtkProximityReadoutRepresentation> Readout;
  vtkSmartPointer<vtkDistancePlotRepresentation> Plot;
  vtkSmartPointer<vtkCallbackCommand> FrameObserver;
  vtkSmartPointer<vtkCallbackCommand> LevelObserver;
  unsigned long FrameTag = 0;
  unsigned long LevelTag = 0;
  std::string LineClass; ///< the class whose colour the closest-point line wears

private:
  vtkVesselProximityOverlays(const vtkVesselProximityOverlays&) = delete;
  void operator=(const vtkVesselProximityOverlays&) = delete;
  void StopObserving();
};

#endif
