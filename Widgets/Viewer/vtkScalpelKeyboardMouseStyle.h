#ifndef vtkScalpelKeyboardMouseStyle_h
#define vtkScalpelKeyboardMouseStyle_h

#include <vtkInteractorStyleTrackballCamera.h>

#include <string>

namespace vp
{
class ScalpelControls;
}

/// Trackball camera, plus the scalpel under the user's hands:
/// - arrow keys move the scalpel 1 mm in the view plane (with Shift 5 mm), PageUp/PageDown
///   towards/away from the viewer; i / o advance and retract it along its own axis;
/// - Ctrl + left drag moves it in the view plane, following the mouse;
/// - space plays or pauses the recorded poses, n / b step forward and back;
/// - x saves a screenshot, c frames the vessels again, h prints the keys.
/// VTK's own keys (r, w, s, 3, f, q, e) keep their meaning; p (pick) is switched off.
class vtkScalpelKeyboardMouseStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static vtkScalpelKeyboardMouseStyle* New();
  vtkTypeMacro(vtkScalpelKeyboardMouseStyle, vtkInteractorStyleTrackballCamera);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// What the keys and the mouse act on (the view; not owned: the view owns this style).
  void SetView(vp::ScalpelControls* view) { this->View = view; }
  /// Step of one key press, mm (default 1; Shift multiplies by 5).
  vtkSetClampMacro(StepMm, double, 0.01, 100.0);
  vtkGetMacro(StepMm, double);

  /// Acts on one key (a VTK key sym); returns whether it was ours. The keyboard and
  /// vtkVesselProximityView::PressKeys both come here.
  bool HandleKey(const std::string& keySym, bool shift);
  /// The keys, as the viewer prints them.
  static const char* KeyHelp();

  void OnKeyPress() override;
  void OnChar() override;
  void OnLeftButtonDown() override;
  void OnLeftButtonUp() override;
  void OnMouseMove() override;

protected:
  vtkScalpelKeyboardMouseStyle();
  ~vtkScalpelKeyboardMouseStyle() override;

  vp::ScalpelControls* View = nullptr;
  double StepMm = 1.0;
  bool Dragging = false;
  int LastPositionPx[2] = { 0, 0 };

private:
  vtkScalpelKeyboardMouseStyle(const vtkScalpelKeyboardMouseStyle&) = delete;
  void operator=(const vtkScalpelKeyboardMouseStyle&) = delete;
  /// The camera's right, up and towards-the-viewer directions (unit, world).
  void CameraAxes(double right[3], double up[3], double towardViewer[3]) const;
};

#endif
