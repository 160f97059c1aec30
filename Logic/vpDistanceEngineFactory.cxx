#include "vpDistanceEngineFactory.h"

#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpVulkanContext.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkZBufferVesselDistance.h"

#include <algorithm>

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
vtkSmartPointer<vtkVesselDistanceEngine> MakeExact(const DistanceEngineSettings&, std::string*)
{
  return vtkSmartPointer<vtkExactVesselDistance>::New();
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeBrute(const DistanceEngineSettings&, std::string*)
{
  return vtkSmartPointer<vtkBruteForceVesselDistance>::New();
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeZBufferEngine(const DistanceEngineSettings& settings, std::string*)
{
  return MakeZBuffer(settings);
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeZBufferOrExact(const DistanceEngineSettings& settings, std::string* note)
{
  try
  {
    return MakeZBuffer(settings);
  }
  catch (const DeviceError& e)
  {
    if (note)
    {
      *note = e.what();
    }
    return vtkSmartPointer<vtkExactVesselDistance>::New();
  }
}
} // namespace

const std::vector<EngineMethod>& EngineMethods()
{
  static const std::vector<EngineMethod> methods = {
    { "exact", "exact: Embree BVH, exact", OfferedForTips | OfferedForTracking | OfferedInView | OfferedToSlicerTips, &MakeExact },
    { "zbuffer", "zbuffer: Vulkan depth layers, within the error bound",
      OfferedForTips | OfferedForTracking | OfferedInView | OfferedToSlicerTips, &MakeZBufferEngine },
    // The z-buffer engine; the logic checks it against the exact one (SceneRequest::CompareWithExact).
    { "both", "both: the z-buffer, checked against exact", OfferedForTips | OfferedForTracking | OfferedToSlicerTips,
      &MakeZBufferEngine },
    { "brute", "brute: the paper's CPU algorithm", OfferedForTips, &MakeBrute },
    { "auto", "auto: the z-buffer when a Vulkan device opens, else exact", OfferedForTips | OfferedToSlicerTips,
      &MakeZBufferOrExact },
  };
  return methods;
}

std::vector<std::string> EngineMethodNames(EngineOffer offer)
{
  std::vector<std::string> names;
  for (const EngineMethod& m : EngineMethods())
  {
    if (m.Offered & offer)
    {
      names.emplace_back(m.Name);
    }
  }
  return names;
}

std::string EngineMethodHelp(const std::vector<std::string>& names, const std::string& separator)
{
  std::string help;
  for (const std::string& name : names)
  {
    for (const EngineMethod& m : EngineMethods())
    {
      if (name == m.Name)
      {
        help += (help.empty() ? "" : separator) + m.Help;
      }
    }
  }
  return help;
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const DistanceEngineSettings& settings, std::string* note)
{
  const std::vector<EngineMethod>& methods = EngineMethods();
  const auto method = std::find_if(methods.begin(), methods.end(), [&](const EngineMethod& m) { return settings.Method == m.Name; });
  if (method == methods.end())
  {
    std::string names;
    for (const EngineMethod& m : methods)
    {
      names += std::string(names.empty() ? "" : ", ") + m.Name;
    }
    throw ParameterError("Method", "unknown method '" + settings.Method + "' (" + names + ")");
  }
  vtkSmartPointer<vtkVesselDistanceEngine> engine = method->Make(settings, note);
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
