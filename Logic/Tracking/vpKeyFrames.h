#ifndef vpKeyFrames_h
#define vpKeyFrames_h

#include "vpTrackedFrame.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vp
{
/// A frame worth a picture: its pose's index in the run and why ("warning", "closest_portal_vein").
struct KeyFrame
{
  std::size_t PoseIndex = 0;
  std::string Name;
};

/// Picks, as a run's frames come, the frames a reviewer wants to see: the first and the last, each
/// change of the overall danger level (up to MaximumLevelChanges, the first ones: a tool dithering
/// at a threshold would give hundreds), the closest approach of the tip to each vessel class
/// (inside counts as closer than any outside), the instrument's deepest penetration into each
/// class, and the first pose the tracker lost. Poses are counted in the order given, frames and
/// lost poses together.
class KeyFrameFinder
{
public:
  static constexpr std::size_t MaximumLevelChanges = 12;

  void AddFrame(const TrackedFrame& frame);
  void AddLost();
  /// The key frames in pose order; a pose that is key for several reasons once, its names joined.
  std::vector<KeyFrame> GetKeyFrames() const;
  /// Level changes left out beyond MaximumLevelChanges.
  std::size_t GetLevelChangesLeftOut() const { return this->ChangesLeftOut; }

private:
  std::size_t Poses = 0;
  bool AnyFrame = false;
  std::size_t LastFrame = 0;
  DangerLevel Level = DangerLevel::Safe; ///< the last frame's
  std::size_t Changes = 0, ChangesLeftOut = 0;
  std::multimap<std::size_t, std::string> Keys;
  std::map<std::string, std::pair<double, std::size_t>> Closest; ///< signed mm (inside negative), pose
  std::map<std::string, std::pair<double, std::size_t>> Deepest; ///< depth mm, pose
  bool LostSeen = false;
};
} // namespace vp

#endif
