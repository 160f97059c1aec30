#ifndef vpLiveBenchmark_h
#define vpLiveBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpDistanceEngineSettings.h"
#include "vpPoseFile.h"
#include "vpVesselMeshSet.h"

#include <vector>

class vtkScalpelModel;

namespace vp
{
/// What the live bench runs: poses sent over OpenIGTLink (loopback) at RateHz for Seconds, then
/// at SustainedRateHz for SustainedSeconds.
struct LiveBenchSettings
{
  double RateHz = 60.0;
  double Seconds = 10.0;
  double SustainedRateHz = 1000.0;
  double SustainedSeconds = 60.0;
  /// Also the same stream at RateHz with the tip alone (no whole instrument, no penetration):
  /// what `live --no-surface` computes, the anchor for the breach.
  bool TipOnlyBeside = false;
  /// Also the same stream at RateHz through this engine (the z-buffer: what `live --engine
  /// zbuffer` computes); null: none. A device that cannot be opened is reported, not fatal.
  const DistanceEngineSettings* EngineBeside = nullptr;
};

/// The live path as a clinician's tracker drives it: the module's logic (exact engine, tip and
/// whole instrument, every class) on a live OpenIGTLink stream over loopback (vp::IgtlLink), a
/// sender thread streaming TRANSFORM poses and reading back the results; per frame the latency
/// from a pose's arrival to its results being sent, and the frame's own compute time beside it
/// (the in-process anchor: the same logic without the network). The sustained phase measures the
/// resident memory after 5 s and at the end. poses are cycled. scalpel null: the built-in CUSA
/// handpiece.
BenchJson BenchLive(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const std::vector<TrackedPose>& poses,
  const LiveBenchSettings& settings);
} // namespace vp

#endif
