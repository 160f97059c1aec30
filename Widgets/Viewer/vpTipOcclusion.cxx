#include "vpTipOcclusion.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkMapper.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkStaticCellLocator.h>

#include <cmath>

namespace vp
{
vtkStaticCellLocator* TipOcclusion::LocatorOf(vtkPolyData* mesh)
{
  Kept& kept = this->Locators[mesh];
  if (!kept.Locator || kept.BuiltAt < mesh->GetMTime())
  {
    kept.Locator = vtkSmartPointer<vtkStaticCellLocator>::New();
    kept.Locator->SetDataSet(mesh);
    kept.Locator->BuildLocator();
    kept.BuiltAt = mesh->GetMTime();
  }
  return kept.Locator;
}

bool TipOcclusion::Hides(vtkRenderer* renderer, const std::vector<vtkActor*>& actors, const double point[3], double toleranceMm)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  if (camera->GetParallelProjection())
  {
    // Every line of sight is parallel: the point's starts as far back as the camera is.
    const double back = camera->GetDistance() + std::sqrt(vtkMath::Distance2BetweenPoints(eye, point));
    for (int k = 0; k < 3; ++k)
    {
      eye[k] = point[k] - back * direction[k];
    }
  }
  const double length = std::sqrt(vtkMath::Distance2BetweenPoints(eye, point));
  if (length <= toleranceMm)
  {
    return false;
  }
  // The line of sight stops toleranceMm short of the point.
  double end[3];
  for (int k = 0; k < 3; ++k)
  {
    end[k] = point[k] + (eye[k] - point[k]) * toleranceMm / length;
  }
  for (vtkActor* actor : actors)
  {
    auto* mesh = actor && actor->GetMapper() ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInput()) : nullptr;
    if (!mesh || mesh->GetNumberOfCells() == 0)
    {
      continue;
    }
    // Into the mesh's own coordinates, where the actor is placed by a matrix.
    vtkNew<vtkMatrix4x4> toMesh;
    actor->GetMatrix(toMesh);
    toMesh->Invert();
    double a[4] = { eye[0], eye[1], eye[2], 1.0 }, b[4] = { end[0], end[1], end[2], 1.0 };
    toMesh->MultiplyPoint(a, a);
    toMesh->MultiplyPoint(b, b);
    double t = 0.0, x[3], pcoords[3];
    int subId = 0;
    if (this->LocatorOf(mesh)->IntersectWithLine(a, b, 0.0, t, x, pcoords, subId))
    {
      return true;
    }
  }
  return false;
}
} // namespace vp
