#ifndef vtkZBufferSurfaceDistance_h
#define vtkZBufferSurfaceDistance_h

#include "vpProximityResult.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkSmartPointer.h>

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

/// The whole-instrument distance on the z-buffer engine's depth layers: per class, the least
/// distance from any point of the instrument's surface to the vessel's marked cells, with the
/// closest pair, within a stated bound. Nothing about the vessels is rebuilt when the tool moves.
///
/// The instrument is sampled once (vp::SurfaceSamples: every surface point within
/// SampleSpacingMm of a sample, grouped in clusters). After each rendering of the layers, a
/// lower-bound field over blocks of cells (vp::BlockDistanceField) is built on the host from the
/// layers' occupancy. Per pose, the field bounds every cluster and then every sample from below,
/// and only the samples that can still be the nearest go to the GPU, in batches nearest-bound
/// first, each batch searching only as far as the best distance found so far
/// (vtkZBufferVesselDistance::ComputeProximityBatchWithin). The previous frame's closest samples
/// go first: they set a tight bound from the first batch on.
///
/// Bound: the samples' least distance is within SampleSpacingMm above the surface's, and each
/// sample's within the layers' bound of the truth, so the answer (that least distance less half
/// the spacing) is within GetErrorBoundMm() of the exact one. When a pose would need more than
/// MaxQueriedPoints samples measured, the search stops and the answer's bound widens by half the
/// gap still undecided (its own ErrorBoundMm says so); it never claims more than it knows.
class vtkZBufferSurfaceDistance : public vtkScalpelSurfaceDistance
{
public:
  static vtkZBufferSurfaceDistance* New();
  vtkTypeMacro(vtkZBufferSurfaceDistance, vtkScalpelSurfaceDistance);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The z-buffer engine whose layers are searched (fixed box).
  void SetZBuffer(vtkZBufferVesselDistance* engine);
  vtkZBufferVesselDistance* GetZBuffer() const { return this->ZBuffer; }

  /// Largest distance from any point of the instrument's surface to its nearest sample, mm.
  /// Default 0: half the engine's cell.
  vtkSetMacro(SampleSpacingMm, double);
  vtkGetMacro(SampleSpacingMm, double);
  /// Edge of the lower-bound field's blocks, mm (a whole number of cells). Default 1.6 mm.
  vtkSetMacro(BlockMm, double);
  vtkGetMacro(BlockMm, double);
  /// Most samples measured on the GPU per pose. Default 8192.
  vtkSetMacro(MaxQueriedPoints, int);
  vtkGetMacro(MaxQueriedPoints, int);

  /// Samples the instrument and builds the lower-bound field now (the first query does it
  /// otherwise, and again after the tool or the engine changed).
  void Build();
  double GetBuildTimeMs() const { return this->BuildTimeMs; }

  void ComputeSurfaceProximity(const std::array<double, 16>& modelToWorld, std::vector<vp::SurfaceProximity>& out,
    const std::vector<vp::SurfaceProximity>* previous = nullptr) const override;
  const char* GetMethodName() const override { return "zbuffer"; }
  /// The instrument's samples (after Build()).
  long long GetNumberOfToolTriangles() const override;
  long long GetNumberOfSamples() const;
  /// The bound of an answer whose search finished: the layers' bound plus half the spacing.
  double GetErrorBoundMm() const;
  /// Samples measured and GPU submissions for the last pose (for benchmarks).
  long long GetLastQueriedPoints() const { return this->LastQueried; }
  long long GetLastSubmissions() const { return this->LastSubmissions; }

protected:
  vtkZBufferSurfaceDistance();
  ~vtkZBufferSurfaceDistance() override;

  vtkSmartPointer<vtkZBufferVesselDistance> ZBuffer;
  double SampleSpacingMm = 0.0;
  double BlockMm = 1.6;
  int MaxQueriedPoints = 8192;
  double BuildTimeMs = 0.0;

private:
  vtkZBufferSurfaceDistance(const vtkZBufferSurfaceDistance&) = delete;
  void operator=(const vtkZBufferSurfaceDistance&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
  mutable std::mutex BuildLock;
  mutable std::atomic<long long> LastQueried{ 0 };
  mutable std::atomic<long long> LastSubmissions{ 0 };
};

#endif
