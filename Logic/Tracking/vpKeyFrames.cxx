#include "vpKeyFrames.h"

namespace vp
{
void KeyFrameFinder::AddFrame(const TrackedFrame& frame)
{
  const std::size_t pose = this->Poses++;
  if (!this->AnyFrame)
  {
    this->Keys.emplace(pose, "start");
  }
  else if (frame.Level != this->Level)
  {
    if (this->Changes++ < MaximumLevelChanges)
    {
      this->Keys.emplace(pose, DangerLevelName(frame.Level));
    }
    else
    {
      ++this->ChangesLeftOut;
    }
  }
  this->AnyFrame = true;
  this->LastFrame = pose;
  this->Level = frame.Level;
  for (std::size_t c = 0; c < frame.Proximity.Classes.size(); ++c)
  {
    const ClassProximity& p = frame.Proximity.Classes[c];
    if (p.InRange)
    {
      const double signedMm = p.Inside && *p.Inside ? -p.DistanceMm : p.DistanceMm;
      const auto it = this->Closest.find(p.ClassName);
      if (it == this->Closest.end() || signedMm < it->second.first)
      {
        this->Closest[p.ClassName] = { signedMm, pose };
      }
    }
    if (c < frame.Penetrations.size() && frame.Penetrations[c].Known && frame.Penetrations[c].VolumeMm3 > 0.0)
    {
      const auto it = this->Deepest.find(p.ClassName);
      if (it == this->Deepest.end() || frame.Penetrations[c].DepthMm > it->second.first)
      {
        this->Deepest[p.ClassName] = { frame.Penetrations[c].DepthMm, pose };
      }
    }
  }
}

void KeyFrameFinder::AddLost()
{
  const std::size_t pose = this->Poses++;
  if (!this->LostSeen)
  {
    this->LostSeen = true;
    this->Keys.emplace(pose, "tracking_lost");
  }
}

std::vector<KeyFrame> KeyFrameFinder::GetKeyFrames() const
{
  std::multimap<std::size_t, std::string> keys = this->Keys;
  for (const auto& [name, entry] : this->Closest)
  {
    keys.emplace(entry.second, "closest_" + name);
  }
  for (const auto& [name, entry] : this->Deepest)
  {
    keys.emplace(entry.second, "deepest_" + name);
  }
  if (this->AnyFrame && this->LastFrame > 0)
  {
    keys.emplace(this->LastFrame, "end");
  }
  std::vector<KeyFrame> frames;
  for (const auto& [pose, name] : keys)
  {
    if (!frames.empty() && frames.back().PoseIndex == pose)
    {
      frames.back().Name += "_" + name;
    }
    else
    {
      frames.push_back({ pose, name });
    }
  }
  return frames;
}
} // namespace vp
