#ifndef vpDistanceEngineSettings_h
#define vpDistanceEngineSettings_h

#include <array>
#include <optional>
#include <string>

namespace vp
{
/// Which engine answers and how it is set up: what a front end asks for, in the logic's names.
/// Unset optionals keep the engine's own defaults.
struct DistanceEngineSettings
{
  /// exact (Embree BVH), zbuffer (Vulkan depth layers), both (the z-buffer engine; the caller
  /// checks it against the exact one), brute (the paper's CPU algorithm), or auto (the z-buffer
  /// engine when a Vulkan device opens, else the exact one).
  std::string Method = "exact";
  std::optional<double> RangeMm;
  // The z-buffer engine's (vtkZBufferVesselDistance's Set/Get of the same names):
  std::string DeviceSelector;
  std::optional<double> CellSizeMm;
  int ResolutionPx = 0;
  std::string LayerMode = "exact"; ///< exact or paper
  std::string BoxMode = "fixed";   ///< fixed or moving
  std::optional<std::array<double, 3>> MovingBoxSizeMm;
  int DistanceBins = 0;
};

} // namespace vp

#endif
