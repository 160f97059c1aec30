#ifndef vtkVesselProximityView_h
#define vtkVesselProximityView_h

#include "vpPoseFile.h"
#include "vpScalpelControls.h"
#include "vpTipOcclusion.h"

#include <vtkImageData.h>
#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

class vtkPolyData;
class vtkRenderer;
class vtkRenderWindow;
class vtkRenderWindowInteractor;
class vtkScalpelKeyboardMouseStyle;
class vtkVesselProximityLogic;
class vtkVesselProximityOverlays;
namespace vp
{
class FrameOutput;
class TrackingSession;
class LivePoseSource;
}

/// A 3D view of the module: the overlays of a vtkVesselProximityLogic in a render window, with
/// the scalpel moved by keys and mouse (vtkScalpelKeyboardMouseStyle) or replayed from poses.
///
/// Every move becomes a pose of the view's tracking session (vp::TrackingSession); the overlays
/// are its first output, then the outputs added with AddOutput.
/// The camera starts looking from anterior with superior up, as Slicer's 3D view does, framed on
/// the vessels. Off-screen rendering (SetOffScreen) serves screenshots and tests; it still needs
/// an X display on Debian's VTK (Xvfb will do).
class vtkVesselProximityView : public vtkObject, public vp::ScalpelControls
{
public:
  static vtkVesselProximityView* New();
  vtkTypeMacro(vtkVesselProximityView, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The logic to show and drive; its scene must be set (vessels, scalpel).
  void SetLogic(vtkVesselProximityLogic* logic);
  vtkVesselProximityLogic* GetLogic() const;
  void SetLiverSurface(vtkPolyData* liver);
  /// The overlays that draw the logic (default: new ones). A module hands in its widget
  /// representation here (vpVesselProximityModule::CreateWidgetRepresentation); the logic already
  /// set is handed on to them.
  void SetOverlays(vtkVesselProximityOverlays* overlays);
  vtkVesselProximityOverlays* GetOverlays() const;
  vtkRenderer* GetRenderer() const override;
  void GetTipInWorld(double tipMm[3]) const override;
  vtkRenderWindow* GetRenderWindow() const;

  /// Window size in pixels (default 1280 x 800).
  void SetSizePx(int width, int height);
  void SetOffScreen(bool offScreen);

  /// Recorded poses for replay (n, b, space); the first is shown by ShowPose(0).
  void SetPoses(const std::vector<vp::TrackedPose>& poses);
  int GetNumberOfPoses() const override { return static_cast<int>(this->Poses.size()); }
  /// Shows recorded pose i: the logic computes its frame, the overlays follow; a pose the tracker
  /// lost (TrackedPose::Lost) shows "tracking lost" instead.
  void ShowPose(int i) override;
  int GetCurrentPose() const override { return this->CurrentPose; }
  /// Shows recorded poses 0 to last in one fresh session (the plot showing the way there), its
  /// outputs told of each and of the replay's end, and leaves pose last current: poses shown
  /// afterwards continue that session. Returns false when a held signal stopped the replay
  /// (vp::TrackingSession::Run).
  bool ReplayTo(int last);
  /// Moves the scalpel from where it is by a world displacement (mm) and computes the frame.
  void MoveScalpelBy(const double deltaMm[3]) override;
  /// Moves the scalpel along its own axis (positive: the tip advances).
  void AdvanceScalpelBy(double mm) override;
  /// Sets the scalpel's pose directly (model-to-world, row-major).
  void SetScalpelPose(const std::array<double, 16>& modelToWorld);
  /// Replay: steps to the next pose on every timer tick while playing.
  void SetPlaying(bool playing) override;
  bool GetPlaying() const override { return this->Playing; }

  /// An output told of every frame the view computes, from any session it starts (not owned:
  /// it outlives the view's frames): vp::FrameOutput.
  void AddOutput(vp::FrameOutput* output);

  /// Follows a live stream (vp::LivePoseSource, which must outlive the view): each pose it gives
  /// is shown as it comes, a loss as "tracking lost" (vtkVesselProximityOverlays::ShowTrackingLost:
  /// no distance is shown as current). Start() looks at it every 10 ms; FollowLiveFor() follows
  /// it without a window loop, for screenshots and scripts.
  void SetLiveSource(vp::LivePoseSource* source) { this->Live = source; }
  /// Follows the stream for seconds, or until it ends, rendering after each change.
  void FollowLiveFor(double seconds);
  /// Whether the stream's last word was a loss (nothing shown as current).
  bool GetTrackingLost() const { return this->TrackingLost; }

  /// Where the camera looks from (patient directions, the world being LPS): anterior (the default,
  /// superior up, as Slicer's 3D view), lateral (from the patient's right, superior up), superior
  /// (from above, anterior up), tool (beside the scalpel on its anterior side, the tip in the
  /// middle and the shaft pointing up the screen, each frame), follow (the camera keeps its
  /// direction and distance and moves with the tip, each frame) or clear (beside the tool across
  /// the line from the tip to the nearest vessel's closest point, turned until a rendered picture
  /// shows both in plain sight: vp::PlaceClearViewCamera, before each render of a new frame). The
  /// first three frame the vessels once.
  enum class CameraPreset
  {
    Anterior,
    Lateral,
    Superior,
    Tool,
    Follow,
    Clear
  };
  /// The preset's name as --view takes it ("anterior"), and back (false for an unknown one).
  static const char* CameraPresetName(CameraPreset preset);
  static bool ParseCameraPreset(const std::string& name, CameraPreset& preset);
  void SetCameraPreset(CameraPreset preset);
  CameraPreset GetCameraPreset() const { return this->Preset; }
  /// Frames the vessels from the preset's direction.
  void ResetCamera() override;
  void Render() override;
  /// Renders and writes the window as a PNG (whole or not at all). Throws vp::InputError
  /// naming the file when it cannot be written. Screenshots are numbered when file is empty:
  /// <ScreenshotPrefix>NNN.png.
  std::string SaveScreenshot(const std::string& file = std::string()) override;
  /// The picture the last SaveScreenshot wrote (RGB), or null: what a caller checks without
  /// reading the file back.
  vtkImageData* GetLastScreenshot() const { return this->LastScreenshot; }
  void SetScreenshotPrefix(const std::string& prefix) { this->ScreenshotPrefix = prefix; }

  /// Hands the window to the user until it is closed.
  void Start();
  /// Sends key presses through the same handler as the keyboard (names as VTK's key syms:
  /// "Left", "Up", "Prior", "i", "x", "space", ...): scripted sessions and tests.
  void PressKeys(const std::vector<std::string>& keys);
  /// The key help the viewer prints (vtkScalpelKeyboardMouseStyle's keys).
  static const char* KeyHelp();

protected:
  vtkVesselProximityView();
  ~vtkVesselProximityView() override;

  vtkSmartPointer<vtkVesselProximityOverlays> Overlays;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkRenderWindowInteractor> Interactor;
  vtkSmartPointer<vtkScalpelKeyboardMouseStyle> Style;
  std::vector<vp::TrackedPose> Poses;
  int CurrentPose = -1;
  double TimeS = 0.0; ///< time stamped on poses made by moving the scalpel by hand
  /// The poses shown so far, through the logic's frame loop; a new one when time jumps back.
  std::unique_ptr<vp::TrackingSession> Session;
  std::vector<vp::FrameOutput*> Outputs;
  bool Playing = false;
  int TimerId = -1;
  vp::LivePoseSource* Live = nullptr;
  bool TrackingLost = false;
  int ScreenshotCount = 0;
  vtkSmartPointer<vtkImageData> LastScreenshot;
  std::string ScreenshotPrefix = "vesselproximity-screenshot-";
  CameraPreset Preset = CameraPreset::Anterior;
  /// Frames shown so far, and the one the clear camera was last placed for (-1: none since the
  /// preset was set).
  long long FramesShown = 0;
  long long ClearCameraFrame = -1;
  /// The clear preset's camera for the logic's last frame, when not placed for it yet.
  void PlaceClearCamera();
  /// The fixed presets keep their direction: where a vessel hides the tip from it, the vessels are
  /// seen through (vtkVesselModelsRepresentation::SetSeeThrough) until none does.
  void SeeThroughVesselsHidingTheTip();
  vp::TipOcclusion Occlusion;
  /// The orientation marker: a cube labelled with the patient's directions (L/R, A/P, S/I) in the
  /// lower left corner, its own renderer turned with the main camera before each render.
  vtkSmartPointer<vtkRenderer> MarkerRenderer;

private:
  vtkVesselProximityView(const vtkVesselProximityView&) = delete;
  void operator=(const vtkVesselProximityView&) = delete;
  class Display;
  std::unique_ptr<Display> Shown; ///< the session's first output: overlays, then camera
  /// The session a pose at timeS belongs to (a new one when time jumped back or the logic
  /// changed), or null when there is no scene to track in.
  vp::TrackingSession* SessionFor(double timeS);
  void StartSession();
  void Process(const std::array<double, 16>& modelToWorld, double timeS);
  /// The tool and follow presets: the camera put where the scalpel now asks.
  void FollowScalpel();
  void OnTimer();
  /// Takes what the live stream has (waiting at most waitMs for the first): whether anything
  /// changed, and false in ended when the stream is over.
  bool FollowLive(double waitMs, bool& ended);
};

#endif
