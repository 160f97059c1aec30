#include "vtkClosestPointLineRepresentation.h"

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

#include <cstdio>

vtkStandardNewMacro(vtkClosestPointLineRepresentation);

vtkClosestPointLineRepresentation::vtkClosestPointLineRepresentation()
  : Line(vtkSmartPointer<vtkLineSource>::New())
  , LineActor(vtkSmartPointer<vtkActor>::New())
  , Label(vtkSmartPointer<vtkTextActor>::New())
  , LabelAnchor(vtkSmartPointer<vtkCoordinate>::New())
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(this->Line->GetOutputPort());
  this->LineActor->SetMapper(mapper);
  this->LineActor->GetProperty()->SetLineWidth(3.0);
  this->LineActor->GetProperty()->SetLighting(false);
  vtkTextProperty* text = this->Label->GetTextProperty();
  text->SetFontSize(18);
  text->SetBold(true);
  text->SetShadow(true);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  // A few pixels to the right of the line's middle, wherever that is on the screen.
  this->LabelAnchor->SetCoordinateSystemToWorld();
  this->Label->GetPositionCoordinate()->SetReferenceCoordinate(this->LabelAnchor);
  this->Label->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  this->Label->GetPositionCoordinate()->SetValue(12, 0);
  this->SetColour(1.0, 0.85, 0.1);
  this->Hide();
}

vtkClosestPointLineRepresentation::~vtkClosestPointLineRepresentation() = default;

void vtkClosestPointLineRepresentation::SetLine(const double tip[3], const double point[3], double distanceMm, bool inside)
{
  this->Line->SetPoint1(tip[0], tip[1], tip[2]);
  this->Line->SetPoint2(point[0], point[1], point[2]);
  this->LabelAnchor->SetValue(0.5 * (tip[0] + point[0]), 0.5 * (tip[1] + point[1]), 0.5 * (tip[2] + point[2]));
  char text[64];
  std::snprintf(text, sizeof(text), inside ? "%.1f mm inside" : "%.1f mm", distanceMm);
  if (this->GetLabelText() != text)
  {
    this->Label->SetInput(text);
  }
  this->LineActor->SetVisibility(true);
  this->Label->SetVisibility(true);
}

void vtkClosestPointLineRepresentation::Hide()
{
  this->LineActor->SetVisibility(false);
  this->Label->SetVisibility(false);
}

bool vtkClosestPointLineRepresentation::IsShown() const
{
  return this->LineActor->GetVisibility() != 0;
}

void vtkClosestPointLineRepresentation::SetColour(double r, double g, double b)
{
  this->LineActor->GetProperty()->SetColor(r, g, b);
  this->Label->GetTextProperty()->SetColor(r, g, b);
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
  renderer->AddActor2D(this->Label);
}

void vtkClosestPointLineRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  renderer->RemoveActor(this->LineActor);
  renderer->RemoveActor2D(this->Label);
}

void vtkClosestPointLineRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shown: " << this->IsShown() << "\n" << indent << "Label: " << this->GetLabelText() << "\n";
}
