#include "vtkScalpelDangerRepresentation.h"

#include <vtkActor.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

vtkStandardNewMacro(vtkScalpelDangerRepresentation);

vtkScalpelDangerRepresentation::vtkScalpelDangerRepresentation()
  : Actor(vtkSmartPointer<vtkActor>::New())
  , Pose(vtkSmartPointer<vtkMatrix4x4>::New())
{
  for (int l = 0; l < vp::NumberOfDangerLevels; ++l)
  {
    this->Colours[l] = vp::DangerLevelColour(static_cast<vp::DangerLevel>(l));
  }
  vtkNew<vtkPolyDataMapper> mapper;
  this->Actor->SetMapper(mapper);
  this->Actor->SetUserMatrix(this->Pose);
  this->Actor->GetProperty()->SetSpecular(0.4);
  this->Actor->GetProperty()->SetSpecularPower(30);
  this->ApplyColour();
  this->ColourChanges = 0;
}

vtkScalpelDangerRepresentation::~vtkScalpelDangerRepresentation() = default;

void vtkScalpelDangerRepresentation::SetScalpelSurface(vtkPolyData* surface)
{
  vtkPolyDataMapper::SafeDownCast(this->Actor->GetMapper())->SetInputData(surface);
  this->Modified();
}

void vtkScalpelDangerRepresentation::SetModelToWorld(const std::array<double, 16>& m)
{
  this->Pose->DeepCopy(m.data());
}

void vtkScalpelDangerRepresentation::ApplyColour()
{
  const auto& c = this->Colours[static_cast<int>(this->Level)];
  this->Actor->GetProperty()->SetColor(c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
  ++this->ColourChanges;
}

void vtkScalpelDangerRepresentation::SetDangerLevel(vp::DangerLevel level)
{
  if (level != this->Level)
  {
    this->Level = level;
    this->ApplyColour();
    this->Modified();
  }
}

void vtkScalpelDangerRepresentation::SetLevelColour(vp::DangerLevel level, const std::array<unsigned char, 3>& rgb)
{
  this->Colours[static_cast<int>(level)] = rgb;
  if (level == this->Level)
  {
    this->ApplyColour();
  }
  this->Modified();
}

std::array<unsigned char, 3> vtkScalpelDangerRepresentation::GetLevelColour(vp::DangerLevel level) const
{
  return this->Colours[static_cast<int>(level)];
}

void vtkScalpelDangerRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  renderer->AddActor(this->Actor);
}

void vtkScalpelDangerRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  renderer->RemoveActor(this->Actor);
}

void vtkScalpelDangerRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DangerLevel: " << vp::DangerLevelName(this->Level) << "\n";
  for (int l = 0; l < vp::NumberOfDangerLevels; ++l)
  {
    const auto& c = this->Colours[l];
    os << indent << "Colour " << vp::DangerLevelName(static_cast<vp::DangerLevel>(l)) << ": " << int(c[0]) << " "
       << int(c[1]) << " " << int(c[2]) << "\n";
  }
  os << indent << "NumberOfColourChanges: " << this->ColourChanges << "\n";
}
