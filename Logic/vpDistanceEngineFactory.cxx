#include "vpDistanceEngineFactory.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpVulkanContext.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkZBufferVesselDistance.h"

namespace vp
{
namespace
{
vtkSmartPointer<vtkZBufferVesselDistance> MakeZBuffer(const DistanceEngineSettings& s)
{
  auto z = vtkSmartPointer<vtkZBufferVesselDistance>::New();
  z->SetDeviceSelector(s.DeviceSelector);
  if (s.CellSizeMm)
  {
    z->SetCellSizeMm(*s.CellSizeMm);
  }
  z->SetResolutionPx(s.ResolutionPx);
  if (s.LayerMode != "exact" && s.LayerMode != "paper")
  {
    throw ParameterError("LayerMode", "expected exact or paper, got '" + s.LayerMode + "'");
  }
  z->SetLayerMode(s.LayerMode == "paper" ? vtkZBufferVesselDistance::PaperNearFar : vtkZBufferVesselDistance::ExactIntervals);
  if (s.BoxMode != "fixed" && s.BoxMode != "moving")
  {
    throw ParameterError("BoxMode", "expected fixed or moving, got '" + s.BoxMode + "'");
  }
  z->SetBoxMode(s.BoxMode == "moving" ? vtkZBufferVesselDistance::MovingWithTip : vtkZBufferVesselDistance::FixedAroundVessels);
  if (s.MovingBoxSizeMm)
  {
    z->SetMovingBoxSizeMm((*s.MovingBoxSizeMm)[0], (*s.MovingBoxSizeMm)[1], (*s.MovingBoxSizeMm)[2]);
  }
  z->SetDistanceBins(s.DistanceBins);
  z->GetDeviceName(); // opens the device
  return z;
}
} // namespace

vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const DistanceEngineSettings& settings, std::string* note)
{
  vtkSmartPointer<vtkVesselDistanceEngine> engine;
  const std::string& method = settings.Method;
  if (method == "exact")
  {
    engine = vtkSmartPointer<vtkExactVesselDistance>::New();
  }
  else if (method == "brute")
  {
    engine = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  }
  else if (method == "zbuffer" || method == "both")
  {
    engine = MakeZBuffer(settings);
  }
  else if (method == "auto")
  {
    try
    {
      engine = MakeZBuffer(settings);
    }
    catch (const DeviceError& e)
    {
      if (note)
      {
        *note = e.what();
      }
      engine = vtkSmartPointer<vtkExactVesselDistance>::New();
    }
  }
  else
  {
    throw ParameterError("Method", "unknown method '" + method + "' (exact, zbuffer, both, brute or auto)");
  }
  if (settings.RangeMm)
  {
    // A user's range: a body's size at most (the engines' own searches may reach further).
    if (!(*settings.RangeMm <= limits::MaxRangeMm))
    {
      throw ParameterError("RangeMm", "must be at most " + NumberText(limits::MaxRangeMm) + " millimetres (more than any body)");
    }
    engine->SetRangeMm(*settings.RangeMm);
  }
  return engine;
}
} // namespace vp
