#ifndef vpKeyFrameScreenshots_h
#define vpKeyFrameScreenshots_h

#include "vpFrameOutput.h"
#include "vpKeyFrames.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkVesselProximityView;

namespace vp
{
/// An output of the frame pipeline that photographs a run's key frames (vp::KeyFrameFinder, from
/// an earlier run of the same poses): added to a view (vtkVesselProximityView::AddOutput), it
/// counts the poses as they come, frames and losses alike, and at each key pose saves the view as
/// folder/frameNNNN_<name>.png, the overlays already showing that pose.
class KeyFrameScreenshots : public FrameOutput
{
public:
  /// view outlives the output; keys in pose order.
  KeyFrameScreenshots(vtkVesselProximityView* view, std::vector<KeyFrame> keys, std::string folder);

  void OnFrame(const TrackedFrame& frame) override { this->NextPose(frame.TimeS); }
  void OnLost(const TrackedPose& pose) override { this->NextPose(pose.TimeS); }

  struct Shot
  {
    KeyFrame Key;
    double TimeS = 0.0;
    std::string File;
    vtkSmartPointer<vtkImageData> Picture; ///< as written (RGB)
  };
  /// The pictures taken so far, in pose order.
  const std::vector<Shot>& GetShots() const { return this->Shots; }
  /// The last key's pose: a replay need go no further.
  std::size_t GetLastKeyPose() const { return this->Keys.empty() ? 0 : this->Keys.back().PoseIndex; }

private:
  void NextPose(double timeS);

  vtkVesselProximityView* View;
  std::vector<KeyFrame> Keys;
  std::string Folder;
  std::vector<Shot> Shots;
  std::size_t Pose = 0;
  std::size_t NextKey = 0;
};
} // namespace vp

#endif
