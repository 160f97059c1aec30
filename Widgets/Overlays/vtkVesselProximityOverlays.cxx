#include "vtkVesselProximityOverlays.h"

#include "vpFrameHeadline.h"

#include "vpDangerBands.h"
#include "vtkClosestPointLineRepresentation.h"
#include "vtkDistancePlotRepresentation.h"
#include "vtkProximityReadoutRepresentation.h"
#include "vtkScalpelDangerRepresentation.h"
#include "vtkScalpelModel.h"
#include "vtkVesselModelsRepresentation.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityParameters.h"

#include <vtkObjectFactory.h>
#include <vtkRenderer.h>

#include <algorithm>

vtkStandardNewMacro(vtkVesselProximityOverlays);

vtkVesselProximityOverlays::vtkVesselProximityOverlays()
  : Vessels(vtkSmartPointer<vtkVesselModelsRepresentation>::New())
  , Scalpel(vtkSmartPointer<vtkScalpelDangerRepresentation>::New())
  , ClosestLine(vtkSmartPointer<vtkClosestPointLineRepresentation>::New())
  , Readout(vtkSmartPointer<vtkProximityReadoutRepresentation>::New())
  , Plot(vtkSmartPointer<vtkDistancePlotRepresentation>::New())
{
}

vtkVesselProximityOverlays::~vtkVesselProximityOverlays() = default;

void vtkVesselProximityOverlays::SetLogic(vtkVesselProximityLogic* logic)
{
  if (logic == this->Logic)
  {
    return;
  }
  this->Logic = logic;
  this->UpdateFromScene();
  this->Modified();
}

void vtkVesselProximityOverlays::UpdateFromScene()
{
  if (!this->Logic)
  {
    return;
  }
  std::vector<std::string> names;
  std::vector<std::array<double, 3>> colours;
  for (int i = 0; i < this->Logic->GetNumberOfVessels(); ++i)
  {
    names.push_back(this->Logic->GetVesselClassName(i));
    this->Vessels->SetVessel(names.back(), this->Logic->GetVesselSurface(i));
    colours.push_back(this->Vessels->GetClassColour(names.back()));
  }
  this->Readout->SetClasses(names, colours);
  vtkVesselProximityParameters* parameters = this->Logic->GetParameters();
  for (int t = 0; t < parameters->GetNumberOfTumours(); ++t)
  {
    this->Vessels->SetTumour(parameters->GetTumourId(t), parameters->GetTumourSurface(t));
  }
  this->Readout->SetEngine(this->Logic->GetDistanceEngine() ? this->Logic->GetDistanceEngine()->GetMethodName() : "");
  this->Plot->SetClasses(names);
  this->Plot->SetDangerThresholds(this->Logic->GetDangerThresholds());
  if (vtkScalpelModel* scalpel = this->Logic->GetScalpel())
  {
    this->Scalpel->SetScalpelSurface(scalpel->GetModel());
    this->Scalpel->SetModelToWorld(scalpel->GetModelToWorld());
  }
  // Joining a session already running: take its current level once.
  if (this->Logic->GetTrackingLogic()->GetNumberOfFrames() > 0)
  {
    this->Scalpel->SetDangerLevel(this->Logic->GetLastFrame().Level);
  }
}

void vtkVesselProximityOverlays::SetLiverSurface(vtkPolyData* liver)
{
  this->Vessels->SetVessel("liver", liver);
}

void vtkVesselProximityOverlays::SetRenderer(vtkRenderer* renderer)
{
  if (renderer == this->Renderer)
  {
    return;
  }
  if (this->Renderer)
  {
    this->Vessels->RemoveFromRenderer(this->Renderer);
    this->Scalpel->RemoveFromRenderer(this->Renderer);
    this->ClosestLine->RemoveFromRenderer(this->Renderer);
    this->Readout->RemoveFromRenderer(this->Renderer);
    this->Plot->RemoveFromRenderer(this->Renderer);
  }
  this->Renderer = renderer;
  if (renderer)
  {
    this->Vessels->AddToRenderer(renderer);
    this->Scalpel->AddToRenderer(renderer);
    this->ClosestLine->AddToRenderer(renderer);
    this->Readout->AddToRenderer(renderer);
    this->Plot->AddToRenderer(renderer);
  }
  this->Modified();
}

void vtkVesselProximityOverlays::OnLevelChange(const vp::DangerLevelChange& change)
{
  this->Scalpel->SetDangerLevel(change.To);
}

void vtkVesselProximityOverlays::OnLost(const vp::TrackedPose& pose)
{
  this->ShowTrackingLost(1000.0 * std::max(0.0, pose.TimeS - this->LastFrameTimeS));
}

void vtkVesselProximityOverlays::ShowFrame(const vp::TrackedFrame& frame)
{
  this->LastFrameTimeS = frame.TimeS;
  if (this->Logic && this->Logic->GetScalpel())
  {
    this->Scalpel->SetModelToWorld(this->Logic->GetScalpel()->GetModelToWorld());
  }
  const int nearest = frame.Proximity.NearestIndex();
  if (nearest >= 0)
  {
    const vp::ClassProximity& p = frame.Proximity.Classes[nearest];
    this->ClosestLine->SetLine(frame.TipMm, p.ClosestPoint, p.DistanceMm, p.Inside && *p.Inside, p.ClassName,
      frame.Proximity.ErrorBoundMm);
    if (p.ClassName != this->LineClass) // the line wears the nearest class's readout colour
    {
      this->LineClass = p.ClassName;
      const std::array<double, 3> c = vp::ToFraction(vp::ReadoutTextColour(vp::ToRgb(this->Vessels->GetClassColour(p.ClassName))));
      this->ClosestLine->SetColour(c[0], c[1], c[2]);
    }
  }
  else
  {
    this->ClosestLine->Hide();
  }
  // The exact answer beside an approximate one when the logic computed both for this pose.
  this->Readout->ShowFrame(frame, vp::FrameHeadline(frame), frame.Exact ? &*frame.Exact : nullptr);
  this->Readout->ShowMargin(frame.Tumour ? &*frame.Tumour : nullptr,
    this->Logic ? this->Logic->GetTrackingLogic()->GetMarginSettings().MarginMm : vp::MarginSettings().MarginMm);
  this->Readout->ShowFrameTime(frame.FrameMs, frame.OverBudget,
    this->Logic ? this->Logic->GetTrackingLogic()->GetFrameBudgetMs() : 0.0);
  this->Plot->AddFrame(frame);
}

void vtkVesselProximityOverlays::ShowTrackingLost(double sinceMs)
{
  this->ClosestLine->Hide();
  this->Readout->ShowTrackingLost(sinceMs);
}

void vtkVesselProximityOverlays::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Logic: " << (this->Logic ? "set" : "(none)") << "\n";
  os << indent << "Renderer: " << (this->Renderer ? "set" : "(none)") << "\n";
  this->Scalpel->PrintSelf(os, indent.GetNextIndent());
  this->Readout->PrintSelf(os, indent.GetNextIndent());
}

vtkVesselProximityLogic* vtkVesselProximityOverlays::GetLogic() const
{
  return this->Logic;
}

vtkVesselModelsRepresentation* vtkVesselProximityOverlays::GetVessels() const
{
  return this->Vessels;
}

vtkScalpelDangerRepresentation* vtkVesselProximityOverlays::GetScalpel() const
{
  return this->Scalpel;
}

vtkClosestPointLineRepresentation* vtkVesselProximityOverlays::GetClosestPointLine() const
{
  return this->ClosestLine;
}

vtkProximityReadoutRepresentation* vtkVesselProximityOverlays::GetReadout() const
{
  return this->Readout;
}

vtkDistancePlotRepresentation* vtkVesselProximityOverlays::GetPlot() const
{
  return this->Plot;
}
