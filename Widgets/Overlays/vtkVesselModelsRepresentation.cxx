#include "vtkVesselModelsRepresentation.h"

#include "vpDangerBands.h"

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <algorithm>

vtkStandardNewMacro(vtkVesselModelsRepresentation);

vtkVesselModelsRepresentation::vtkVesselModelsRepresentation() = default;
vtkVesselModelsRepresentation::~vtkVesselModelsRepresentation() = default;

void vtkVesselModelsRepresentation::Style(Entry& entry, const std::array<double, 3>& rgb) const
{
  vtkProperty* property = entry.Actor->GetProperty();
  property->SetColor(rgb[0], rgb[1], rgb[2]);
  property->SetSpecular(0.3);
  property->SetSpecularPower(20);
  const bool liver = entry.ClassName == "liver";
  property->SetOpacity(liver ? this->LiverOpacity : this->SeeThrough ? this->SeeThroughOpacity : 1.0);
  // A translucent liver must not hide what is behind it in the depth buffer either.
  entry.Actor->SetPickable(!liver);
}

std::vector<vtkActor*> vtkVesselModelsRepresentation::GetVesselActors() const
{
  std::vector<vtkActor*> actors;
  for (const Entry& entry : this->Entries)
  {
    if (entry.ClassName != "liver")
    {
      actors.push_back(entry.Actor);
    }
  }
  return actors;
}

void vtkVesselModelsRepresentation::SetSeeThrough(bool seeThrough)
{
  if (seeThrough == this->SeeThrough)
  {
    return;
  }
  this->SeeThrough = seeThrough;
  for (const Entry& entry : this->Entries)
  {
    if (entry.ClassName != "liver")
    {
      entry.Actor->GetProperty()->SetOpacity(seeThrough ? this->SeeThroughOpacity : 1.0);
    }
  }
  this->Modified();
}

vtkActor* vtkVesselModelsRepresentation::FindActor(const std::vector<Entry>& entries, const std::string& name)
{
  const auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return e.ClassName == name; });
  return it == entries.end() ? nullptr : it->Actor.Get();
}

vtkVesselModelsRepresentation::Entry& vtkVesselModelsRepresentation::AddEntry(std::vector<Entry>& entries, const std::string& name)
{
  Entry entry{ name, vtkSmartPointer<vtkActor>::New() };
  vtkNew<vtkPolyDataMapper> mapper;
  entry.Actor->SetMapper(mapper);
  for (vtkRenderer* renderer : this->Renderers)
  {
    renderer->AddActor(entry.Actor);
  }
  entries.push_back(entry);
  return entries.back();
}

void vtkVesselModelsRepresentation::SetVessel(const std::string& className, vtkPolyData* surface)
{
  vtkActor* actor = FindActor(this->Entries, className);
  if (!actor)
  {
    const int index = static_cast<int>(this->Entries.size());
    Entry& entry = this->AddEntry(this->Entries, className);
    this->Style(entry, vp::ToFraction(vp::ClassDisplayColour(className, index)));
    actor = entry.Actor;
  }
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(surface);
  // Normals come with the surface (the model builder writes consistent outward triangles);
  // without point normals the shading is flat, which reads fine on smoothed vessels.
  this->Modified();
}

void vtkVesselModelsRepresentation::SetTumour(const std::string& id, vtkPolyData* surface)
{
  vtkActor* actor = FindActor(this->Tumours, id);
  if (!actor)
  {
    actor = this->AddEntry(this->Tumours, id).Actor;
    const std::array<double, 3> c = vp::ToFraction(vp::TumourDisplayColour);
    actor->GetProperty()->SetColor(c[0], c[1], c[2]);
    actor->GetProperty()->SetSpecular(0.3);
    actor->GetProperty()->SetSpecularPower(20);
    actor->GetProperty()->SetOpacity(this->TumourOpacity);
  }
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(surface);
  this->Modified();
}

vtkActor* vtkVesselModelsRepresentation::GetTumourActor(const std::string& id) const
{
  return FindActor(this->Tumours, id);
}

void vtkVesselModelsRepresentation::SetClassColour(const std::string& className, const std::array<double, 3>& rgb)
{
  for (Entry& e : this->Entries)
  {
    if (e.ClassName == className)
    {
      this->Style(e, rgb);
      this->Modified();
      return;
    }
  }
}

std::array<double, 3> vtkVesselModelsRepresentation::GetClassColour(const std::string& className) const
{
  for (const Entry& e : this->Entries)
  {
    if (e.ClassName == className)
    {
      const double* c = e.Actor->GetProperty()->GetColor();
      return { c[0], c[1], c[2] };
    }
  }
  return vp::ToFraction(vp::ClassDisplayColour(className, static_cast<int>(this->Entries.size())));
}

void vtkVesselModelsRepresentation::AddToRenderer(vtkRenderer* renderer)
{
  this->Renderers.push_back(renderer);
  for (const std::vector<Entry>* entries : { &this->Entries, &this->Tumours })
  {
    for (const Entry& e : *entries)
    {
      renderer->AddActor(e.Actor);
    }
  }
}

void vtkVesselModelsRepresentation::RemoveFromRenderer(vtkRenderer* renderer)
{
  for (const std::vector<Entry>* entries : { &this->Entries, &this->Tumours })
  {
    for (const Entry& e : *entries)
    {
      renderer->RemoveActor(e.Actor);
    }
  }
  this->Renderers.erase(std::remove(this->Renderers.begin(), this->Renderers.end(), renderer), this->Renderers.end());
}

vtkActor* vtkVesselModelsRepresentation::GetActor(const std::string& className) const
{
  return FindActor(this->Entries, className);
}

void vtkVesselModelsRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Classes:";
  for (const Entry& e : this->Entries)
  {
    os << " " << e.ClassName;
  }
  os << "\n" << indent << "Tumours:";
  for (const Entry& e : this->Tumours)
  {
    os << " " << e.ClassName;
  }
  os << "\n" << indent << "LiverOpacity: " << this->LiverOpacity << "\n";
  os << indent << "TumourOpacity: " << this->TumourOpacity << "\n";
  os << indent << "SeeThrough: " << this->SeeThrough << " (opacity " << this->SeeThroughOpacity << ")\n";
}
