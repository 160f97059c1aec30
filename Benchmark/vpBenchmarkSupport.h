#ifndef vpBenchmarkSupport_h
#define vpBenchmarkSupport_h

// What the benchmarks share: timings as JSON, a batch timed against single queries, one z-buffer
// query with its device time, the tips they are measured on, and the built-in vessels.

#include "vpProximityResult.h"
#include "vpVesselMeshSet.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkZBufferVesselDistance.h"

#include <nlohmann/json.hpp>

#include <array>
#include <vector>

namespace vp
{
using BenchJson = nlohmann::ordered_json;
using BenchPoints = std::vector<std::array<double, 3>>;

/// Median and p95 of the times, in ms, and how many there are.
BenchJson Timing(const std::vector<double>& ms);
/// Tips answered per second by calls of ms milliseconds each (the median call's).
double TipsPerSecond(std::size_t tips, double ms);

/// All tips as one batch (ComputeProximityBatch), five times: time per batch and tips per second
/// (from the median batch). With singles, also how many answers differ from them in any way
/// (there must be none: a batch is the single queries, bit for bit).
BenchJson BenchBatch(vtkVesselDistanceEngine* engine, const BenchPoints& tips, const std::vector<ProximityResult>* singles);

/// A z-buffer's calls by part (vtkZBufferVesselDistance::GetLastCallTimes), one call after
/// another: Json() gives each part's median and p95 (total, device, device_listing,
/// device_visiting, device_reducing, submit_wait, votes, ceilings, read, order, host_listing, in
/// ms) and the last call's votes, submissions and tiles listed.
class CallTimeSeries
{
public:
  void Add(const vtkZBufferVesselDistance::CallTimes& t);
  BenchJson Json() const;
  double DeviceMedianMs() const;

private:
  std::vector<double> Total, Device, Listing, Visiting, Reducing, Wait, Votes, Ceilings, Read, Order, HostListing;
  std::size_t LastVotes = 0, LastSubmissions = 0, LastTilesListed = 0;
};

/// Class answers of two runs over the same tips that differ in range, distance or inside.
int CountDifferingAnswers(const std::vector<ProximityResult>& a, const std::vector<ProximityResult>& b);

/// One z-buffer query, its host time in ms and its device time (the engine's timestamps).
void TimedQuery(vtkZBufferVesselDistance* zbuffer, const double* tip, const double* axis, ProximityResult& result,
  std::vector<double>& ms, std::vector<double>& deviceMs);

/// Random tips in the vessels' box (grown by 10 mm, where a scalpel works), and a tracked tip's
/// random walk of 0.5 mm steps through it; seeded.
struct BenchTips
{
  BenchPoints Random, Track;
};
BenchTips MakeBenchTips(const std::vector<NamedMesh>& vessels, int queries, unsigned seed);

/// The built-in analytic vessels, as the bench measures them when no files are given.
std::vector<NamedMesh> BuiltInVessels();
} // namespace vp

#endif
