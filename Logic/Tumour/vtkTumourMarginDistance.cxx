#include "vtkTumourMarginDistance.h"

#include "vpInputError.h"
#include "vtkExactVesselDistance.h"
#include "vtkFclSurfaceDistance.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <cmath>
#include <limits>
#include <stdexcept>

vtkStandardNewMacro(vtkTumourMarginDistance);

vtkTumourMarginDistance::vtkTumourMarginDistance() = default;
vtkTumourMarginDistance::~vtkTumourMarginDistance() = default;

void vtkTumourMarginDistance::AddTumour(const std::string& id, vtkPolyData* surface)
{
  if (!surface)
  {
    throw std::invalid_argument("vtkTumourMarginDistance: a tumour's surface cannot be null");
  }
  if (id.empty())
  {
    throw vp::ParameterError("Tumours", "a tumour needs an id");
  }
  for (const auto& tumour : this->Tumours)
  {
    if (tumour.first == id)
    {
      throw vp::ParameterError("Tumours", "tumour '" + vp::Printable(id) + "' is given twice");
    }
  }
  this->Tumours.emplace_back(id, surface);
  this->Built = false;
  this->Modified();
}

void vtkTumourMarginDistance::RemoveAllTumours()
{
  this->Tumours.clear();
  this->Built = false;
  this->Modified();
}

void vtkTumourMarginDistance::SetToolSurface(vtkPolyData* model)
{
  if (this->ToolSurface != model)
  {
    this->ToolSurface = model;
    this->Built = false;
    this->Modified();
  }
}

void vtkTumourMarginDistance::SetInstrumentRangeMm(double rangeMm)
{
  if (!(rangeMm > 0.0) || !std::isfinite(rangeMm))
  {
    throw vp::ParameterError("InstrumentRangeMm", "must be a positive number of millimetres");
  }
  if (rangeMm != this->InstrumentRangeMm)
  {
    this->InstrumentRangeMm = rangeMm; // a search radius: nothing to build again
    this->Modified();
  }
}

void vtkTumourMarginDistance::Build()
{
  if (this->Built)
  {
    return;
  }
  this->Exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  // The tip's queries take no range (always answered); the instrument's is InstrumentRangeMm.
  this->Exact->SetRangeMm(1e6);
  for (const auto& tumour : this->Tumours)
  {
    this->Exact->AddVessel(tumour.first, tumour.second);
  }
  this->Instrument = nullptr;
  this->LastSurface.clear();
  if (!this->Tumours.empty())
  {
    this->Exact->Build();
    if (this->ToolSurface)
    {
      this->Instrument = vtkSmartPointer<vtkFclSurfaceDistance>::New();
      this->Instrument->SetVesselDistance(this->Exact);
      this->Instrument->SetToolSurface(this->ToolSurface);
      this->Instrument->Build();
    }
  }
  this->Built = true;
}

void vtkTumourMarginDistance::ComputeMargin(
  const double tip[3], const std::array<double, 16>& modelToWorld, vp::TumourMargin& out, const vp::TumourMargin* previous)
{
  this->Build();
  out = vp::TumourMargin();
  out.Tumours.resize(this->Tumours.size());
  const double unlimited = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < this->Tumours.size(); ++t)
  {
    vp::TumourProximity& p = out.Tumours[t];
    p.Id = this->Tumours[t].first;
    const int c = static_cast<int>(t);
    std::optional<bool> inside;
    const double distanceMm = this->Exact->NearestDistanceWithin(c, tip, unlimited, &inside, p.ClosestPoint);
    if (!inside)
    {
      // Not closed: the rays' vote, the more concerning side when they disagree.
      inside = this->Exact->VoteInside(c, tip, distanceMm, p.InsideUncertain);
    }
    p.SignedMm = *inside ? -distanceMm : distanceMm;
  }
  if (this->Instrument)
  {
    const bool follows = previous && this->LastSurface.size() == this->Tumours.size();
    std::vector<vp::SurfaceProximity> surface;
    this->Instrument->SetRangeMm(this->InstrumentRangeMm);
    this->Instrument->ComputeSurfaceProximity(modelToWorld, surface, follows ? &this->LastSurface : nullptr);
    for (std::size_t t = 0; t < surface.size() && t < out.Tumours.size(); ++t)
    {
      out.Tumours[t].SurfaceKnown = surface[t].InRange;
      out.Tumours[t].SurfaceMm = surface[t].DistanceMm;
    }
    this->LastSurface = std::move(surface);
  }
}

void vtkTumourMarginDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tumours: " << this->Tumours.size() << "\n";
  for (const auto& tumour : this->Tumours)
  {
    os << indent.GetNextIndent() << tumour.first << ": " << tumour.second->GetNumberOfCells() << " cells\n";
  }
  os << indent << "InstrumentRangeMm: " << this->InstrumentRangeMm << "\n";
  os << indent << "ToolSurface: " << (this->ToolSurface ? "set" : "(none: the tip alone)") << "\n";
  os << indent << "Built: " << (this->Built ? "yes" : "no") << "\n";
}
