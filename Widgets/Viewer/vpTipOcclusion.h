#ifndef vpTipOcclusion_h
#define vpTipOcclusion_h

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <map>
#include <vector>

class vtkActor;
class vtkPolyData;
class vtkRenderer;
class vtkStaticCellLocator;

namespace vp
{
/// Whether surfaces hide a point from a renderer's camera, without rendering: the line of sight
/// from the camera to the point, cut short by a tolerance, against each surface's cells through a
/// vtkStaticCellLocator kept per mesh and rebuilt only when the mesh changes (a tracked tip moves
/// every frame; the vessels do not). A view from a fixed direction asks it each frame.
class TipOcclusion
{
public:
  /// True when one of the actors' surfaces crosses the line of sight to point more than
  /// toleranceMm in front of it (the point's own wall, a tip just inside a vessel, do not count).
  /// Actors whose mapper has no vtkPolyData input are skipped.
  bool Hides(vtkRenderer* renderer, const std::vector<vtkActor*>& actors, const double point[3], double toleranceMm = 3.0);
  /// Meshes with a locator kept (for tests: a second question about the same mesh builds none).
  std::size_t GetNumberOfLocators() const { return this->Locators.size(); }

private:
  struct Kept
  {
    vtkSmartPointer<vtkStaticCellLocator> Locator;
    vtkMTimeType BuiltAt = 0;
  };
  std::map<vtkPolyData*, Kept> Locators;
  vtkStaticCellLocator* LocatorOf(vtkPolyData* mesh);
};
} // namespace vp

#endif
