#ifndef vtkVesselDistanceEngine_h
#define vtkVesselDistanceEngine_h

#include "vpProximityResult.h"
#include "vpVesselSurface.h"

#include <vtkObject.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <string>
#include <vector>



/// Common interface of the distance engines: named vessel classes in, per-class proximity out.
///
/// Usage: AddVessel() for each class, Build() once (the engine also builds lazily on the first
/// query), then ComputeProximity() for every tip. Building is the expensive part and happens only
/// when the vessels change, never because the tip moved. After Build(), ComputeProximity() is
/// const and may be called from several threads at once.
class vtkVesselDistanceEngine : public vtkObject
{
public:
  vtkTypeMacro(vtkVesselDistanceEngine, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds (or replaces) the surface of a vessel class. The mesh is copied into the engine's own
  /// representation at Build(); later changes to it need another AddVessel().
  void AddVessel(const std::string& className, vtkPolyData* mesh);
  void RemoveAllVessels();
  int GetNumberOfVessels() const { return static_cast<int>(this->Meshes.size()); }
  std::string GetVesselName(int i) const { return this->Meshes[i].first; }
  /// The prepared surface of class i (after Build()).
  const vp::VesselSurface& GetSurface(int i) const { return *this->Surfaces[i]; }

  /// Distances beyond this are reported as out of range (null). Default: 50 mm, the paper's
  /// range of proximity bins; clinically, danger lies well inside it.
  static constexpr double DefaultRangeMm = 50.0;
  void SetRangeMm(double range);
  double GetRangeMm() const { return this->RangeMm; }

  /// Prepares every surface and the engine's acceleration structures. Throws vp::InputError
  /// naming the class when a mesh is unusable. Does nothing when nothing changed.
  void Build();
  /// Wall time of the last Build() that did work, in milliseconds.
  double GetBuildTimeMs() const { return this->BuildTimeMs; }

  /// Proximity of every vessel class to tip. axis (unit, may be null) asks for the directional
  /// distance. previous (may be null) is this engine's answer for an earlier tip: a moving tip
  /// cannot be nearer than |previous distance - displacement| nor further than previous distance
  /// + displacement, which engines may use to narrow their search.
  virtual void ComputeProximity(const double tip[3], const double* axis, vp::ProximityResult& result,
    const vp::ProximityResult* previous = nullptr) const = 0;

  /// Proximity of every vessel class to each tip (LPS mm), with an axis per tip (axes: as many as
  /// tips, or null for none). results[i] equals, bit for bit,
  /// ComputeProximity() for tip i without a previous answer. This default answers the tips on
  /// all cores (the engines' queries are thread-safe after Build()); an engine that can answer
  /// them at once overrides it (the z-buffer: one GPU submission per batch).
  using Points = std::vector<std::array<double, 3>>;
  virtual void ComputeProximityBatch(const Points& tips, const Points* axes, std::vector<vp::ProximityResult>& results) const;

  /// The bound on |reported - exact| of every distance this engine reports with its current
  /// settings: 0 for exact engines.
  virtual double GetErrorBoundMm() const { return 0.0; }

  /// Where the answers are computed, for reports ("cpu (Embree BVH)", a GPU's name, ...). The
  /// z-buffer engine opens its device to say; throws vp::DeviceError when there is none.
  virtual std::string GetDeviceDescription() { return "cpu"; }

  /// Short name used on the command line and in reports ("exact", "brute", ...).
  virtual const char* GetMethodName() const = 0;
  /// Whether every answer is exact (GetErrorBoundMm() 0 whatever the settings), so that nothing
  /// is gained by checking it against the exact engine. Default false: a new engine is checked.
  virtual bool IsExact() const { return false; }

  /// Builds now, after Build(), what the engine would otherwise build at its first frames (the
  /// z-buffer's query ceilings): a tracker's frames then never pay for it. Default: nothing.
  virtual void PrepareForTracking() {}

protected:
  vtkVesselDistanceEngine();
  ~vtkVesselDistanceEngine() override;

  /// Builds the engine's own structures over this->Surfaces.
  virtual void BuildInternal() = 0;
  void EnsureBuilt() const;
  /// Builds if needed, then resets result for tip: one unfilled entry per class, named.
  void BeginResult(const double tip[3], vp::ProximityResult& result) const;

  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Meshes;
  std::vector<std::shared_ptr<const vp::VesselSurface>> Surfaces;
  double RangeMm = DefaultRangeMm;
  double BuildTimeMs = 0.0;
  bool Built = false;

private:
  vtkVesselDistanceEngine(const vtkVesselDistanceEngine&) = delete;
  void operator=(const vtkVesselDistanceEngine&) = delete;
};

#endif
