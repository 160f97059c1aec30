#include "vpFrameHeadline.h"

#include "vpClassName.h"
#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace vp
{
namespace
{
std::string Upper(std::string text)
{
  for (char& c : text)
  {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return text;
}

std::string Millimetres(double mm)
{
  return FixedText(mm, "%.1f") + " mm";
}

/// The danger levels' rank of a margin level.
DangerLevel RankOf(MarginLevel level)
{
  switch (level)
  {
    case MarginLevel::Clear:
      return DangerLevel::Safe;
    case MarginLevel::Near:
      return DangerLevel::Warning;
    case MarginLevel::Violated:
      return DangerLevel::Danger;
    case MarginLevel::Inside:
      return DangerLevel::Breach;
  }
  return DangerLevel::Safe;
}

/// "instrument 1.0 mm into the hepatic vein" or "instrument 0.4 mm from the portal vein".
std::string InstrumentCause(const TrackedFrame& frame, std::size_t c, const std::string& vessel)
{
  const SurfaceProximity& s = frame.Surface[c];
  const bool inside = c < frame.Penetrations.size() && frame.Penetrations[c].Known &&
    (frame.Penetrations[c].VolumeMm3 > 0.0 || frame.Penetrations[c].DepthMm > 0.0);
  if (inside)
  {
    return "instrument " + Millimetres(frame.Penetrations[c].DepthMm) + " into the " + vessel;
  }
  if (c < frame.Penetrations.size() && !frame.Penetrations[c].Known && s.DistanceMm <= s.ErrorBoundMm)
  {
    return "instrument touching the " + vessel + " (inside unknown: an open surface)";
  }
  return "instrument " + Millimetres(s.DistanceMm) + " from the " + vessel;
}

/// "tip 0.6 mm inside the portal vein" or "tip 1.2 mm from the portal vein".
std::string TipCause(const ClassProximity& p, const std::string& vessel)
{
  if (p.InsideUncertain)
  {
    return "tip " + Millimetres(p.DistanceMm) + " from the " + vessel + " wall (inside unknown: an open surface)";
  }
  return "tip " + Millimetres(p.DistanceMm) + (p.Inside.value_or(false) ? " inside the " : " from the ") + vessel;
}
} // namespace

std::string ReadableClassName(std::string name)
{
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

std::string DescribeDanger(const TrackedFrame& frame)
{
  const std::string level = Upper(DangerLevelName(frame.Level));
  if (frame.LevelClass < 0)
  {
    return level;
  }
  const auto c = static_cast<std::size_t>(frame.LevelClass);
  const std::string vessel = ReadableClassName(frame.Proximity.Classes[c].ClassName);
  return level + ": " +
    (frame.LevelCause == DangerCause::Instrument ? InstrumentCause(frame, c, vessel)
                                                 : TipCause(frame.Proximity.Classes[c], vessel));
}

std::string DescribeMargin(const TrackedFrame& frame)
{
  if (!frame.Tumour || frame.Tumour->Worst < 0)
  {
    return "";
  }
  const TumourProximity& t = frame.Tumour->Tumours[static_cast<std::size_t>(frame.Tumour->Worst)];
  switch (frame.Tumour->Level)
  {
    case MarginLevel::Inside:
      return "INSIDE TUMOUR: " + TumourSpoken(t.Id) + ", " + Millimetres(std::abs(t.SignedMm)) + " in";
    case MarginLevel::Violated:
      return "MARGIN VIOLATED: " + TumourSpoken(t.Id) + ", " + Millimetres(t.SignedMm);
    case MarginLevel::Near:
      return "MARGIN NEAR: " + TumourSpoken(t.Id) + ", " + Millimetres(t.SignedMm);
    case MarginLevel::Clear:
      return "MARGIN CLEAR";
  }
  return "";
}

bool MarginOutranksDanger(const TrackedFrame& frame)
{
  return frame.Tumour && frame.Tumour->Worst >= 0 && RankOf(frame.Tumour->Level) > frame.Level;
}

std::string FrameHeadline(const TrackedFrame& frame)
{
  return MarginOutranksDanger(frame) ? DescribeMargin(frame) : DescribeDanger(frame);
}
} // namespace vp
