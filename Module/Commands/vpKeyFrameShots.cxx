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
std::vector<std::string> RenderKeyFrameShots(const ModuleServices& module, const KeyFrameShotRequest& request)
{
  vtkNew<vtkVesselProximityView> view;
  view->SetOverlays(module.CreateWidgetRepresentation());
  view->SetOffScreen(true);
  view->SetSizePx(1280, 800);
  view->SetLogic(request.Logic);
  if (request.Liver)
  {
    view->SetLiverSurface(request.Liver);
  }
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
  std::vector<std::string> files;
  std::vector<ContactSheetEntry> sheet;
  std::size_t next = 0;
  for (std::size_t i = 0; i < request.Poses.size() && next < request.Keys.size(); ++i)
  {
    view->ShowPose(static_cast<int>(i)); // every pose, so that the plot shows the way there
    if (i != request.Keys[next].PoseIndex)
    {
      continue;
    }
    char name[160];
    std::snprintf(name, sizeof(name), "/frame%04zu_%s.png", i, request.Keys[next].Name.c_str());
    files.push_back(view->SaveScreenshot(request.Folder + name));
    char caption[400];
    std::snprintf(caption, sizeof(caption), "%.2f s: %s", request.Poses[i].TimeS, request.Keys[next].Caption.c_str());
    sheet.push_back({ view->GetLastScreenshot(), caption });
    ++next;
  }
  WritePngAtomically(MakeContactSheet(sheet), request.ContactSheetFile);
  return files;
}
} // namespace vp
