#ifndef vpKeyFrameShots_h
#define vpKeyFrameShots_h

#include "vpKeyFrameScreenshots.h"
#include "vpKeyFrames.h"
#include "vpPoseFile.h"
#include "vtkVesselProximityView.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkPolyData;
class vtkVesselProximityLogic;

namespace vp
{
class ModuleServices;

/// Pictures of a run's key frames (vp::KeyFrameFinder): the poses replayed through an off-screen
/// view of the logic with the module's overlays, a screenshot at each key frame
/// (vp::KeyFrameScreenshots: folder/frameNNNN_<name>.png) and, when asked, a contact sheet of
/// them all, captioned with time and reason. Needs a display (the caller makes sure of one).
struct KeyFrameShotRequest
{
  vtkVesselProximityLogic* Logic = nullptr; ///< its scene open
  vtkPolyData* Liver = nullptr;             ///< may be null
  std::vector<TrackedPose> Poses;
  std::vector<KeyFrame> Keys;
  vtkVesselProximityView::CameraPreset Camera = vtkVesselProximityView::CameraPreset::Anterior;
  std::string Folder;            ///< where the screenshots go
  std::string ContactSheetFile;  ///< the contact sheet (keyframes.png); empty: none
};

/// An off-screen view of the logic (its scene open) with the module's overlays, 1280 x 800, the
/// liver (may be null) translucent: where a command's pictures are taken.
vtkSmartPointer<vtkVesselProximityView> OffScreenView(const ModuleServices& module, vtkVesselProximityLogic* logic, vtkPolyData* liver);

/// The screenshots taken, in pose order.
std::vector<KeyFrameScreenshots::Shot> RenderKeyFrameShots(const ModuleServices& module, const KeyFrameShotRequest& request);
} // namespace vp

#endif
