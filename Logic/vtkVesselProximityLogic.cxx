#include "vtkVesselProximityLogic.h"

#include "vpDefaultScalpel.h"
#include "vpDistanceEngineFactory.h"
#include "vpInstrumentDistanceFactory.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshReader.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelPenetration.h"
#include "vtkTumourMarginDistance.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselProximityParameters.h"

#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <stdexcept>

vtkStandardNewMacro(vtkVesselProximityLogic);

vtkVesselProximityLogic::vtkVesselProximityLogic()
  : Tracking(vtkSmartPointer<vtkScalpelTrackingLogic>::New())
{
  this->SetParameters(vtkSmartPointer<vtkVesselProximityParameters>::New());
}

vtkVesselProximityLogic::~vtkVesselProximityLogic()
{
  this->Parameters->RemoveObserver(this->ParametersObserver);
  this->Tracking->ReadSettingsFrom(nullptr); // whoever still holds the tracking logic reads its own
}

vp::OpenedScene vtkVesselProximityLogic::OpenScene(const vp::SceneRequest& request)
{
  vp::OpenedScene scene;
  vp::CheckVesselClassNames(request.Vessels);
  vtkSmartPointer<vtkVesselDistanceEngine> engine = vp::MakeDistanceEngine(request.Engine, &scene.EngineNote);
  this->StartStage("reading the vessels");
  scene.Vessels = vp::LoadVesselMeshes(request.Vessels);
  if (request.RepairVessels)
  {
    this->StartStage("repairing the vessels");
    vp::RepairVesselMeshes(scene.Vessels);
  }
  if (!request.Tumours.empty())
  {
    this->StartStage("reading the tumours");
    scene.Tumours = vp::LoadTumourMeshes(request.Tumours);
  }
  this->StartStage("reading the scalpel");
  if (!request.LiverFile.empty())
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(request.LiverFile);
    reader->Read();
    scene.Liver = reader->GetOutput();
  }
  vtkSmartPointer<vtkScalpelModel> scalpel = request.Scalpel ? request.Scalpel
    : request.ScalpelFile.empty()                            ? vp::MakeDefaultScalpel(request.Tip)
                                                             : vp::LoadScalpel(request.ScalpelFile, request.Tip);

  vtkVesselProximityParameters* p = this->Parameters;
  p->RemoveAllVessels();
  for (const vp::NamedMesh& vessel : scene.Vessels)
  {
    p->SetVessel(vessel.ClassName, vessel.Mesh);
  }
  p->RemoveAllTumours();
  for (const vp::NamedMesh& tumour : scene.Tumours)
  {
    p->SetTumour(tumour.ClassName, tumour.Mesh);
  }
  p->SetScalpel(scalpel);
  p->SetDistanceEngine(engine);
  p->SetCompareWithExact(request.CompareWithExact && !engine->IsExact());
  p->SetComputeSurfaceDistance(request.ComputeSurfaceDistance);
  p->SetInstrumentMethod(request.Instrument);
  p->SetInstrumentRangeMm(request.InstrumentRangeMm);
  p->SetComputePenetration(request.ComputePenetration);
  p->SetPenetrationQueryBudget(request.PenetrationQueryBudget);
  p->SetDangerThresholds(request.Tracking.Thresholds);
  p->SetHysteresisMm(request.Tracking.HysteresisMm);
  p->SetFrameBudgetMs(request.Tracking.FrameBudgetMs);
  p->SetHapticSettings(request.Tracking.Haptic);
  p->SetMarginSettings(request.Tracking.Margin);
  this->Build();
  this->Tracking->ValidateSettings();
  this->ResetTracking();
  scene.PenetrationUnknown = this->Penetration && !this->Penetration->IsToolClosed();
  return scene;
}

void vtkVesselProximityLogic::StartStage(const std::string& stage)
{
  this->InvokeEvent(StageStartedEvent, const_cast<char*>(stage.c_str()));
}

void vtkVesselProximityLogic::SetParameters(vtkVesselProximityParameters* parameters)
{
  if (!parameters)
  {
    throw std::invalid_argument("vtkVesselProximityLogic: the parameter set cannot be null");
  }
  if (parameters == this->Parameters)
  {
    return;
  }
  if (this->Parameters)
  {
    this->Parameters->RemoveObserver(this->ParametersObserver);
  }
  this->Parameters = parameters;
  this->ParametersObserver =
    parameters->AddObserver(vtkCommand::ModifiedEvent, this, &vtkVesselProximityLogic::ApplyParameters);
  this->AppliedSceneMTime = 0;
  this->ApplyParameters();
}

void vtkVesselProximityLogic::ApplyParameters()
{
  vtkVesselProximityParameters* p = this->Parameters;
  if (p->GetSceneMTime() > this->AppliedSceneMTime)
  {
    this->AppliedSceneMTime = p->GetSceneMTime();
    this->Tracking->SetScalpel(p->GetScalpel());
    this->SceneChanged = true;
  }
  // The tracking settings are the parameter set's alone, read each frame where they lie.
  this->Tracking->ReadSettingsFrom(&p->GetTrackingSettings());
  this->Modified();
}

void vtkVesselProximityLogic::AddVessel(const std::string& className, vtkPolyData* surface)
{
  this->Parameters->SetVessel(className, surface);
}

void vtkVesselProximityLogic::RemoveAllVessels()
{
  this->Parameters->RemoveAllVessels();
}

int vtkVesselProximityLogic::GetNumberOfVessels() const
{
  return this->Parameters->GetNumberOfVessels();
}

const std::string& vtkVesselProximityLogic::GetVesselClassName(int i) const
{
  return this->Parameters->GetVesselClassName(i);
}

vtkPolyData* vtkVesselProximityLogic::GetVesselSurface(int i) const
{
  return this->Parameters->GetVesselSurface(i);
}

void vtkVesselProximityLogic::SetScalpel(vtkScalpelModel* scalpel)
{
  this->Parameters->SetScalpel(scalpel);
}

vtkScalpelModel* vtkVesselProximityLogic::GetScalpel() const
{
  return this->Tracking->GetScalpel();
}

void vtkVesselProximityLogic::SetDistanceEngine(vtkVesselDistanceEngine* engine)
{
  this->Parameters->SetDistanceEngine(engine);
}

vtkVesselDistanceEngine* vtkVesselProximityLogic::GetDistanceEngine() const
{
  return this->Parameters->GetDistanceEngine();
}

void vtkVesselProximityLogic::SetCompareWithExact(bool compare)
{
  this->Parameters->SetCompareWithExact(compare);
}

bool vtkVesselProximityLogic::GetCompareWithExact() const
{
  return this->Parameters->GetCompareWithExact();
}

void vtkVesselProximityLogic::SetComputeSurfaceDistance(bool compute)
{
  this->Parameters->SetComputeSurfaceDistance(compute);
}

bool vtkVesselProximityLogic::GetComputeSurfaceDistance() const
{
  return this->Parameters->GetComputeSurfaceDistance();
}

void vtkVesselProximityLogic::SetDangerThresholds(const vp::DangerThresholds& thresholds)
{
  this->Parameters->SetDangerThresholds(thresholds);
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
  vtkVesselDistanceEngine* engine = this->GetDistanceEngine();
  const bool compareWithExact = this->GetCompareWithExact();
  if (this->GetNumberOfVessels() == 0)
  {
    throw std::logic_error("vtkVesselProximityLogic: add at least one vessel before building");
  }
  // The exact engine serves the comparison and the whole surface; a second one, beside an
  // approximate engine, is built only when one of them is wanted.
  const bool surface = this->WantsSurfaceDistance();
  this->Exact = vtkExactVesselDistance::ServingBeside(engine, compareWithExact || surface);
  std::vector<vtkVesselDistanceEngine*> engines{ engine };
  if (this->Exact && this->Exact != engine)
  {
    engines.push_back(this->Exact);
  }
  for (vtkVesselDistanceEngine* e : engines)
  {
    this->StartStage(std::string("building the ") + e->GetMethodName() + " engine");
    e->RemoveAllVessels();
    for (int i = 0; i < this->GetNumberOfVessels(); ++i)
    {
      e->AddVessel(this->GetVesselClassName(i), this->GetVesselSurface(i));
    }
    e->Build();
  }
  engine->PrepareForTracking(); // once: not in the first frames' time
  this->Tracking->SetDistanceEngine(engine);
  this->Tracking->SetReferenceEngine(compareWithExact ? this->Exact.GetPointer() : nullptr);
  if (surface)
  {
    this->StartStage("sampling the instrument");
    this->BuildInstrument(engine);
  }
  else
  {
    this->Surface = nullptr;
    this->Penetration = nullptr;
  }
  this->Tracking->SetSurfaceDistance(this->Surface);
  this->Tracking->SetPenetration(this->Penetration);
  this->BuildTumourMargin(surface);
  this->SceneChanged = false;
  ++this->NumberOfBuilds;
}

void vtkVesselProximityLogic::BuildInstrument(vtkVesselDistanceEngine* engine)
{
  vtkVesselProximityParameters* p = this->Parameters;
  vtkPolyData* tool = this->GetScalpel()->GetModel();
  this->Surface = vp::MakeInstrumentDistance(p->GetInstrumentMethod(), engine, this->Exact, tool, p->GetInstrumentRangeMm());
  this->Penetration = nullptr;
  if (p->GetComputePenetration())
  {
    this->Penetration = vtkSmartPointer<vtkScalpelPenetration>::New();
    this->Penetration->SetVesselDistance(this->Exact);
    this->Penetration->SetInstrumentDistance(this->Surface);
    this->Penetration->SetToolSurface(tool);
    this->Penetration->SetQueryBudget(p->GetPenetrationQueryBudget());
    this->Penetration->Build();
  }
}

void vtkVesselProximityLogic::BuildTumourMargin(bool surface)
{
  vtkVesselProximityParameters* p = this->Parameters;
  this->TumourMargin = nullptr;
  if (p->GetNumberOfTumours() > 0)
  {
    this->StartStage("building the tumours' trees");
    this->TumourMargin = vtkSmartPointer<vtkTumourMarginDistance>::New();
    for (int t = 0; t < p->GetNumberOfTumours(); ++t)
    {
      this->TumourMargin->AddTumour(p->GetTumourId(t), p->GetTumourSurface(t));
    }
    // The whole instrument against the tumours when it is measured against the vessels.
    this->TumourMargin->SetToolSurface(surface ? this->GetScalpel()->GetModel() : nullptr);
    this->TumourMargin->Build(); // once: not in the first frame's time
  }
  this->Tracking->SetTumourMargin(this->TumourMargin);
}

const vp::TrackedFrame& vtkVesselProximityLogic::ProcessPose(const vp::TrackedPose& pose)
{
  if (!this->Tracking->GetScalpel())
  {
    throw std::logic_error("vtkVesselProximityLogic: set the scalpel before processing poses");
  }
  // The switches are scene changes of the parameter set; a scalpel that was given its model after
  // it was set is not, yet the surface tree needs that model.
  if ((this->Surface != nullptr) != this->WantsSurfaceDistance())
  {
    this->SceneChanged = true;
  }
  this->Build();
  return this->Tracking->ProcessPose(pose);
}

bool vtkVesselProximityLogic::WantsSurfaceDistance() const
{
  vtkScalpelModel* scalpel = this->Tracking->GetScalpel();
  return this->GetComputeSurfaceDistance() && scalpel && scalpel->GetModel();
}

bool vtkVesselProximityLogic::GetVesselBounds(double bounds[6]) const
{
  for (int i = 0; i < this->GetNumberOfVessels(); ++i)
  {
    double b[6];
    this->GetVesselSurface(i)->GetBounds(b);
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = i == 0 ? b[2 * a] : std::min(bounds[2 * a], b[2 * a]);
      bounds[2 * a + 1] = i == 0 ? b[2 * a + 1] : std::max(bounds[2 * a + 1], b[2 * a + 1]);
    }
  }
  return this->GetNumberOfVessels() > 0;
}

const vp::TrackedFrame& vtkVesselProximityLogic::GetLastFrame() const
{
  return this->Tracking->GetLastFrame();
}

void vtkVesselProximityLogic::ResetTracking()
{
  this->Tracking->Reset();
}

void vtkVesselProximityLogic::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
  os << indent << "Parameters:\n";
  this->Parameters->PrintSelf(os, indent.GetNextIndent());
  os << indent << "TrackingLogic:\n";
  this->Tracking->PrintSelf(os, indent.GetNextIndent());
}
