#ifndef vpScalpelControls_h
#define vpScalpelControls_h

#include <string>

class vtkRenderer;

namespace vp
{
/// What the keyboard and the mouse act on (vtkScalpelKeyboardMouseStyle): the scalpel, the
/// recorded poses, the camera and the picture. vtkVesselProximityView implements it; the style
/// knows only this, so the view and its style do not include each other.
class ScalpelControls
{
public:
  virtual ~ScalpelControls() = default;

  /// The renderer whose camera the keys and the mouse move in.
  virtual vtkRenderer* GetRenderer() const = 0;
  /// Where the scalpel's tip is now (world, mm).
  virtual void GetTipInWorld(double tipMm[3]) const = 0;
  /// Moves the scalpel by a world displacement (mm) and computes the frame.
  virtual void MoveScalpelBy(const double deltaMm[3]) = 0;
  /// Moves the scalpel along its own axis (positive: the tip advances).
  virtual void AdvanceScalpelBy(double mm) = 0;
  virtual void SetPlaying(bool playing) = 0;
  virtual bool GetPlaying() const = 0;
  virtual int GetNumberOfPoses() const = 0;
  virtual void ShowPose(int i) = 0;
  virtual int GetCurrentPose() const = 0;
  /// Writes the window as a PNG (numbered when file is empty) and returns its name.
  virtual std::string SaveScreenshot(const std::string& file) = 0;
  virtual void ResetCamera() = 0;
  virtual void Render() = 0;

protected:
  ScalpelControls() = default;
  ScalpelControls(const ScalpelControls&) = default;
  ScalpelControls& operator=(const ScalpelControls&) = default;
};
} // namespace vp

#endif
