#ifndef vpDistanceEngineFactory_h
#define vpDistanceEngineFactory_h

#include "vpDistanceEngineSettings.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <string>

namespace vp
{
/// The engine the settings describe, its Vulkan device opened (a missing one is reported before
/// any file is read). Throws ParameterError naming the setting for a bad value, and DeviceError
/// when the z-buffer engine was asked for and there is no device. With Method auto and no device,
/// the exact engine, and *note (when given) says why.
vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const DistanceEngineSettings& settings, std::string* note = nullptr);
} // namespace vp

#endif
