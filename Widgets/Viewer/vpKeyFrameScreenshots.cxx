#include "vpKeyFrameScreenshots.h"

#include "vtkVesselProximityView.h"

#include <cstdio>
#include <utility>

namespace vp
{
KeyFrameScreenshots::KeyFrameScreenshots(vtkVesselProximityView* view, std::vector<KeyFrame> keys, std::string folder)
  : View(view)
  , Keys(std::move(keys))
  , Folder(std::move(folder))
{
}

void KeyFrameScreenshots::NextPose(double timeS)
{
  const std::size_t pose = this->Pose++;
  if (this->NextKey >= this->Keys.size() || this->Keys[this->NextKey].PoseIndex != pose)
  {
    return;
  }
  const KeyFrame& key = this->Keys[this->NextKey++];
  char name[160];
  std::snprintf(name, sizeof(name), "/frame%04zu_%s.png", pose, key.Name.c_str());
  Shot shot;
  shot.Key = key;
  shot.TimeS = timeS;
  shot.File = this->View->SaveScreenshot(this->Folder + name);
  shot.Picture = this->View->GetLastScreenshot();
  this->Shots.push_back(std::move(shot));
}
} // namespace vp
