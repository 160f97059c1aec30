#include "vpInstrumentDistanceFactory.h"

#include "vtkFclSurfaceDistance.h"
#include "vtkZBufferSurfaceDistance.h"
#include "vtkZBufferVesselDistance.h"

namespace vp
{
vtkSmartPointer<vtkScalpelSurfaceDistance> MakeInstrumentDistance(InstrumentMethod method, vtkVesselDistanceEngine* engine,
  vtkExactVesselDistance* exact, vtkPolyData* tool, double rangeMm)
{
  auto* layers = vtkZBufferVesselDistance::SafeDownCast(engine);
  if (method == InstrumentMethod::Automatic && layers && layers->GetBoxMode() == vtkZBufferVesselDistance::FixedAroundVessels)
  {
    auto zbuffer = vtkSmartPointer<vtkZBufferSurfaceDistance>::New();
    zbuffer->SetZBuffer(layers);
    zbuffer->SetToolSurface(tool);
    zbuffer->SetRangeMm(rangeMm);
    zbuffer->Build(); // the samples and the field
    return zbuffer;
  }
  if (method == InstrumentMethod::BoundingSpheres)
  {
    auto spheres = vtkSmartPointer<vtkScalpelSurfaceDistance>::New();
    spheres->SetVesselDistance(exact);
    spheres->SetToolSurface(tool);
    spheres->SetRangeMm(rangeMm);
    return spheres;
  }
  auto fcl = vtkSmartPointer<vtkFclSurfaceDistance>::New();
  fcl->SetVesselDistance(exact);
  fcl->SetToolSurface(tool);
  fcl->SetRangeMm(rangeMm);
  fcl->Build(); // the trees
  return fcl;
}
} // namespace vp
