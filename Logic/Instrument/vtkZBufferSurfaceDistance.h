#ifndef vtkZBufferSurfaceDistance_h
#define vtkZBufferSurfaceDistance_h

#include "vpProximityResult.h"
#include "vtkScalpelSurfaceDistance.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkSmartPointer.h>

namespace vp
{
class CellDistanceField;
}

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

/// The whole-instrument distance on the z-buffer engine's depth layers: per class, the least
/// distance from any point of the instrument's surface to the vessel's surface as the layers hold
/// it, with the closest pair, within a bound stated per answer. Nothing about the vessels is
/// rebuilt when the tool moves, and no sample costs a GPU round trip.
///
/// The instrument is sampled once (vp::SurfaceSamples: every surface point within
/// SampleSpacingMm of a sample, in a tree of spheres). After each rendering of the layers,
/// a distance field of the marked cells is built on the host from the layers' occupancy
/// (vp::CellDistanceField: a byte per cell, exact distances between cell centres, in linear
/// time), which bounds the distance from any point from below and above in constant time. Per
/// pose, after the previous frame's closest samples, the tree is walked best first: a node is
/// bounded from below at its centre, and opened only while it can still hold the nearest sample,
/// so the parts of the instrument far from every vessel cost a bound each, not one per sample.
///
/// Bound: with the samples' least lower and upper bounds lo and hi, the truth lies in
/// [lo - SampleSpacingMm, hi]. The answer is the lower end, never above the truth (it may
/// overstate proximity, never understate it; contact reads 0), and its ErrorBoundMm the width, at
/// most GetErrorBoundMm() (1.64 mm with 0.4 mm cells, about 1.2 mm typically) within the field's
/// fine reach (16 cells: 6.4 mm) and box; beyond, the field's levels are half a cell apart up to
/// 79.5 cells (31.8 mm), and the coarse blocks' a few millimetres wide farther still. The closest point on
/// the vessel is the nearest marked cell's point nearest the tool's, found by descending the field
/// (or, beyond its reach, one query of the layers).
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
  /// Edge of the coarse blocks that bound distances beyond the field's reach, mm (a whole number
  /// of cells). Default 1.6 mm.
  vtkSetMacro(BlockMm, double);
  vtkGetMacro(BlockMm, double);
  /// Most field cells per class: one byte each. When the layers hold more cells, a field cell
  /// covers k x k x k of them (the bound grows with it). Default 2^26 (64 MiB per class).
  vtkSetMacro(MaxFieldCells, long long);
  vtkGetMacro(MaxFieldCells, long long);

  /// Samples the instrument and builds the distance field now (the first query does it
  /// otherwise, and again after the tool or the engine changed).
  void Build();
  double GetBuildTimeMs() const { return this->BuildTimeMs; }

  void ComputeSurfaceProximity(const std::array<double, 16>& modelToWorld, std::vector<vp::SurfaceProximity>& out,
    const std::vector<vp::SurfaceProximity>* previous = nullptr) const override;
  const char* GetMethodName() const override { return "zbuffer"; }
  /// The instrument's samples (after Build()).
  long long GetNumberOfToolTriangles() const override;
  long long GetNumberOfSamples() const;
  /// The largest bound of an answer within the field's fine reach (16 cells) and box: twice the
  /// field's (a cell's diagonal and an eighth of a cell's edge, vp::CellDistanceField::BoundMm)
  /// plus the spacing.
  double GetErrorBoundMm() const;
  /// The distance field of the current layers (building what is out of date), for the
  /// penetration's walk: it stays valid while held.
  std::shared_ptr<const vp::CellDistanceField> GetDistanceField() const;
  /// The field's memory (bytes) and layer cells per field cell along an axis (after Build()).
  std::size_t GetFieldMemoryBytes() const;
  int GetFieldLayerCellsPerCell() const;
  /// Samples evaluated and GPU submissions (closest points beyond the field's reach) for the
  /// last pose (for benchmarks).
  long long GetLastEvaluatedSamples() const { return this->LastEvaluated; }
  long long GetLastSubmissions() const { return this->LastSubmissions; }

protected:
  vtkZBufferSurfaceDistance();
  ~vtkZBufferSurfaceDistance() override;

  vtkSmartPointer<vtkZBufferVesselDistance> ZBuffer;
  double SampleSpacingMm = 0.0;
  double BlockMm = 1.6;
  long long MaxFieldCells = 1LL << 26;
  double BuildTimeMs = 0.0;

private:
  vtkZBufferSurfaceDistance(const vtkZBufferSurfaceDistance&) = delete;
  void operator=(const vtkZBufferSurfaceDistance&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
  mutable std::mutex BuildLock;
  mutable std::atomic<long long> LastEvaluated{ 0 };
  mutable std::atomic<long long> LastSubmissions{ 0 };
};

#endif
