#ifndef vtkVesselSurfaceRepair_h
#define vtkVesselSurfaceRepair_h

#include "vpVesselSurface.h"

#include <vtkPolyDataAlgorithm.h>

#include <cstddef>
#include <string>

namespace vp
{
/// What vtkVesselSurfaceRepair changed, and the defects before and after.
struct SurfaceRepairReport
{
  MeshDefects Before;
  MeshDefects After;
  std::size_t MergedPoints = 0;        // coincident points made one (cracks closed)
  std::size_t RemovedDegenerate = 0;   // triangles with a repeated point
  std::size_t RemovedDuplicates = 0;   // second copies of a triangle (duplicated sheets)
  std::size_t RemovedFins = 0;         // triangles hanging by one edge off a non-manifold edge
  std::size_t FilledHoles = 0;         // boundary loops closed
  std::size_t AddedTriangles = 0;      // the triangles that closed them
  std::size_t TurnedTriangles = 0;     // given triangles rewound to agree with their neighbours
  bool Changed() const
  {
    return MergedPoints + RemovedDegenerate + RemovedDuplicates + RemovedFins + AddedTriangles + TurnedTriangles > 0;
  }
  /// "merged 2 points, filled 3 holes with 41 triangles, turned 12 triangles; now closed" or
  /// "nothing to repair; closed".
  std::string Describe() const;
};
} // namespace vp

/// Repairs a vessel surface so that its inside can be decided exactly, with VTK's filters:
/// coincident points merged and degenerate triangles dropped (vtkCleanPolyData, exact
/// coincidence only), duplicated triangles removed (by hand: VTK 9.1's vtkRemoveDuplicatePolys
/// leaks), triangles hanging
/// off a non-manifold edge by that edge alone removed (fins), holes up to MaximumHoleRadiusMm
/// filled (vtkFillHolesFilter) and the winding made consistent (vtkPolyDataNormals). Nothing is
/// moved: every point of the output is a point of the input. What cannot be repaired (a hole
/// wider than the limit, two sheets crossing at an edge) stays, and the report's After says so.
///
/// The output holds points and triangles only. GetReport() is valid after Update().
class vtkVesselSurfaceRepair : public vtkPolyDataAlgorithm
{
public:
  static vtkVesselSurfaceRepair* New();
  vtkTypeMacro(vtkVesselSurfaceRepair, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Holes whose rim fits in a sphere of this radius are filled. Default 30 mm: the cut end of
  /// a vena cava where a segmentation stops at the volume's edge (IRCADb's need more than 15).
  /// 0 fills none.
  vtkSetClampMacro(MaximumHoleRadiusMm, double, 0.0, 1.0e6);
  vtkGetMacro(MaximumHoleRadiusMm, double);

  const vp::SurfaceRepairReport& GetReport() const { return this->Report; }

protected:
  vtkVesselSurfaceRepair();
  ~vtkVesselSurfaceRepair() override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkVesselSurfaceRepair(const vtkVesselSurfaceRepair&) = delete;
  void operator=(const vtkVesselSurfaceRepair&) = delete;

  double MaximumHoleRadiusMm = 30.0;
  vp::SurfaceRepairReport Report;
};

#endif
