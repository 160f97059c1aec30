#include "vtkVesselDistanceEngine.h"

#include "vpInputError.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

vtkVesselDistanceEngine::vtkVesselDistanceEngine() = default;
vtkVesselDistanceEngine::~vtkVesselDistanceEngine() = default;

void vtkVesselDistanceEngine::AddVessel(const std::string& className, vtkPolyData* mesh)
{
  if (className.empty())
  {
    throw vp::InputError("(vessel)", "a vessel class needs a name");
  }
  for (auto& entry : this->Meshes)
  {
    if (entry.first == className)
    {
      entry.second = mesh;
      this->Built = false;
      this->Modified();
      return;
    }
  }
  this->Meshes.emplace_back(className, mesh);
  this->Built = false;
  this->Modified();
}

void vtkVesselDistanceEngine::RemoveAllVessels()
{
  this->Meshes.clear();
  this->Surfaces.clear();
  this->Built = false;
  this->Modified();
}

void vtkVesselDistanceEngine::SetRangeMm(double range)
{
  if (!(range > 0.0) || !std::isfinite(range))
  {
    throw vp::ParameterError("RangeMm", "must be a positive number of millimetres");
  }
  if (range != this->RangeMm)
  {
    this->RangeMm = range;
    this->Modified();
  }
}

void vtkVesselDistanceEngine::Build()
{
  if (this->Built)
  {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  this->Surfaces.clear();
  for (const auto& entry : this->Meshes)
  {
    this->Surfaces.push_back(std::make_shared<vp::VesselSurface>(entry.first, entry.second));
  }
  this->BuildInternal();
  this->Built = true;
  this->BuildTimeMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void vtkVesselDistanceEngine::EnsureBuilt() const
{
  if (!this->Built)
  {
    // Lazy build keeps the first query correct; concurrent callers must Build() beforehand.
    const_cast<vtkVesselDistanceEngine*>(this)->Build();
  }
}

void vtkVesselDistanceEngine::ComputeProximityBatch(
  const Points& tips, const Points* axes, std::vector<vp::ProximityResult>& results) const
{
  this->EnsureBuilt(); // before any thread starts
  const std::size_t count = tips.size();
  results.resize(count);
  auto answer = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      this->ComputeProximity(tips[i].data(), axes ? (*axes)[i].data() : nullptr, results[i]);
    }
  };
  // A thread costs tens of microseconds to start: only batches worth it are split.
  const std::size_t threads = count < 64 ? 1 : std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  std::vector<std::thread> workers;
  const std::size_t share = (count + threads - 1) / threads;
  for (std::size_t t = 1; t < threads; ++t)
  {
    workers.emplace_back(answer, std::min(count, t * share), std::min(count, (t + 1) * share));
  }
  answer(0, std::min(count, share));
  for (std::thread& w : workers)
  {
    w.join();
  }
}

void vtkVesselDistanceEngine::BeginResult(const double tip[3], vp::ProximityResult& result) const
{
  this->EnsureBuilt();
  result.Tip[0] = tip[0];
  result.Tip[1] = tip[1];
  result.Tip[2] = tip[2];
  result.ErrorBoundMm = 0.0;
  result.Classes.assign(this->Surfaces.size(), vp::ClassProximity());
  for (std::size_t c = 0; c < this->Surfaces.size(); ++c)
  {
    result.Classes[c].ClassName = this->Surfaces[c]->Name();
  }
}

void vtkVesselDistanceEngine::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->GetMethodName() << "\n";
  os << indent << "RangeMm: " << this->RangeMm << "\n";
  os << indent << "Built: " << (this->Built ? "yes" : "no") << "\n";
  os << indent << "BuildTimeMs: " << this->BuildTimeMs << "\n";
  for (std::size_t i = 0; i < this->Meshes.size(); ++i)
  {
    os << indent << "Vessel " << this->Meshes[i].first << ": "
       << (this->Meshes[i].second ? this->Meshes[i].second->GetNumberOfPolys() : 0) << " cells"
       << (i < this->Surfaces.size() && this->Surfaces[i]->IsClosed() ? ", closed" : "") << "\n";
  }
}
