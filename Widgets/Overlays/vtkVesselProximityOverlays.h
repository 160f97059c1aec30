#ifndef vtkVesselProximityOverlays_h
#define vtkVesselProximityOverlays_h

#include "vpFrameOutput.h"
#include "vtkScalpelTrackingLogic.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkClosestPointLineRepresentation;
class vtkDistancePlotRepresentation;
class vtkPolyData;
class vtkProximityReadoutRepresentation;
class vtkRenderer;
class vtkScalpelDangerRepresentation;
class vtkVesselModelsRepresentation;
class vtkVesselProximityLogic;

/// The module's widget representation: everything drawn over a 3D view for one
/// vtkVesselProximityLogic, an output of the frame pipeline (vp::FrameOutput: add it to the
/// session that runs the logic's frames, as vtkVesselProximityView does).
///
/// - vessels coloured by class (label table);
/// - the scalpel at its pose, coloured by danger level: recoloured on a change of level only,
///   moved (a user matrix) on each frame;
/// - a line from the tip to the closest vessel point, labelled with the distance;
/// - one readout line per vessel class and the overall level;
/// - the distance-over-time plot.
///
/// Nothing the logic builds (locators, z-buffer layers) is touched here; a pose costs a matrix,
/// two line points, changed text and a plot redraw.
class vtkVesselProximityOverlays : public vtkObject, public vp::FrameOutput
{
public:
  static vtkVesselProximityOverlays* New();
  vtkTypeMacro(vtkVesselProximityOverlays, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Takes the logic's vessels, scalpel surface and thresholds (its frames come as an output).
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

  /// As an output of the frame pipeline: the scalpel recoloured on a change of level, each frame
  /// shown, a lost pose shown as tracking lost since the last frame shown.
  void OnLevelChange(const vp::DangerLevelChange& change) override;
  void OnFrame(const vp::TrackedFrame& frame) override { this->ShowFrame(frame); }
  void OnLost(const vp::TrackedPose& pose) override;

  /// Shows a frame; public for a viewer that replays recorded frames without the logic.
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
  std::string LineClass; ///< the class whose colour the closest-point line wears
  double LastFrameTimeS = 0.0; ///< the last frame shown, from which a loss is counted

private:
  vtkVesselProximityOverlays(const vtkVesselProximityOverlays&) = delete;
  void operator=(const vtkVesselProximityOverlays&) = delete;
};

#endif
