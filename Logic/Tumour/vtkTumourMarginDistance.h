#ifndef vtkTumourMarginDistance_h
#define vtkTumourMarginDistance_h

#include "vpProximityResult.h"
#include "vpTumourProximity.h"

#include <vtkObject.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

class vtkExactVesselDistance;
class vtkFclSurfaceDistance;
class vtkPolyData;

/// The distance from the scalpel's tip, and from its whole surface (within a range), to each tumour to be
/// resected: what the resection margin is measured with. Exact, whatever the distance: a tumour
/// is small beside the vessels (a few thousand triangles), so the vessels' exact machinery answers
/// it in microseconds, where an approximate engine's bound would eat into a 5 mm margin.
///
/// The tumours' trees are built once (Build(), or the first call), as the vessels' are: each
/// tumour a class of a vtkExactVesselDistance (Embree's point queries; inside by the pseudonormal
/// on a closed surface, by the vote of rays on one that is not), and, with a tool surface, of a
/// vtkFclSurfaceDistance for the whole instrument. Nothing is rebuilt because the scalpel moved.
///
/// Levels are the tracking logic's to give (vp::ClassifyMargin with its hysteresis); this class
/// measures.
class vtkTumourMarginDistance : public vtkObject
{
public:
  static vtkTumourMarginDistance* New();
  vtkTypeMacro(vtkTumourMarginDistance, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Adds a tumour (LPS mm; closed for inside/outside) under an id of its own. Throws
  /// vp::ParameterError("Tumours") for an empty or repeated id, std::invalid_argument for null.
  void AddTumour(const std::string& id, vtkPolyData* surface);
  void RemoveAllTumours();
  int GetNumberOfTumours() const { return static_cast<int>(this->Tumours.size()); }
  const std::string& GetTumourId(int i) const { return this->Tumours[i].first; }
  vtkPolyData* GetTumourSurface(int i) const { return this->Tumours[i].second; }

  /// The instrument's surface in model coordinates, for the whole instrument's distance (null,
  /// the default: the tip alone).
  void SetToolSurface(vtkPolyData* model);

  /// How far the whole instrument is searched for each tumour, in mm (default 10: the default
  /// margin and its near band, where a tumour is more than clear; the tracking logic sets its
  /// margin plus near band each frame). A tumour farther from every point of the instrument has no
  /// instrument distance (SurfaceKnown false): FCL proving a distance of 30 mm to a blob costs
  /// several times what proving none within 10 does. The tip's distance has no range. A search
  /// radius, not a reason to build again. Throws ParameterError unless positive.
  void SetInstrumentRangeMm(double rangeMm);
  double GetInstrumentRangeMm() const { return this->InstrumentRangeMm; }

  /// Builds the trees when a tumour or the tool changed. Throws vp::InputError naming a tumour
  /// whose mesh is unusable (no triangle, not finite).
  void Build();

  /// Each tumour's signed distance from tip (world, mm) and its closest point, and, with a tool
  /// surface, the whole instrument's closest approach at modelToWorld (row-major). previous: the
  /// answer for an earlier pose (may be null), whose closest pairs start the instrument's search.
  /// out.Tumours gets one entry per tumour, in order; levels are left Clear.
  void ComputeMargin(const double tip[3], const std::array<double, 16>& modelToWorld, vp::TumourMargin& out,
    const vp::TumourMargin* previous = nullptr);

protected:
  vtkTumourMarginDistance();
  ~vtkTumourMarginDistance() override;

private:
  vtkTumourMarginDistance(const vtkTumourMarginDistance&) = delete;
  void operator=(const vtkTumourMarginDistance&) = delete;

  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> Tumours;
  vtkSmartPointer<vtkPolyData> ToolSurface;
  vtkSmartPointer<vtkExactVesselDistance> Exact;
  vtkSmartPointer<vtkFclSurfaceDistance> Instrument;
  double InstrumentRangeMm = 10.0;
  bool Built = false;
  /// The closest pairs of the previous answer, as the instrument's calculator reads them.
  std::vector<vp::SurfaceProximity> LastSurface;
};

#endif
