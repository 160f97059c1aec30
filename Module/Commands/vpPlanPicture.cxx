#include "vpPlanPicture.h"

#include "vpDangerLevels.h"
#include "vpKeyFrameShots.h"
#include "vpModuleServices.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityOverlays.h"
#include "vtkVesselProximityView.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTubeFilter.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vp
{
namespace
{
/// The tip's path along an approach as a tube, each pose's point in its danger level's colour.
vtkSmartPointer<vtkActor> PathActor(const PlannedApproach& approach, double radiusMm)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetName("level");
  const double lengthMm = std::sqrt(std::pow(approach.EndMm[0] - approach.EntryMm[0], 2) +
    std::pow(approach.EndMm[1] - approach.EntryMm[1], 2) + std::pow(approach.EndMm[2] - approach.EntryMm[2], 2));
  const std::size_t n = std::max<std::size_t>(approach.StepLevels.size(), 2);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double s = lengthMm * static_cast<double>(i) / static_cast<double>(n - 1);
    points->InsertNextPoint(approach.EntryMm[0] + s * approach.Direction[0], approach.EntryMm[1] + s * approach.Direction[1],
      approach.EntryMm[2] + s * approach.Direction[2]);
    const DangerLevel level = approach.StepLevels.empty() ? DangerLevel::Safe : approach.StepLevels[std::min(i, approach.StepLevels.size() - 1)];
    const std::array<unsigned char, 3> c = DangerLevelColour(level);
    colours->InsertNextTypedTuple(c.data());
  }
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    line->InsertCellPoint(static_cast<vtkIdType>(i));
  }
  vtkNew<vtkPolyData> path;
  path->SetPoints(points);
  path->SetLines(line);
  path->GetPointData()->SetScalars(colours);
  vtkNew<vtkTubeFilter> tube;
  tube->SetInputData(path);
  tube->SetRadius(radiusMm);
  tube->SetNumberOfSides(16);
  tube->CappingOn();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(tube->GetOutputPort());
  mapper->SetColorModeToDirectScalars();
  mapper->SetScalarModeToUsePointData();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// The camera across the path (from the patient's front when the path is not front to back,
/// else from the side), framed on the path and the target.
void LookAcross(vtkRenderer* renderer, const PlannedApproach& approach, vtkPolyData* target)
{
  const std::array<double, 3>& d = approach.Direction;
  std::array<double, 3> view{ 0, -1, 0 }; // anterior, LPS
  if (std::abs(d[1]) > 0.9)
  {
    view = { -1, 0, 0 }; // the patient's right
  }
  const double along = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
  for (int a = 0; a < 3; ++a)
  {
    view[a] -= along * d[a];
  }
  double bounds[6];
  target->GetBounds(bounds);
  for (const std::array<double, 3>& p : { approach.EntryMm, approach.EndMm })
  {
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], p[a] - 10.0);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], p[a] + 10.0);
    }
  }
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2 };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + view[0], centre[1] + view[1], centre[2] + view[2]);
  camera->SetViewUp(0.0, 0.0, 1.0); // superior up, as the module's anterior view
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera(bounds);
  renderer->ResetCameraClippingRange();
}

std::string Caption(const ApproachPlan& plan)
{
  char text[600];
  const PlannedApproach& a = plan.Asked;
  std::snprintf(text, sizeof text, "plan: %s, %zu poses %.3g mm apart\nclearance %.2f mm%s%s%s", plan.TargetName.c_str(),
    a.Poses.size(), plan.StepMm, a.ClearanceMm, a.ClearanceClass.empty() ? " (no vessel in range)" : " (",
    a.ClearanceClass.c_str(), a.ClearanceClass.empty() ? "" : ")");
  std::string caption = text;
  if (plan.Safest && plan.Safest->AngleFromAskedDeg > 0.0)
  {
    std::snprintf(text, sizeof text, "\nsafest (thin), %.1f deg off: %.2f mm", plan.Safest->AngleFromAskedDeg, plan.Safest->ClearanceMm);
    caption += text;
  }
  else if (plan.Safest)
  {
    std::snprintf(text, sizeof text, "\nno safer direction within %.3g deg", plan.SearchDeg);
    caption += text;
  }
  return caption;
}
} // namespace

void RenderPlanPicture(const ModuleServices& module, const PlanPictureRequest& request)
{
  const ApproachPlan& plan = *request.Plan;
  vtkSmartPointer<vtkVesselProximityView> view = OffScreenView(module, request.Logic, request.Liver);
  // The instrument at the entry, its path ahead of it in sight (at a later pose its shaft would
  // hide the path behind the tip).
  view->SetPoses(plan.Asked.Poses);
  view->ReplayTo(0);
  vtkRenderer* renderer = view->GetRenderer();
  renderer->AddActor(PathActor(plan.Asked, 0.8));
  if (plan.Safest && plan.Safest->AngleFromAskedDeg > 0.0)
  {
    renderer->AddActor(PathActor(*plan.Safest, 0.4));
  }
  vtkNew<vtkTextActor> caption;
  caption->SetInput(Caption(plan).c_str());
  // Top right: the readout holds the top left, the orientation marker and the plot the bottom.
  caption->GetTextProperty()->SetFontSize(18);
  caption->GetTextProperty()->SetJustificationToRight();
  caption->GetTextProperty()->SetVerticalJustificationToTop();
  caption->SetDisplayPosition(1268, 788);
  renderer->AddActor2D(caption);
  LookAcross(renderer, plan.Asked, request.Target);
  view->SaveScreenshot(request.File);
}
} // namespace vp
