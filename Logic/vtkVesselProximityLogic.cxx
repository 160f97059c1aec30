#include "vtkVesselProximityLogic.h"

#include "vtkExactVesselDistance.h"
#include "vtkScalpelModel.h"
#include "vtkFclSurfaceDistance.h"
#include "vtkZBufferSurfaceDistance.h"
#include "vtkZBufferVesselDistance.h"
#include "vtkScalpelPenetration.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <stdexcept>

vtkStandardNewMacro(vtkVesselProximityLogic);

vtkVesselProximityLogic::vtkVesselProximityLogic()
  : Engine(vtkSmartPointer<vtkExactVesselDistance>::New())
  , Tracking(vtkSmartPointer<vtkScalpelTrackingLogic>::New())
{
}

vtkVesselProximityLogic::~vtkVesselProximityLogic() = default;

void vtkVesselProximityLogic::AddVessel(const std::string& className, vtkPolyData* surface)
{
  for (auto& vessel : this->Vessels)
  {
    if (vessel.first == className)
    {
      vessel.second = surface;
      this->SceneChanged = true;
      this->Modified();
      return;
    }
  }
  this->Vessels.emplace_back(className, surface);
  this->SceneChanged = true;
  this->Modified();
}

void vtkVesselProximityLogic::RemoveAllVessels()
{
  this->Vessels.clear();
  this->SceneChanged = true;
  this->Modified();
}

void vtkVesselProximityLogic::SetScalpel(vtkScalpelModel* scalpel)
{
  if (scalpel != this->Tracking->GetScalpel())
  {
    this->Tracking->SetScalpel(scalpel);
    this->SceneChanged = true; // the surface-distance tree is built from its model
    this->Modified();
  }
}

vtkScalpelModel* vtkVesselProximityLogic::GetScalpel() const
{
  return this->Tracking->GetScalpel();
}

void vtkVesselProximityLogic::SetDistanceEngine(vtkVesselDistanceEngine* engine)
{
  if (!engine)
  {
    throw std::invalid_argument("vtkVesselProximityLogic: the distance engine cannot be null");
  }
  if (engine != this->Engine)
  {
    this->Engine = engine;
    this->SceneChanged = true;
    this->Modified();
  }
}

void vtkVesselProximityLogic::SetDangerThresholds(const vp::DangerThresholds& thresholds)
{
  this->Tracking->SetDangerThresholds(thresholds);
  this->Modified();
}

const vp::DangerThresholds& vtkVesselProximityLogic::GetDangerThresholds() const
{
  return this->Tracking->GetDangerThresholds();
}

void vtkVesselProximityLogic::Build()
{
  if (!this->SceneChanged)
  {
    return;
  }
  if (this->Vessels.empty())
  {
    throw std::logic_error("vtkVesselProximityLogic: add at least one vessel before building");
  }
  // The exact engine serves the comparison and the whole surface; a second one, beside an
  // approximate engine, is built only when one of them is wanted.
  const bool surface = this->WantsSurfaceDistance();
  this->Exact = vtkExactVesselDistance::SafeDownCast(this->Engine);
  if (!this->Exact && (this->CompareWithExact || surface))
  {
    this->Exact = vtkSmartPointer<vtkExactVesselDistance>::New();
    this->Exact->SetRangeMm(this->Engine->GetRangeMm());
  }
  std::vector<vtkVesselDistanceEngine*> engines{ this->Engine };
  if (this->Exact && this->Exact != this->Engine)
  {
    engines.push_back(this->Exact);
  }
  for (vtkVesselDistanceEngine* engine : engines)
  {
    engine->RemoveAllVessels();
    for (const auto& vessel : this->Vessels)
    {
      engine->AddVessel(vessel.first, vessel.second);
    }
    engine->Build();
  }
  this->Tracking->SetDistanceEngine(this->Engine);
  if (surface)
  {
    // The z-buffer answers the whole instrument from its own layers (a distance field of them,
    // within a stated bound) when they stay put; otherwise FCL answers it exactly.
    auto* layers = vtkZBufferVesselDistance::SafeDownCast(this->Engine);
    if (layers && layers->GetBoxMode() == vtkZBufferVesselDistance::FixedAroundVessels)
    {
      auto zbuffer = vtkSmartPointer<vtkZBufferSurfaceDistance>::New();
      zbuffer->SetZBuffer(layers);
      zbuffer->SetToolSurface(this->GetScalpel()->GetModel());
      zbuffer->Build(); // the samples and the field, once: not in the first frame's time
      this->Surface = zbuffer;
    }
    else
    {
      auto fcl = vtkSmartPointer<vtkFclSurfaceDistance>::New();
      fcl->SetVesselDistance(this->Exact);
      fcl->SetToolSurface(this->GetScalpel()->GetModel());
      fcl->Build(); // the trees, once: not in the first frame's time
      this->Surface = fcl;
    }
    this->Tracking->SetSurfaceDistance(this->Surface);
    this->Penetration = vtkSmartPointer<vtkScalpelPenetration>::New();
    this->Penetration->SetVesselDistance(this->Exact);
    this->Penetration->SetZBufferSurface(vtkZBufferSurfaceDistance::SafeDownCast(this->Surface));
    this->Penetration->SetToolSurface(this->GetScalpel()->GetModel());
    this->Penetration->Build();
    this->Tracking->SetPenetration(this->Penetration);
  }
  else
  {
    this->Surface = nullptr;
    this->Penetration = nullptr;
    this->Tracking->SetSurfaceDistance(nullptr);
    this->Tracking->SetPenetration(nullptr);
  }
  this->SceneChanged = false;
  ++this->NumberOfBuilds;
}

const vp::TrackedFrame& vtkVesselProximityLogic::ProcessPose(const vp::TrackedPose& pose)
{
  if (!this->Tracking->GetScalpel())
  {
    throw std::logic_error("vtkVesselProximityLogic: set the scalpel before processing poses");
  }
  // The surface tree and the exact engine follow their switches: turning one on or off is a
  // scene change.
  if ((this->Surface != nullptr) != this->WantsSurfaceDistance() || (this->CompareWithExact && !this->Exact))
  {
    this->SceneChanged = true;
  }
  this->Build();
  const vp::TrackedFrame& frame = this->Tracking->ProcessPose(pose);
  if (this->CompareWithExact && this->Exact != this->Engine)
  {
    this->Exact->ComputeProximity(frame.TipMm, frame.AxisWorld, this->LastExact);
  }
  return frame;
}

bool vtkVesselProximityLogic::WantsSurfaceDistance() const
{
  vtkScalpelModel* scalpel = this->Tracking->GetScalpel();
  return this->ComputeSurfaceDistance && scalpel && scalpel->GetModel();
}

bool vtkVesselProximityLogic::GetVesselBounds(double bounds[6]) const
{
  for (std::size_t i = 0; i < this->Vessels.size(); ++i)
  {
    double b[6];
    this->Vessels[i].second->GetBounds(b);
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = i == 0 ? b[2 * a] : std::min(bounds[2 * a], b[2 * a]);
      bounds[2 * a + 1] = i == 0 ? b[2 * a + 1] : std::max(bounds[2 * a + 1], b[2 * a + 1]);
    }
  }
  return !this->Vessels.empty();
}

const vp::TrackedFrame& vtkVesselProximityLogic::GetLastFrame() const
{
  return this->Tracking->GetLastFrame();
}

const vp::ProximityResult& vtkVesselProximityLogic::GetLastExactProximity() const
{
  return this->Exact == this->Engine || !this->CompareWithExact ? this->Tracking->GetLastFrame().Proximity : this->LastExact;
}

void vtkVesselProximityLogic::ResetTracking()
{
  this->Tracking->Reset();
}

void vtkVesselProximityLogic::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Vessels:";
  for (const auto& vessel : this->Vessels)
  {
    os << " " << vessel.first;
  }
  os << "\n" << indent << "DistanceEngine: " << this->Engine->GetMethodName() << "\n";
  os << indent << "CompareWithExact: " << this->CompareWithExact << "\n";
  os << indent << "ComputeSurfaceDistance: " << this->ComputeSurfaceDistance << "\n";
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
  os << indent << "TrackingLogic:\n";
  this->Tracking->PrintSelf(os, indent.GetNextIndent());
}
