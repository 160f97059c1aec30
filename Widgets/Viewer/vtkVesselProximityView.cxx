#include "vtkVesselProximityView.h"

#include "vpClearViewCamera.h"

#include "vpClock.h"
#include "vpDangerBands.h"
#include "vpInputError.h"
#include "vpLivePoseSource.h"
#include "vpPngFile.h"
#include "vpTrackingSession.h"
#include "vtkScalpelKeyboardMouseStyle.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"
#include "vtkDistancePlotRepresentation.h"
#include "vtkScalpelDangerRepresentation.h"
#include "vtkVesselModelsRepresentation.h"
#include "vtkVesselProximityOverlays.h"

#include <vtkAnnotatedCubeActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

vtkStandardNewMacro(vtkVesselProximityView);

/// What the view shows of each frame: the overlays, then the camera that follows the scalpel.
/// The session's first output, ahead of those added with AddOutput (a screenshot taken by one of
/// them shows the frame), and unchanged when the overlays are swapped.
class vtkVesselProximityView::Display : public vp::FrameOutput
{
public:
  explicit Display(vtkVesselProximityView* view)
    : View(view)
  {
  }
  void OnLevelChange(const vp::DangerLevelChange& change) override { this->View->Overlays->OnLevelChange(change); }
  void OnMarginChange(const vp::MarginLevelChange& change) override { this->View->Overlays->OnMarginChange(change); }
  void OnFrame(const vp::TrackedFrame& frame) override
  {
    this->View->TimeS = frame.TimeS;
    this->View->TrackingLost = false;
    this->View->Overlays->OnFrame(frame);
    ++this->View->FramesShown;
    this->View->FollowScalpel();
  }
  void OnLost(const vp::TrackedPose& pose) override
  {
    this->View->TrackingLost = true;
    this->View->Overlays->OnLost(pose);
  }

private:
  vtkVesselProximityView* View;
};

vtkVesselProximityView::vtkVesselProximityView()
  : Overlays(vtkSmartPointer<vtkVesselProximityOverlays>::New())
  , Renderer(vtkSmartPointer<vtkRenderer>::New())
  , Window(vtkSmartPointer<vtkRenderWindow>::New())
  , Interactor(vtkSmartPointer<vtkRenderWindowInteractor>::New())
  , Style(vtkSmartPointer<vtkScalpelKeyboardMouseStyle>::New())
  , Shown(std::make_unique<Display>(this))
{
  // Slicer's 3D view background: a vertical gradient, here darker so the white and gray levels
  // of the scalpel stand out.
  this->Renderer->GradientBackgroundOn();
  // The readout's text colours are chosen against these (vp::ReadoutTextColour).
  this->Renderer->SetBackground(vp::ToFraction(vp::ViewBackgroundBottom).data());
  this->Renderer->SetBackground2(vp::ToFraction(vp::ViewBackgroundTop).data());
  this->Window->AddRenderer(this->Renderer);
  // The orientation marker: directions as the world (LPS) has them, +x left, +y posterior, +z
  // superior; drawn last, over the scene, in the lower left corner.
  this->MarkerRenderer = vtkSmartPointer<vtkRenderer>::New();
  this->MarkerRenderer->SetViewport(0.0, 0.0, 0.14, 0.22);
  this->MarkerRenderer->SetLayer(1);
  this->MarkerRenderer->InteractiveOff();
  vtkNew<vtkAnnotatedCubeActor> cube;
  cube->SetXPlusFaceText("L");
  cube->SetXMinusFaceText("R");
  cube->SetYPlusFaceText("P");
  cube->SetYMinusFaceText("A");
  cube->SetZPlusFaceText("S");
  cube->SetZMinusFaceText("I");
  cube->SetFaceTextScale(0.65);
  cube->GetCubeProperty()->SetColor(0.30, 0.32, 0.40);
  cube->GetTextEdgesProperty()->SetColor(0.9, 0.9, 0.9);
  cube->GetTextEdgesProperty()->SetLineWidth(1.5);
  for (vtkProperty* face : { cube->GetXPlusFaceProperty(), cube->GetXMinusFaceProperty(), cube->GetYPlusFaceProperty(),
         cube->GetYMinusFaceProperty(), cube->GetZPlusFaceProperty(), cube->GetZMinusFaceProperty() })
  {
    face->SetColor(1.0, 1.0, 1.0);
  }
  this->MarkerRenderer->AddActor(cube);
  this->Window->SetNumberOfLayers(2);
  this->Window->AddRenderer(this->MarkerRenderer);
  this->Window->SetWindowName("VesselProximity");
  // Smooth edges without multisampling, whose result differs between GL drivers.
  this->Window->SetMultiSamples(0);
  this->Interactor->SetRenderWindow(this->Window);
  this->Style->SetView(this);
  this->Interactor->SetInteractorStyle(this->Style);
  this->Overlays->SetRenderer(this->Renderer);
  this->SetSizePx(1280, 800);
}

vtkVesselProximityView::~vtkVesselProximityView()
{
  this->Style->SetView(nullptr);
}

void vtkVesselProximityView::SetLogic(vtkVesselProximityLogic* logic)
{
  this->Overlays->SetLogic(logic);
  this->ResetCamera();
  this->Modified();
}

void vtkVesselProximityView::SetOverlays(vtkVesselProximityOverlays* overlays)
{
  if (!overlays || overlays == this->Overlays)
  {
    return;
  }
  vtkVesselProximityLogic* logic = this->Overlays->GetLogic();
  this->Overlays->SetRenderer(nullptr);
  this->Overlays = overlays;
  this->Overlays->SetRenderer(this->Renderer);
  if (logic)
  {
    this->Overlays->SetLogic(logic);
  }
  const int* size = this->Window->GetSize();
  this->SetSizePx(size[0], size[1]); // the plot's size follows the window's
  this->Modified();
}

vtkVesselProximityLogic* vtkVesselProximityView::GetLogic() const
{
  return this->Overlays->GetLogic();
}

void vtkVesselProximityView::SetLiverSurface(vtkPolyData* liver)
{
  this->Overlays->SetLiverSurface(liver);
}

void vtkVesselProximityView::SetSizePx(int width, int height)
{
  this->Window->SetSize(width, height);
  // The plot takes about a third of the width and of the height, so it never hides the scene.
  this->Overlays->GetPlot()->SetSizePx(std::max(380, width * 9 / 25), std::max(180, height * 3 / 10));
}

void vtkVesselProximityView::SetOffScreen(bool offScreen)
{
  this->Window->SetOffScreenRendering(offScreen);
}

void vtkVesselProximityView::SetPoses(const std::vector<vp::TrackedPose>& poses)
{
  this->Poses = poses;
  this->CurrentPose = -1;
}

vp::TrackingSession* vtkVesselProximityView::SessionFor(double timeS)
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  if (!logic || !logic->GetScalpel())
  {
    return nullptr;
  }
  // Poses must move forward in time; a jump back (replay restarted) starts a new session, as
  // does a logic of its own.
  const bool jumpedBack = this->Session && this->Session->GetNumberOfFrames() > 0 && timeS <= logic->GetLastFrame().TimeS;
  if (!this->Session || this->Session->GetLogic() != logic || jumpedBack)
  {
    this->StartSession();
  }
  return this->Session.get();
}

void vtkVesselProximityView::StartSession()
{
  // A session starts safe, its plot empty.
  vtkVesselProximityLogic* logic = this->GetLogic();
  const bool hadFrames = logic->GetTrackingLogic()->GetNumberOfFrames() > 0;
  this->Session = std::make_unique<vp::TrackingSession>(logic);
  this->Session->AddOutput(this->Shown.get());
  for (vp::FrameOutput* output : this->Outputs)
  {
    this->Session->AddOutput(output);
  }
  if (hadFrames)
  {
    this->Overlays->GetPlot()->ClearHistory();
    this->Overlays->GetScalpel()->SetDangerLevel(vp::DangerLevel::Safe);
  }
}

void vtkVesselProximityView::Process(const std::array<double, 16>& modelToWorld, double timeS)
{
  if (vp::TrackingSession* session = this->SessionFor(timeS))
  {
    vp::TrackedPose pose;
    pose.TimeS = timeS;
    pose.ModelToWorld = modelToWorld;
    session->Process(pose);
  }
}

void vtkVesselProximityView::AddOutput(vp::FrameOutput* output)
{
  this->Outputs.push_back(output);
  if (this->Session)
  {
    this->Session->AddOutput(output);
  }
}

void vtkVesselProximityView::ShowPose(int i)
{
  if (i < 0 || i >= static_cast<int>(this->Poses.size()))
  {
    return;
  }
  this->CurrentPose = i;
  if (!this->Poses[i].Lost)
  {
    this->Process(this->Poses[i].ModelToWorld, this->Poses[i].TimeS);
  }
  else if (vp::TrackingSession* session = this->SessionFor(this->Poses[i].TimeS))
  {
    // A pose the tracker lost is no pose: the overlays say so and show no distance as current.
    session->ProcessLost(this->Poses[i]);
  }
}

bool vtkVesselProximityView::ReplayTo(int last)
{
  last = std::min(last, static_cast<int>(this->Poses.size()) - 1);
  if (last < 0 || !this->GetLogic() || !this->GetLogic()->GetScalpel())
  {
    return true;
  }
  this->StartSession();
  this->CurrentPose = last;
  const std::vector<vp::TrackedPose> shown(this->Poses.begin(), this->Poses.begin() + last + 1);
  vp::PoseListSource poses(shown, "the view's poses"); // it holds the list, not a copy
  return this->Session->Run(poses);
}

void vtkVesselProximityView::SetScalpelPose(const std::array<double, 16>& modelToWorld)
{
  this->Process(modelToWorld, this->TimeS + 0.02);
}

void vtkVesselProximityView::MoveScalpelBy(const double delta[3])
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  if (!logic || !logic->GetScalpel())
  {
    return;
  }
  std::array<double, 16> m = logic->GetScalpel()->GetModelToWorld();
  m[3] += delta[0];
  m[7] += delta[1];
  m[11] += delta[2];
  this->SetScalpelPose(m);
}

void vtkVesselProximityView::AdvanceScalpelBy(double mm)
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  if (!logic || !logic->GetScalpel())
  {
    return;
  }
  double axis[3];
  logic->GetScalpel()->GetAxisInWorld(axis);
  const double delta[3] = { mm * axis[0], mm * axis[1], mm * axis[2] };
  this->MoveScalpelBy(delta);
}

void vtkVesselProximityView::SetPlaying(bool playing)
{
  if (playing == this->Playing || this->Poses.empty())
  {
    return;
  }
  this->Playing = playing;
  if (!this->Interactor->GetInitialized())
  {
    return; // scripted or off-screen: nothing ticks
  }
  if (playing)
  {
    // The poses' own rate, at most 50 per second: replay at the speed it was recorded.
    const double dt = this->Poses.size() > 1 ? (this->Poses.back().TimeS - this->Poses.front().TimeS) / (this->Poses.size() - 1) : 0.02;
    this->TimerId = this->Interactor->CreateRepeatingTimer(static_cast<unsigned long>(std::max(20.0, 1000.0 * dt)));
  }
  else if (this->TimerId >= 0)
  {
    this->Interactor->DestroyTimer(this->TimerId);
    this->TimerId = -1;
  }
}

bool vtkVesselProximityView::FollowLive(double waitMs, bool& ended)
{
  ended = false;
  bool changed = false;
  vp::TrackedPose pose;
  // Everything waiting is taken (the source keeps only the newest pose): one render for it all.
  for (double wait = waitMs;; wait = 0.0)
  {
    const vp::LivePoseSource::Step step = this->Live->Poll(pose, wait);
    if (step == vp::LivePoseSource::Step::Pose)
    {
      this->Process(pose.ModelToWorld, pose.TimeS);
      changed = true;
    }
    else if (step == vp::LivePoseSource::Step::Lost)
    {
      // The loss is dated when it was declared: the overlays count it from the last frame.
      if (vp::TrackingSession* session = this->SessionFor(pose.TimeS))
      {
        session->ProcessLost(pose);
      }
      changed = true;
    }
    else
    {
      ended = step == vp::LivePoseSource::Step::Ended;
      return changed;
    }
  }
}

void vtkVesselProximityView::FollowLiveFor(double seconds)
{
  if (!this->Live)
  {
    return;
  }
  for (const double until = vp::NowMs() + 1000.0 * seconds; vp::NowMs() < until;)
  {
    bool ended = false;
    if (this->FollowLive(10.0, ended))
    {
      this->Render();
    }
    if (ended)
    {
      return;
    }
  }
}

void vtkVesselProximityView::OnTimer()
{
  if (this->Live)
  {
    bool ended = false;
    if (this->FollowLive(0.0, ended))
    {
      this->Render();
    }
    if (ended)
    {
      this->Interactor->TerminateApp(); // Ctrl-C or the duration: the session is over
    }
    return;
  }
  if (!this->Playing)
  {
    return;
  }
  if (this->CurrentPose + 1 >= static_cast<int>(this->Poses.size()))
  {
    this->SetPlaying(false);
    return;
  }
  this->ShowPose(this->CurrentPose + 1);
  this->Render();
}

const char* vtkVesselProximityView::CameraPresetName(CameraPreset preset)
{
  switch (preset)
  {
    case CameraPreset::Anterior:
      return "anterior";
    case CameraPreset::Lateral:
      return "lateral";
    case CameraPreset::Superior:
      return "superior";
    case CameraPreset::Tool:
      return "tool";
    case CameraPreset::Follow:
      return "follow";
    case CameraPreset::Clear:
      return "clear";
  }
  return "anterior";
}

bool vtkVesselProximityView::ParseCameraPreset(const std::string& name, CameraPreset& preset)
{
  for (CameraPreset p : { CameraPreset::Anterior, CameraPreset::Lateral, CameraPreset::Superior, CameraPreset::Tool,
         CameraPreset::Follow, CameraPreset::Clear })
  {
    if (name == CameraPresetName(p))
    {
      preset = p;
      return true;
    }
  }
  return false;
}

void vtkVesselProximityView::SetCameraPreset(CameraPreset preset)
{
  this->Preset = preset;
  this->ClearCameraFrame = -1;
  this->ResetCamera();
  this->Modified();
}

void vtkVesselProximityView::ResetCamera()
{
  // Frame the vessels only: the scalpel's handle is long and would push them into a corner.
  double bounds[6];
  vtkVesselProximityLogic* logic = this->GetLogic();
  const bool haveVessels = logic && logic->GetVesselBounds(bounds);
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  // LPS: anterior is -y, the patient's right -x, superior +z; from anterior the patient's right
  // appears on the left, as in Slicer.
  camera->SetFocalPoint(0, 0, 0);
  switch (this->Preset)
  {
    case CameraPreset::Lateral:
      camera->SetPosition(-1, 0, 0);
      camera->SetViewUp(0, 0, 1);
      break;
    case CameraPreset::Superior:
      camera->SetPosition(0, 0, 1);
      camera->SetViewUp(0, -1, 0);
      break;
    default:
      camera->SetPosition(0, -1, 0);
      camera->SetViewUp(0, 0, 1);
  }
  if (haveVessels)
  {
    this->Renderer->ResetCamera(bounds);
  }
  else
  {
    this->Renderer->ResetCamera();
  }
  this->FollowScalpel();
}

void vtkVesselProximityView::FollowScalpel()
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  if ((this->Preset != CameraPreset::Tool && this->Preset != CameraPreset::Follow) || !logic || !logic->GetScalpel())
  {
    return;
  }
  double tip[3], axis[3];
  logic->GetScalpel()->GetTipInWorld(tip);
  logic->GetScalpel()->GetAxisInWorld(axis);
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  const double distance = camera->GetDistance();
  if (this->Preset == CameraPreset::Follow)
  {
    // Same direction and distance, the tip in the middle.
    double direction[3];
    camera->GetDirectionOfProjection(direction);
    camera->SetFocalPoint(tip);
    camera->SetPosition(tip[0] - distance * direction[0], tip[1] - distance * direction[1], tip[2] - distance * direction[2]);
    return;
  }
  // Beside the tool, on its anterior side (its superior side when it points anterior or
  // posterior), the tip in the middle and the shaft pointing down the screen: looking down the axis
  // the handpiece would hide everything (the tutorial's end-on dark disc).
  double side[3] = { 0, -1, 0 };
  double along = side[0] * axis[0] + side[1] * axis[1] + side[2] * axis[2];
  if (std::abs(along) > 0.9)
  {
    side[1] = 0;
    side[2] = 1;
    along = axis[2];
  }
  for (int k = 0; k < 3; ++k)
  {
    side[k] -= along * axis[k];
  }
  const double norm = std::sqrt(side[0] * side[0] + side[1] * side[1] + side[2] * side[2]);
  const double back = std::clamp(distance, 40.0, 150.0);
  camera->SetFocalPoint(tip);
  camera->SetPosition(tip[0] + back * side[0] / norm, tip[1] + back * side[1] / norm, tip[2] + back * side[2] / norm);
  camera->SetViewUp(-axis[0], -axis[1], -axis[2]);
  camera->OrthogonalizeViewUp();
  this->Renderer->ResetCameraClippingRange();
}

void vtkVesselProximityView::PlaceClearCamera()
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  if (!logic || !logic->GetScalpel() || logic->GetTrackingLogic()->GetNumberOfFrames() == 0)
  {
    return;
  }
  const vp::TrackedFrame& frame = logic->GetLastFrame();
  if (this->FramesShown == this->ClearCameraFrame)
  {
    return;
  }
  this->ClearCameraFrame = this->FramesShown;
  const int nearest = frame.Proximity.NearestIndex();
  const vp::ClassProximity* near = nearest >= 0 ? &frame.Proximity.Classes[static_cast<std::size_t>(nearest)] : nullptr;
  vp::PlaceClearViewCamera(this->Renderer, frame.TipMm, frame.AxisWorld, near ? near->ClosestPoint : nullptr,
    near && near->Inside.value_or(false) ? near->DistanceMm : 0.0);
}

void vtkVesselProximityView::SeeThroughVesselsHidingTheTip()
{
  vtkVesselProximityLogic* logic = this->GetLogic();
  vtkVesselModelsRepresentation* vessels = this->Overlays->GetVessels();
  const bool fixed = this->Preset == CameraPreset::Anterior || this->Preset == CameraPreset::Lateral ||
    this->Preset == CameraPreset::Superior;
  const bool tipShown = fixed && logic && logic->GetScalpel() && logic->GetTrackingLogic()->GetNumberOfFrames() > 0 &&
    !this->TrackingLost;
  vessels->SetSeeThrough(
    tipShown && this->Occlusion.Hides(this->Renderer, vessels->GetVesselActors(), logic->GetLastFrame().TipMm));
}

void vtkVesselProximityView::Render()
{
  if (this->Preset == CameraPreset::Clear)
  {
    this->PlaceClearCamera();
  }
  this->SeeThroughVesselsHidingTheTip();
  // The marker turns with the main camera: same direction and up, at a fixed distance.
  vtkCamera* main = this->Renderer->GetActiveCamera();
  vtkCamera* marker = this->MarkerRenderer->GetActiveCamera();
  double direction[3];
  main->GetDirectionOfProjection(direction);
  marker->SetFocalPoint(0, 0, 0);
  marker->SetPosition(-4 * direction[0], -4 * direction[1], -4 * direction[2]);
  marker->SetViewUp(main->GetViewUp());
  marker->SetViewAngle(30);
  this->MarkerRenderer->ResetCameraClippingRange();
  this->Window->Render();
}

std::string vtkVesselProximityView::SaveScreenshot(const std::string& requested)
{
  std::string file = requested;
  if (file.empty())
  {
    char number[16];
    std::snprintf(number, sizeof(number), "%03d", ++this->ScreenshotCount);
    file = this->ScreenshotPrefix + number + ".png";
  }
  this->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(this->Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  this->LastScreenshot = grab->GetOutput();
  vp::WritePngAtomically(this->LastScreenshot, file);
  return file;
}

void vtkVesselProximityView::Start()
{
  vtkNew<vtkCallbackCommand> onTimer;
  onTimer->SetClientData(this);
  onTimer->SetCallback([](vtkObject*, unsigned long, void* self, void*) { static_cast<vtkVesselProximityView*>(self)->OnTimer(); });
  this->Interactor->Initialize();
  this->Interactor->AddObserver(vtkCommand::TimerEvent, onTimer);
  if (this->Live)
  {
    this->TimerId = this->Interactor->CreateRepeatingTimer(10); // a pose is shown within 10 ms of its arrival
  }
  this->Render();
  this->Interactor->Start();
}

void vtkVesselProximityView::PressKeys(const std::vector<std::string>& keys)
{
  for (const std::string& key : keys)
  {
    this->Style->HandleKey(key, false);
  }
}

const char* vtkVesselProximityView::KeyHelp()
{
  return vtkScalpelKeyboardMouseStyle::KeyHelp();
}

void vtkVesselProximityView::GetTipInWorld(double tipMm[3]) const
{
  this->GetLogic()->GetScalpel()->GetTipInWorld(tipMm);
}

void vtkVesselProximityView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Poses: " << this->Poses.size() << " (current " << this->CurrentPose << ")\n";
  os << indent << "Playing: " << this->Playing << "\n" << indent << "ScreenshotPrefix: " << this->ScreenshotPrefix << "\n";
}

vtkVesselProximityOverlays* vtkVesselProximityView::GetOverlays() const
{
  return this->Overlays;
}

vtkRenderer* vtkVesselProximityView::GetRenderer() const
{
  return this->Renderer;
}

vtkRenderWindow* vtkVesselProximityView::GetRenderWindow() const
{
  return this->Window;
}
