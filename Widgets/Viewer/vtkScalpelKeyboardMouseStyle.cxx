#include "vtkScalpelKeyboardMouseStyle.h"

#include "vpScalpelControls.h"

#include <vtkCamera.h>
#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <iostream>

vtkStandardNewMacro(vtkScalpelKeyboardMouseStyle);

vtkScalpelKeyboardMouseStyle::vtkScalpelKeyboardMouseStyle() = default;
vtkScalpelKeyboardMouseStyle::~vtkScalpelKeyboardMouseStyle() = default;

void vtkScalpelKeyboardMouseStyle::CameraAxes(double right[3], double up[3], double toward[3]) const
{
  vtkCamera* camera = this->View->GetRenderer()->GetActiveCamera();
  camera->GetViewUp(up);
  double forward[3];
  camera->GetDirectionOfProjection(forward);
  vtkMath::Cross(forward, up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, forward, up); // view up need not be orthogonal to the projection
  vtkMath::Normalize(up);
  for (int a = 0; a < 3; ++a)
  {
    toward[a] = -forward[a];
  }
}

bool vtkScalpelKeyboardMouseStyle::HandleKey(const std::string& key, bool shift)
{
  if (!this->View)
  {
    return false;
  }
  const double step = this->StepMm * (shift ? 5.0 : 1.0);
  double right[3], up[3], toward[3];
  this->CameraAxes(right, up, toward);
  auto move = [&](const double direction[3], double sign) {
    const double delta[3] = { sign * step * direction[0], sign * step * direction[1], sign * step * direction[2] };
    this->View->MoveScalpelBy(delta);
  };
  if (key == "Left" || key == "Right")
  {
    move(right, key == "Right" ? 1 : -1);
  }
  else if (key == "Up" || key == "Down")
  {
    move(up, key == "Up" ? 1 : -1);
  }
  else if (key == "Prior" || key == "Next")
  {
    move(toward, key == "Prior" ? 1 : -1);
  }
  else if (key == "i" || key == "o")
  {
    this->View->AdvanceScalpelBy(key == "i" ? step : -step);
  }
  else if (key == "space")
  {
    this->View->SetPlaying(!this->View->GetPlaying());
  }
  else if (key == "n" || key == "b")
  {
    if (this->View->GetNumberOfPoses() > 0)
    {
      const int n = this->View->GetNumberOfPoses();
      this->View->ShowPose(((this->View->GetCurrentPose() + (key == "n" ? 1 : -1)) % n + n) % n);
    }
  }
  else if (key == "x")
  {
    std::cout << "saved " << this->View->SaveScreenshot(std::string()) << std::endl;
  }
  else if (key == "c")
  {
    this->View->ResetCamera();
  }
  else if (key == "h")
  {
    std::cout << KeyHelp();
  }
  else
  {
    return false;
  }
  this->View->Render();
  return true;
}

void vtkScalpelKeyboardMouseStyle::OnKeyPress()
{
  vtkRenderWindowInteractor* rwi = this->Interactor;
  if (!this->HandleKey(rwi->GetKeySym() ? rwi->GetKeySym() : "", rwi->GetShiftKey() != 0))
  {
    this->Superclass::OnKeyPress();
  }
}

void vtkScalpelKeyboardMouseStyle::OnChar()
{
  // Our letters were handled on key press; VTK's must not act on them a second time ('c' is not
  // VTK's, but 'p' would pick and draw a box, and 'i' 'o' 'n' 'b' 'x' 'h' are ours).
  const char c = this->Interactor->GetKeyCode();
  if (c == 'i' || c == 'o' || c == 'n' || c == 'b' || c == 'x' || c == 'c' || c == 'h' || c == ' ' || c == 'p')
  {
    return;
  }
  this->Superclass::OnChar();
}

void vtkScalpelKeyboardMouseStyle::OnLeftButtonDown()
{
  if (this->View && this->Interactor->GetControlKey())
  {
    this->Dragging = true;
    this->Interactor->GetEventPosition(this->LastPositionPx);
    return;
  }
  this->Superclass::OnLeftButtonDown();
}

void vtkScalpelKeyboardMouseStyle::OnLeftButtonUp()
{
  if (this->Dragging)
  {
    this->Dragging = false;
    return;
  }
  this->Superclass::OnLeftButtonUp();
}

void vtkScalpelKeyboardMouseStyle::OnMouseMove()
{
  if (!this->Dragging)
  {
    this->Superclass::OnMouseMove();
    return;
  }
  // Pixels to millimetres on the plane through the tip parallel to the screen: the tip follows
  // the mouse exactly.
  vtkRenderer* renderer = this->View->GetRenderer();
  double tip[3];
  this->View->GetTipInWorld(tip);
  double display[3];
  vtkInteractorObserver::ComputeWorldToDisplay(renderer, tip[0], tip[1], tip[2], display);
  int now[2];
  this->Interactor->GetEventPosition(now);
  double from[4], to[4];
  vtkInteractorObserver::ComputeDisplayToWorld(renderer, this->LastPositionPx[0], this->LastPositionPx[1], display[2], from);
  vtkInteractorObserver::ComputeDisplayToWorld(renderer, now[0], now[1], display[2], to);
  const double delta[3] = { to[0] - from[0], to[1] - from[1], to[2] - from[2] };
  this->LastPositionPx[0] = now[0];
  this->LastPositionPx[1] = now[1];
  this->View->MoveScalpelBy(delta);
  this->View->Render();
}

const char* vtkScalpelKeyboardMouseStyle::KeyHelp()
{
  return "keys: arrows move the scalpel 1 mm in the view plane (Shift: 5 mm), PageUp/PageDown towards/away\n"
         "      from you, i/o advance/retract along its axis; Ctrl+left drag moves it with the mouse;\n"
         "      space plays/pauses the poses, n/b step; x saves a screenshot; c frames the vessels;\n"
         "      r resets the camera, w/s wireframe/surface, q quits; h shows this\n";
}

void vtkScalpelKeyboardMouseStyle::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StepMm: " << this->StepMm << "\n";
}
