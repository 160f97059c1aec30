#include "vpKeyFrames.h"

#include "vpClassName.h"
#include "vpFrameHeadline.h"
#include "vpInputError.h"

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
std::string Millimetres(double signedMm)
{
  return FixedText(std::abs(signedMm), "%.1f") + (signedMm < 0.0 ? " mm inside" : " mm");
}
} // namespace

KeyFrameFinder::Key KeyFrameFinder::At(
  const TrackedFrame& frame, std::size_t pose, const std::string& name, const std::string& caption, int rank) const
{
  Key key;
  key.Pose = pose;
  key.Name = name;
  key.Caption = caption;
  key.TimeS = frame.TimeS;
  key.Level = frame.Level;
  key.Margin = frame.Tumour ? static_cast<int>(frame.Tumour->Level) : -1;
  key.Rank = rank;
  return key;
}

void KeyFrameFinder::AddFrame(const TrackedFrame& frame)
{
  const std::size_t pose = this->Poses++;
  if (!this->AnyFrame)
  {
    this->Keys.push_back(this->At(frame, pose, "start", "start, " + FrameHeadline(frame), 0));
  }
  else
  {
    this->AddLevelChanges(frame, pose);
  }
  this->AnyFrame = true;
  this->Last = this->At(frame, pose, "end", "end, " + FrameHeadline(frame), 0);
  this->Level = frame.Level;
  this->Margin = frame.Tumour ? static_cast<int>(frame.Tumour->Level) : -1;
  this->AddExtremes(frame, pose);
}

void KeyFrameFinder::AddLevelChanges(const TrackedFrame& frame, std::size_t pose)
{
  if (frame.Level != this->Level)
  {
    if (this->Changes++ < MaximumLevelChanges)
    {
      this->Keys.push_back(this->At(frame, pose, DangerLevelName(frame.Level), DescribeDanger(frame), 1));
    }
    else
    {
      ++this->ChangesLeftOut;
    }
  }
  const int margin = frame.Tumour ? static_cast<int>(frame.Tumour->Level) : -1;
  if (margin != this->Margin && margin >= 0)
  {
    if (this->MarginChanges++ < MaximumLevelChanges)
    {
      this->Keys.push_back(this->At(frame, pose, std::string("margin_") + MarginLevelName(frame.Tumour->Level), DescribeMargin(frame), 1));
    }
    else
    {
      ++this->ChangesLeftOut;
    }
  }
}

void KeyFrameFinder::AddExtremes(const TrackedFrame& frame, std::size_t pose)
{
  // Keeps the key of the smallest value seen under each name.
  const auto lower = [&](const std::string& name, double value, const std::string& caption) {
    const auto it = this->Extremes.find(name);
    if (it == this->Extremes.end() || value < it->second.first)
    {
      this->Extremes[name] = { value, this->At(frame, pose, name, caption, 3) };
    }
  };
  for (std::size_t c = 0; c < frame.Proximity.Classes.size(); ++c)
  {
    const ClassProximity& p = frame.Proximity.Classes[c];
    const std::string vessel = ReadableClassName(p.ClassName);
    if (p.InRange)
    {
      const double signedMm = p.Inside && *p.Inside ? -p.DistanceMm : p.DistanceMm;
      lower("closest_" + p.ClassName, signedMm, "tip closest to the " + vessel + ", " + Millimetres(signedMm));
    }
    const bool inside = c < frame.Penetrations.size() && frame.Penetrations[c].Known && frame.Penetrations[c].VolumeMm3 > 0.0;
    if (inside)
    {
      const double depth = frame.Penetrations[c].DepthMm;
      lower("deepest_" + p.ClassName, -depth, "instrument deepest into the " + vessel + ", " + FixedText(depth, "%.1f") + " mm");
    }
    const bool touching = inside || (c < frame.Surface.size() && frame.Surface[c].InRange && frame.Surface[c].DistanceMm <= 0.0);
    if (touching && !this->Contact[p.ClassName])
    {
      this->Contact[p.ClassName] = true;
      this->Keys.push_back(this->At(frame, pose, "contact_" + p.ClassName, "the instrument's first contact with the " + vessel, 2));
    }
  }
  if (frame.Tumour)
  {
    for (const TumourProximity& t : frame.Tumour->Tumours)
    {
      lower("closest_tumour_" + t.Id, t.SignedMm, "tip closest to " + TumourSpoken(t.Id) + ", " + Millimetres(t.SignedMm));
    }
  }
}

void KeyFrameFinder::AddLost()
{
  const std::size_t pose = this->Poses++;
  if (!this->LostSeen)
  {
    this->LostSeen = true;
    Key key;
    key.Pose = pose;
    key.Name = "tracking_lost";
    key.Caption = "tracking lost";
    key.Lost = true;
    this->Keys.push_back(key);
  }
}

std::vector<KeyFrame> KeyFrameFinder::GetKeyFrames() const
{
  std::vector<Key> keys = this->Keys;
  for (const auto& entry : this->Extremes)
  {
    keys.push_back(entry.second.second);
  }
  if (this->AnyFrame && this->Last.Pose > 0)
  {
    keys.push_back(this->Last);
  }
  std::stable_sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.Pose < b.Pose; });
  // One picture for near keys showing the same levels; a level change is never merged across.
  std::vector<Key> kept;
  for (const Key& k : keys)
  {
    Key* previous = kept.empty() ? nullptr : &kept.back();
    const bool same = previous && !k.Lost && !previous->Lost && k.Level == previous->Level && k.Margin == previous->Margin;
    // Two extremes at different poses keep a picture each: each caption's number is its pose's.
    const bool twoExtremes = previous && k.Rank == 3 && previous->Rank == 3;
    if (previous && (previous->Pose == k.Pose || (same && !twoExtremes && k.TimeS - previous->TimeS < MinimumSpacingS)))
    {
      previous->Name += "_" + k.Name;
      previous->Caption += "; " + k.Caption;
      if (k.Rank > previous->Rank)
      {
        previous->Pose = k.Pose;
        previous->TimeS = k.TimeS;
        previous->Rank = k.Rank;
      }
      continue;
    }
    kept.push_back(k);
  }
  std::vector<KeyFrame> frames;
  for (const Key& k : kept)
  {
    frames.push_back({ k.Pose, k.Name, k.Caption });
  }
  return frames;
}
} // namespace vp
