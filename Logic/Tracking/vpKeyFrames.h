#ifndef vpKeyFrames_h
#define vpKeyFrames_h

#include "vpFrameOutput.h"
#include "vpTrackedFrame.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vp
{
/// A frame worth a picture: its pose's index in the run, why as an identifier for a file name
/// ("warning", "closest_portal_vein") and why in words for a caption ("closest to the portal
/// vein, 0.4 mm").
struct KeyFrame
{
  std::size_t PoseIndex = 0;
  std::string Name;
  std::string Caption;
};

/// Picks, as a run's frames come, the frames a reviewer wants to see: the first and the last, each
/// change of the frame's danger level (the tip's or the whole instrument's, whichever is worse)
/// and of the margin's level (up to MaximumLevelChanges of each, the first ones: a tool dithering
/// at a threshold would give hundreds), the closest approach of the tip to each vessel class and
/// each tumour (inside counts as closer than any outside), the instrument's first contact with
/// each class and its deepest penetration into it, and the first pose the tracker lost. Poses are
/// counted in the order given, frames and lost poses together. Two key frames less than
/// MinimumSpacingS apart at the same levels are one picture, its reasons joined: at the closest or
/// deepest frame where one of them is such (two such at different poses stay two pictures, each
/// caption's number its own frame's), else at the contact, else at the earlier.
///
/// An output of the frame pipeline (vp::FrameOutput): a run adds it to find its key frames.
class KeyFrameFinder : public FrameOutput
{
public:
  static constexpr std::size_t MaximumLevelChanges = 12;
  static constexpr double MinimumSpacingS = 0.5;

  void AddFrame(const TrackedFrame& frame);
  void AddLost();
  void OnFrame(const TrackedFrame& frame) override { this->AddFrame(frame); }
  void OnLost(const TrackedPose&) override { this->AddLost(); }
  /// The key frames in pose order; a pose that is key for several reasons once, its names joined.
  std::vector<KeyFrame> GetKeyFrames() const;
  /// Level changes (danger and margin) left out beyond MaximumLevelChanges.
  std::size_t GetLevelChangesLeftOut() const { return this->ChangesLeftOut; }

  /// Where a key frame stands, to tell whether two near ones show the same thing.
  struct Key
  {
    std::size_t Pose = 0;
    std::string Name, Caption;
    double TimeS = 0.0;
    DangerLevel Level = DangerLevel::Safe;
    int Margin = -1; ///< MarginLevel, -1 without tumours
    bool Lost = false;
    /// Where a merged picture is taken: 3 a measurement's extreme (closest, deepest: its caption
    /// has its pose's number), 2 the instrument's first contact, 1 a level change, 0 start, end.
    int Rank = 0;
  };

private:
  Key At(const TrackedFrame& frame, std::size_t pose, const std::string& name, const std::string& caption, int rank) const;
  void AddLevelChanges(const TrackedFrame& frame, std::size_t pose);
  void AddExtremes(const TrackedFrame& frame, std::size_t pose);

  std::size_t Poses = 0;
  bool AnyFrame = false;
  Key Last;
  DangerLevel Level = DangerLevel::Safe; ///< the last frame's
  int Margin = -1;
  std::size_t Changes = 0, MarginChanges = 0, ChangesLeftOut = 0;
  std::vector<Key> Keys;
  std::map<std::string, std::pair<double, Key>> Extremes; ///< by name: the value to beat and its key
  std::map<std::string, bool> Contact;                    ///< classes the instrument has touched
  bool LostSeen = false;
};
} // namespace vp

#endif
