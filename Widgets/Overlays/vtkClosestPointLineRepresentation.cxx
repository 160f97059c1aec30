#include "vtkClosestPointLineRepresentation.h"

#include "vpPlotValues.h"

#include <vtkActor.h>
#include <vtkCoordinate.h>
#include <vtkLineSource.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>

vtkStandardNewMacro(vtkClosestPointLineRepresentation);

vtkClosestPointLineRepresentation::vtkClosestPointLineRepresentation()
  : Line(vtkSmartPointer<vtkLineSource>::New())
  , LineActor(vtkSmartPointer<vtkActor>::New())
  , Label(vtkSmartPointer<vtkTextActor>::New())
  , LabelAnchor(vtkSmartPointer<vtkCoordinate>::New())
  , EndsActor(vtkSmartPointer<vtkActor>::New())
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(this->Line->GetOutputPort());
  this->LineActor->SetMapper(mapper);
  this->LineActor->GetProperty()->SetLineWidth(3.0);
  this->LineActor->GetProperty()->SetLighting(false);
  // The line's two points drawn as points too: a point keeps its size in pixels at any zoom.
  vtkNew<vtkPolyDataMapper> ends;
  ends->SetInputConnection(this->Line->GetOutputPort());
  this->EndsActor->SetMapper(ends);
  this->EndsActor->GetProperty()->SetRepresentationToPoints();
  this->EndsActor->GetProperty()->SetPointSize(9.0);
  this->EndsActor->GetProperty()->SetLighting(false);
  vtkTextProperty* text = this->Label->GetTextProperty();
  text->SetFontSize(18);
  text->SetBold(true);
  text->SetShadow(true);
  text->SetColor(1.0, 1.0, 1.0); // white on a dark backing: readable over any vessel's colour
  text->SetBackgroundColor(0.08, 0.09, 0.12);
  text->SetBackgroundOpacity(0.7);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  // A few pixels to the right of the line's middle, wherever that is on the screen.
  this->LabelAnchor->SetCoordinateSystemToWorld();
  this->Label->GetPositionCoordinate()->SetReferenceCoordinate(this->LabelAnchor);
  this->Label->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  this->Label->GetPositionCoordinate()->SetValue(12, 0);
  this->SetColour(1.0, 1.0, 1.0);
  this->Hide();
}

vtkClosestPointLineRepresentation::~vtkClosestPointLineRepresentation() = default;

void vtkClosestPointLineRepresentation::SetLine(
  const double tip[3], const double point[3], double distanceMm, bool inside, const std::string& className, double boundMm)
{
  this->Line->SetPoint1(tip[0], tip[1], tip[2]);
  this->Line->SetPoint2(point[0], point[1], point[2]);
  this->LabelAnchor->SetValue(0.5 * (tip[0] + point[0]), 0.5 * (tip[1] + point[1]), 0.5 * (tip[2] + point[2]));
  std::string name = className;
  std::replace(name.begin(), name.end(), '_', ' ');
  const std::string text = (name.empty() ? "" : name + " ") + vp::DistanceText(distanceMm, boundMm) + " mm" + (inside ? " inside" : "");
  if (this->GetLabelText() != text)
  {
    this->Label->SetInput(text.c_str());
  }
  this->LineActor->SetVisibility(true);
  this->EndsActor->SetVisibility(true);
  this->Label->SetVisibility(true);
}

void vtkClosestPointLineRepresentation::Hide()
{
  this->LineActor->SetVisibility(false);
  this->EndsActor->SetVisibility(false);
  this->Label->SetVisibility(false);
}

bool vtkClosestPointLineRepresentation::IsShown() const
{
  return this->LineActor->GetVisibility() != 0;
}

void vtkClosestPointLineRepresentation::SetColour(double r, double g, double b)
{
  this->LineActor->GetProperty()->SetColor(r, g, b);
  this->EndsActor->GetProperty()->SetColor(r, g, b);
  this->Modified();
}

std::string vtkClosestPointLineRepresentation::GetLabelText() const
{
  const char* text = this->Label->GetInput();
  return text ? text : "";
}

void vtkClosestPointLineRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  renderer->AddActor(this->LineActor);
  renderer->AddActor(this->EndsActor);
  renderer->AddActor2D(this->Label);
}

void vtkClosestPointLineRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  renderer->RemoveActor(this->LineActor);
  renderer->RemoveActor(this->EndsActor);
  renderer->RemoveActor2D(this->Label);
}

void vtkClosestPointLineRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shown: " << this->IsShown() << "\n" << indent << "Label: " << this->GetLabelText() << "\n";
}
