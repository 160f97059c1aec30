#ifndef vpZBufferBenchmark_h
#define vpZBufferBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpDistanceEngineSettings.h"

#include <optional>

class vtkZBufferVesselDistance;

namespace vp
{
/// The z-buffer engine on all classes at once at one mesh size: its build and rendering, cached
/// queries (host and device time; with an axis; the paper's near/far mode; on a GPU the query pass
/// it did not choose), batches checked against the single queries, the moving box on the tracked
/// tip, beside the exact engine and brute force on the same tips; the largest |zbuffer - exact|
/// against the error bound. The engine is refilled with these vessels. Progress on stderr.
BenchJson BenchZBuffer(vtkZBufferVesselDistance* zbuffer, const std::vector<NamedMesh>& refined, std::size_t target,
  const BenchPoints& tips, const BenchPoints& track, int bruteQueries);

/// Two z-buffer engines of the given settings (the second at secondCellMm when positive) on the
/// same tips, in turns of 20 queries, so that both see the device in the same state (a GPU's
/// clock rises and falls with its load): host and device times for each, and the second's over
/// the first's.
BenchJson SideBySide(const std::vector<NamedMesh>& first, const std::vector<NamedMesh>& second, double secondCellMm,
  const BenchPoints& tips, const DistanceEngineSettings& settings);

/// Vessels refined to this many triangles a class.
struct SizedVessels
{
  std::vector<NamedMesh> Vessels;
  std::size_t Target = 0;
};

/// The z-buffer's report: its device and settings, the sizes (BenchZBuffer's), the cached query's
/// growth from the smallest size to the largest, and side by side the largest beside the smallest
/// and, with fineCellMm, the smallest at that cell beside the set one.
BenchJson ZBufferReport(vtkZBufferVesselDistance* zbuffer, const BenchJson& sizes, const SizedVessels& smallest,
  const SizedVessels& largest, const BenchPoints& tips, const DistanceEngineSettings& settings,
  std::optional<double> fineCellMm);
} // namespace vp

#endif
