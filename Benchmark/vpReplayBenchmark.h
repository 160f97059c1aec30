#ifndef vpReplayBenchmark_h
#define vpReplayBenchmark_h

#include "vpBenchmarkSupport.h"
#include "vpPoseFile.h"
#include "vpDistanceEngineSettings.h"
#include "vpVesselMeshSet.h"

#include <array>
#include <vector>

class vtkScalpelModel;

namespace vp
{
/// A surgeon's path through the vessels (seeded): the tip in straight 0.5 mm steps between points
/// 1 to 15 mm off random vessel surface points, turning 0.2 degrees a frame, at 50 Hz.
std::vector<TrackedPose> PosesNearVessels(const std::vector<NamedMesh>& vessels, std::size_t frames, unsigned seed, vtkScalpelModel* scalpel);

/// Replay throughput: a scalpel tracked for `frames` poses at 50 Hz, its tip stepping 0.5 mm
/// between points a few millimetres off random vessel surface points (seeded), turning 0.2
/// degrees a frame, all vessel classes at full size: frames per second of the module's logic, each
/// configuration opened from a scene request and its poses run through a tracking session, for the
/// exact engine (tip; tip and whole surface), the z-buffer engine on cached layers (when zbuffer
/// settings are given, its layers rendered once first) and brute force (the first bruteFrames).
/// Every z-buffer frame is checked against the exact one. FCL answers the whole instrument on the
/// same poses beside our own, its answers compared with ours. givenPoses, when not empty, replace
/// the generated path (the demo's trajectory, say).
BenchJson BenchReplay(const std::vector<NamedMesh>& vessels, std::size_t frames, unsigned seed,
  vtkScalpelModel* scalpel, const DistanceEngineSettings* zbuffer, int bruteFrames, const std::vector<TrackedPose>& givenPoses);
} // namespace vp

#endif
