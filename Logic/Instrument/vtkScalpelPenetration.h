#ifndef vtkScalpelPenetration_h
#define vtkScalpelPenetration_h

#include "vpProximityResult.h"
#include "vtkExactVesselDistance.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <mutex>
#include <vector>

class vtkPolyData;
class vtkScalpelSurfaceDistance;
class vtkZBufferSurfaceDistance;
namespace vp
{
class CellDistanceField;
}

/// How far an instrument is inside each vessel class: the volume of the instrument inside the
/// class (mm³) and the depth of its deepest point (mm, the distance to the vessel wall), each with
/// a bound. The paper (Table 1) lists both among the z-buffer's strengths; this is the exact
/// engine's answer, to a stated bound, in time that does not grow with how deep the instrument is.
///
/// The instrument's solid is sampled once, in model coordinates, on a lattice of CellSizeMm cubes
/// held in an octree: a cube whose centre lies farther from the instrument's wall than its half
/// diagonal is uniformly inside (kept whole) or outside (dropped), so only the cells the wall cuts
/// are classified one by one, each with its share inside (the wall as a plane, vp::WallPlane).
/// Per pose and class, the same octree is walked in the world: each cube asks the vessel engine
/// for the wall within its own reach only (a bounded search, as cheap deep inside as near the
/// wall); where none is, the cube lies wholly on its parent's side and is counted whole. Only
/// cubes the wall passes are split down to cells, each counted by its share behind both walls.
/// The deepest cell is then searched best first among the cubes wholly inside, each opened only
/// while its bound (a wall point's distance, or its centre's distance plus its half diagonal)
/// can beat the deepest found. With r the half diagonal of a cell:
/// - VolumeMm3 = cell volume x the cells' shares inside both; VolumeBoundMm3 = cell volume x
///   cells within r of either wall that may meet both solids (only those can be counted wrongly),
///   and every cell of the cubes a budget left unsplit (SetQueryBudget);
/// - DepthMm = the largest distance to the vessel wall of a cell centre inside the vessel and
///   inside (or within r of) the instrument, up to DeepSearchToleranceMm above it, or the largest
///   still possible where the search stopped short (DepthSlackMm, the budget);
///   DepthBoundMm = r + that tolerance + how far DepthMm lies above the deepest cell found
///   (distance is 1-Lipschitz; never below the truth by more).
/// Nothing is computed where the surfaces neither touch nor nest: a class whose whole-instrument
/// distance is above 0 is tested at one instrument point only (is the instrument entirely inside?).
///
/// A vessel or instrument surface that is not closed has no inside: Penetration::Known is false
/// for that class (all of them, for an open instrument), never a silent 0.
class vtkScalpelPenetration : public vtkObject
{
public:
  static vtkScalpelPenetration* New();
  /// The default QueryBudget (see SetQueryBudget).
  static constexpr long long DefaultQueryBudget = 1200;
  vtkTypeMacro(vtkScalpelPenetration, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The vessel classes (an exact engine, built before the first query).
  void SetVesselDistance(vtkExactVesselDistance* engine);
  vtkExactVesselDistance* GetVesselDistance() const { return this->Vessels; }
  /// When set, the walk reads the z-buffer's distance field and its layers' inside instead of
  /// the exact engine (which still says which classes are closed): the paper's superimposition
  /// of the instrument's cells on the vessels' layers. A cell counts as uncertain while the wall
  /// may lie within a layer cell's diagonal (0.69 mm) of it, and counts its column's share inside
  /// the layers (a slice the wall crosses, half); the depth is the deepest cell's upper bound,
  /// DepthBoundMm the lattice's half diagonal plus the field's interval. Default: none.
  void SetZBufferSurface(vtkZBufferSurfaceDistance* surface);
  vtkZBufferSurfaceDistance* GetZBufferSurface() const;
  /// The frame's instrument distance: when it answers from the z-buffer's layers, the walk reads
  /// them too (SetZBufferSurface), else the exact engine alone.
  void SetInstrumentDistance(vtkScalpelSurfaceDistance* surface);
  /// The instrument surface in model coordinates (closed, for an inside).
  void SetToolSurface(vtkPolyData* model);
  /// Edge of a lattice cell (mm). Default 0.4 mm: a depth bound of 0.35 mm, as the z-buffer's
  /// default cell. Smaller cells cost more, as the cube of the edge near the walls' crossing.
  void SetCellSizeMm(double cellMm);
  double GetCellSizeMm() const { return this->CellSizeMm; }

  /// The exact engine's tolerance in the search for the deepest cell (mm): deep inside a vessel,
  /// where many triangles are nearly equidistant (at a sphere's centre, all), an exact nearest
  /// search reads them all; the search skips the tree nodes that cannot beat the best by more.
  /// The depth may be this much above the deepest cell's, never below; the cells of the volume
  /// are classified exactly.
  static constexpr double DeepSearchToleranceMm = 0.05;
  /// The deepest cell's search stops when no cube left can beat the deepest found by more than
  /// this (mm); the depth is then the best bound left, at most this much above that cell's.
  static constexpr double DepthSlackMm = 0.1;

  /// The most vessel-wall queries one class's volume walk makes per frame (0: no limit); the
  /// deepest cell's search makes at most QueryBudget / DeepShare (at least 16), each costing some
  /// ten of the walk's. The walk's cost grows with the area of vessel wall inside the instrument,
  /// which a breach makes unbounded; within the budget the cubes the wall crosses are split level
  /// by level, coarse first, on every core, and when the next level would pass it those that fit
  /// are split (the ones the instrument's wall also crosses first) and the others counted by the
  /// wall's plane at their centres, every cell of them in VolumeBoundMm3; the depth left
  /// unsearched is the answer's upper end (DepthMm, never below the truth) and its distance above
  /// the deepest cell found is in DepthBoundMm. A count, not a time, so that a pose gives the
  /// same answer on every machine. The parts left to the plane are corrected for the wall's bend
  /// measured between a cube's plane and its parent's (see the .cxx's Estimate). Default
  /// DefaultQueryBudget, 1200: the CUSA handpiece in IRCADb patients 1 and 4 in under 5 ms at the
  /// 95th percentile on 2 cores, all but one of 2,160 class volumes within 10 % of the fine
  /// reference (bench --engines breach, Documentation/Benchmarks.md).
  void SetQueryBudget(long long queries);
  long long GetQueryBudget() const { return this->QueryBudget; }
  /// A query of the z-buffer's distance field costs less than the exact engine's: with the field,
  /// the walk may make this many times the budget. Measured on IRCADb patients 1 and 4 (bench
  /// --engines breach, z-buffer frame p95 / class volumes outside the contract): 2: 2.05 and
  /// 1.8 ms / 1 and 0; 1.75: 1.98 and 1.76 / 1 and 0; 1.5: 1.60 and 1.49 / 2 and 1.
  static constexpr double FieldBudgetFactor = 1.75;
  /// The deepest cell's search makes at most QueryBudget / DeepShare deep queries (at least 16).
  static constexpr long long DeepShare = 8;

  /// Samples the instrument now (the first query does otherwise); GetBuildTimeMs() says how long.
  void Build();
  double GetBuildTimeMs() const { return this->BuildTimeMs; }
  /// The instrument's volume as sampled (mm³) and its bound; false before Build() or for an open
  /// instrument.
  bool GetToolVolumeMm3(double& volume, double& bound) const;
  /// Whether the instrument's surface is closed (after Build()): without an inside, no
  /// penetration can be known.
  bool IsToolClosed() const;

  /// Per class of the vessel engine, in its order. surface: the whole-instrument distances for
  /// the same pose (vtkScalpelSurfaceDistance), which say where nothing can overlap.
  /// Thread-safe after Build().
  void ComputePenetration(const std::array<double, 16>& modelToWorld, const std::vector<vp::SurfaceProximity>& surface,
    std::vector<vp::Penetration>& out) const;

protected:
  vtkScalpelPenetration();
  ~vtkScalpelPenetration() override;

  vtkSmartPointer<vtkExactVesselDistance> Vessels;
  vtkSmartPointer<vtkZBufferSurfaceDistance> ZBufferSurface;
  vtkSmartPointer<vtkPolyData> ToolSurface;
  double CellSizeMm = 0.4;
  long long QueryBudget = DefaultQueryBudget;
  double BuildTimeMs = 0.0;

private:
  vtkScalpelPenetration(const vtkScalpelPenetration&) = delete;
  void operator=(const vtkScalpelPenetration&) = delete;

  struct Lattice;
  std::shared_ptr<const Lattice> Tool;
  /// One class's walk (ComputePenetration runs the classes on threads).
  vp::Penetration ComputeClass(int c, const std::array<double, 16>& modelToWorld,
    const std::vector<vp::SurfaceProximity>& surface, const vp::CellDistanceField* field) const;
  std::mutex BuildLock;
};

#endif
