#ifndef vpEngineBenchmark_h
#define vpEngineBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpBreachBenchmark.h"
#include "vpDistanceEngineSettings.h"
#include "vpLiveBenchmark.h"
#include "vpModelsBenchmark.h"
#include "vpPoseFile.h"
#include "vtkScalpelModel.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkSmartPointer.h>

#include <optional>
#include <set>
#include <string>

namespace vp
{
/// What `vesselproximity bench` measures, typed.
struct BenchmarkRequest
{
  /// exact, zbuffer, replay, live, penetration, breach and/or models.
  std::set<std::string> Parts;
  /// Triangles per class each vessel is grown to (longest-edge bisection: same surface).
  std::vector<std::size_t> SizesTriangles;
  int Queries = 2000;
  int BruteQueries = 30;
  unsigned Seed = 1;
  std::vector<NamedMesh> Vessels;
  std::string Source; ///< said in the report: "files" or "built-in analytic vessels"
  /// The z-buffer part's engine, its device already opened (so a missing one fails before the
  /// long work), and the settings it was made from (the side-by-side runs make more of them).
  vtkSmartPointer<vtkZBufferVesselDistance> ZBuffer;
  DistanceEngineSettings ZBufferSettings;
  std::optional<double> FineCellMm;
  /// The replay's instrument, and poses to replay instead of the generated path (may be empty).
  vtkSmartPointer<vtkScalpelModel> Scalpel;
  std::vector<TrackedPose> Poses;
  /// The live part's rates and durations (it uses the replay's instrument and poses).
  LiveBenchSettings Live;
  /// The penetration sweep's poses (0.2 to 10 mm deep).
  int PenetrationPoses = 100;
  /// The breach's instrument (null: the built-in CUSA handpiece) and its poses.
  vtkSmartPointer<vtkScalpelModel> BreachScalpel;
  BreachBenchSettings Breach;
  /// The models part's label series (its WorkFolder: the system's temporary folder when empty).
  ModelsBenchSettings Models;
};

/// The z-buffer engine the settings describe, its device opened: a missing one fails before any
/// work. Throws as MakeDistanceEngine.
vtkSmartPointer<vtkZBufferVesselDistance> MakeBenchZBuffer(const DistanceEngineSettings& settings);

/// The engines side by side in one run: report["sizes"] (BenchExact per size), report["zbuffer"]
/// (BenchZBuffer per size and ZBufferReport), report["replay"] (BenchReplay), report["live"],
/// report["penetration"] (BenchPenetration) and report["breach"] (BenchBreach, the vessels as
/// given), report["models"] (BenchModels), the last two with the z-buffer settings, each when its part is asked for. Progress on stderr.
BenchJson RunBenchmark(const BenchmarkRequest& request);
} // namespace vp

#endif
