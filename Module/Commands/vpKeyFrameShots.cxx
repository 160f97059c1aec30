#include "vpKeyFrameShots.h"

#include "vpContactSheet.h"
#include "vpModuleServices.h"
#include "vpPngFile.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityOverlays.h"

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include <cstdio>

namespace vp
{
vtkSmartPointer<vtkVesselProximityView> OffScreenView(const ModuleServices& module, vtkVesselProximityLogic* logic, vtkPolyData* liver)
{
  auto view = vtkSmartPointer<vtkVesselProximityView>::New();
  view->SetOverlays(module.CreateWidgetRepresentation());
  view->SetOffScreen(true);
  view->SetSizePx(1280, 800);
  view->SetLogic(logic);
  if (liver)
  {
    view->SetLiverSurface(liver);
  }
  return view;
}

std::vector<KeyFrameScreenshots::Shot> RenderKeyFrameShots(const ModuleServices& module, const KeyFrameShotRequest& request)
{
  vtkSmartPointer<vtkVesselProximityView> view = OffScreenView(module, request.Logic, request.Liver);
  view->SetCameraPreset(request.Camera);
  if (request.Camera == vtkVesselProximityView::CameraPreset::Anterior)
  {
    // Turned a little to the patient's right and down from above, as the demo's pictures: the
    // scalpel comes in at an angle, not end-on.
    vtkCamera* camera = view->GetRenderer()->GetActiveCamera();
    camera->Azimuth(-35);
    camera->Elevation(25);
    camera->OrthogonalizeViewUp();
    view->GetRenderer()->ResetCameraClippingRange();
  }
  view->SetPoses(request.Poses);
  // The poses run through the view's session up to the last key, every one of them so that the
  // plot shows the way there; the screenshots are an output of that run.
  KeyFrameScreenshots shots(view, request.Keys, request.Folder);
  view->AddOutput(&shots);
  if (!request.Keys.empty())
  {
    view->ReplayTo(static_cast<int>(shots.GetLastKeyPose()));
  }
  if (!request.ContactSheetFile.empty())
  {
    std::vector<ContactSheetEntry> sheet;
    for (const KeyFrameScreenshots::Shot& shot : shots.GetShots())
    {
      char caption[400];
      std::snprintf(caption, sizeof(caption), "%.2f s: %s", shot.TimeS, shot.Key.Caption.c_str());
      sheet.push_back({ shot.Picture, caption });
    }
    WritePngAtomically(MakeContactSheet(sheet), request.ContactSheetFile);
  }
  return shots.GetShots();
}
} // namespace vp
