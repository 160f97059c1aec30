#include "vpLiveResults.h"

#include "vpText.h"

#include "vpFrameHeadline.h"
#include "vpIgtlMessages.h"

#include <nlohmann/json.hpp>

#include <cctype>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

/// LPS (ours) to RAS (what a Slicer peer shows).
Json RasJson(const double p[3])
{
  return Json::array({ -p[0], -p[1], p[2] });
}

std::array<double, 3> Ras(const double p[3])
{
  return { -p[0], -p[1], p[2] };
}

Json HapticJson(const HapticSample& h)
{
  return { { "force_n", h.ForceN }, { "direction", RasJson(h.Direction) }, { "depth_mm", h.DepthMm }, { "rate_mm_s", h.RateMmPerS } };
}

/// The margin's level, the tumour that sets it, and every tumour's signed distance and level.
Json TumourJson(const TumourMargin& margin)
{
  const TumourProximity& worst = margin.Tumours[static_cast<std::size_t>(margin.Worst)];
  Json tumours = Json::object();
  for (const TumourProximity& t : margin.Tumours)
  {
    tumours[t.Id] = { { "tumour_mm", t.SignedMm }, { "level", MarginLevelName(t.Level) }, { "point", RasJson(t.ClosestPoint) },
      { "surface_mm", t.SurfaceKnown ? Json(t.SurfaceMm) : Json(nullptr) } };
  }
  return { { "level", MarginLevelName(margin.Level) }, { "id", worst.Id }, { "tumour_mm", worst.SignedMm },
    { "tumours", tumours } };
}

std::array<unsigned char, 4> Rgba(DangerLevel level)
{
  const auto c = DangerLevelColour(level);
  return { c[0], c[1], c[2], 255 };
}

/// Stamped now: the reply's time.
IgtlPacking Now()
{
  return IgtlStampedAt(IgtlWallClockS());
}

/// Each class in range: its closest point as a TRANSFORM's translation and as a one-point POINT.
std::string PackClassMessages(const TrackedFrame& frame, const IgtlPacking& packing)
{
  std::string packed;
  for (std::size_t c = 0; c < frame.Proximity.Classes.size(); ++c)
  {
    const ClassProximity& p = frame.Proximity.Classes[c];
    if (!p.InRange)
    {
      continue;
    }
    const std::array<double, 3> ras = Ras(p.ClosestPoint);
    const std::array<double, 16> placed = { 1, 0, 0, ras[0], 0, 1, 0, ras[1], 0, 0, 1, ras[2], 0, 0, 0, 1 };
    packed += PackIgtlTransform(LiveClassDevice(p.ClassName, live::ClosestSuffix), placed, packing);
    const DangerLevel level = c < frame.ClassLevels.size() ? frame.ClassLevels[c] : DangerLevel::Safe;
    packed += PackIgtlPoints(LiveClassDevice(p.ClassName, live::PointSuffix), { { p.ClassName, "closest", Rgba(level), ras, 1.0, "" } }, packing);
  }
  return packed;
}
} // namespace

std::string LiveClassDevice(const std::string& className, const char* suffix)
{
  const std::string camel = CamelCase(className, true);
  const std::size_t room = IgtlDeviceNameBytes - std::char_traits<char>::length(suffix);
  return camel.substr(0, room) + suffix;
}

std::string LiveFrameJson(const TrackedFrame& frame)
{
  const ProximityResult& r = frame.Proximity;
  Json out;
  out["state"] = "tracking";
  out["frame"] = frame.Frame;
  out["time"] = frame.TimeS;
  out["space"] = "RAS";
  out["tip"] = RasJson(frame.TipMm);
  out["level"] = DangerLevelName(frame.Level);
  out["level_class"] = frame.LevelClass >= 0 ? Json(r.Classes[static_cast<std::size_t>(frame.LevelClass)].ClassName) : Json(nullptr);
  out["level_cause"] = frame.LevelClass >= 0 ? Json(DangerCauseName(frame.LevelCause)) : Json(nullptr);
  out["headline"] = FrameHeadline(frame); // the worse of the vessel level and the margin level, said
  out["tip_level"] = DangerLevelName(frame.TipLevel);
  out["instrument_level"] = frame.InstrumentClassLevels.empty() ? Json(nullptr) : Json(DangerLevelName(frame.InstrumentLevel));
  out["error_bound_mm"] = r.ErrorBoundMm;
  const int nearest = r.NearestIndex();
  out["nearest"] = nearest >= 0 ? Json{ { "class", r.Classes[static_cast<std::size_t>(nearest)].ClassName },
                                     { "distance_mm", r.Classes[static_cast<std::size_t>(nearest)].DistanceMm } }
                                 : Json(nullptr);
  Json classes = Json::object();
  for (std::size_t c = 0; c < r.Classes.size(); ++c)
  {
    const ClassProximity& p = r.Classes[c];
    Json entry;
    entry["distance_mm"] = p.InRange ? Json(p.DistanceMm) : Json(nullptr);
    entry["inside"] = p.Inside ? Json(*p.Inside) : Json(nullptr);
    entry["level"] = DangerLevelName(frame.ClassLevel(c));
    entry["tip_level"] = c < frame.ClassLevels.size() ? DangerLevelName(frame.ClassLevels[c]) : "safe";
    entry["instrument_level"] =
      c < frame.InstrumentClassLevels.size() ? Json(DangerLevelName(frame.InstrumentClassLevels[c])) : Json(nullptr);
    entry["point"] = p.InRange ? RasJson(p.ClosestPoint) : Json(nullptr);
    entry["surface_mm"] = c < frame.Surface.size() && frame.Surface[c].InRange ? Json(frame.Surface[c].DistanceMm) : Json(nullptr);
    const bool known = c < frame.Penetrations.size() && frame.Penetrations[c].Known;
    entry["penetration_depth_mm"] = known ? Json(frame.Penetrations[c].DepthMm) : Json(nullptr);
    entry["penetration_volume_mm3"] = known ? Json(frame.Penetrations[c].VolumeMm3) : Json(nullptr);
    classes[p.ClassName] = entry;
  }
  out["classes"] = classes;
  if (frame.Haptic)
  {
    out["haptic"] = HapticJson(*frame.Haptic);
  }
  if (frame.Tumour && frame.Tumour->Worst >= 0)
  {
    out["tumour"] = TumourJson(*frame.Tumour);
  }
  return out.dump();
}

std::string PackLiveFrame(const TrackedFrame& frame)
{
  std::vector<IgtlPoint> points;
  points.push_back({ "tip", "scalpel", Rgba(frame.Level), Ras(frame.TipMm), 1.0, "" });
  for (std::size_t c = 0; c < frame.Proximity.Classes.size(); ++c)
  {
    const ClassProximity& p = frame.Proximity.Classes[c];
    if (p.InRange)
    {
      points.push_back({ p.ClassName, "closest", Rgba(c < frame.ClassLevels.size() ? frame.ClassLevels[c] : DangerLevel::Safe),
        Ras(p.ClosestPoint), 1.0, "" });
    }
  }
  if (frame.Tumour && frame.Tumour->Worst >= 0)
  {
    // The nearest tumour point, coloured as the danger level it would be for a vessel at that distance.
    const TumourProximity& t = frame.Tumour->Tumours[static_cast<std::size_t>(frame.Tumour->Worst)];
    points.push_back({ t.Id, "tumour", Rgba(frame.Tumour->Level >= MarginLevel::Violated ? DangerLevel::Danger
                                              : frame.Tumour->Level == MarginLevel::Near ? DangerLevel::Caution
                                                                                          : DangerLevel::Safe),
      Ras(t.ClosestPoint), 1.0, "" });
  }
  // The pose's own time stamp when its source gave one (PLUS does), else the reply's.
  const IgtlPacking packing = frame.SourceClockS > 0.0 ? IgtlStampedAt(frame.SourceClockS) : Now();
  std::string packed = PackIgtlString(live::FrameDevice, LiveFrameJson(frame), 3, packing) +
    PackIgtlPoints(live::PointsDevice, points, packing) + PackClassMessages(frame, packing);
  if (frame.Haptic)
  {
    packed += PackIgtlString(live::HapticDevice, HapticJson(*frame.Haptic).dump(), 3, packing);
  }
  return packed;
}

std::string PackLiveLost(double timeS, double sincePoseMs)
{
  const Json out = { { "state", "lost" }, { "time", timeS }, { "since_pose_ms", sincePoseMs } };
  return PackIgtlString(live::FrameDevice, out.dump(), 3, Now());
}

std::string PackLiveStatus(bool tracking)
{
  IgtlStatus status;
  status.Code = tracking ? 1 : 16; // OpenIGTLink's STATUS_OK, STATUS_NOT_PRESENT
  status.ErrorName = tracking ? "" : "TrackingLost";
  status.Text = tracking ? "Tracking" : "Tracking lost: no pose of the tool";
  return PackIgtlStatus(live::StatusDevice, status, Now());
}

std::string PackLiveLevelChange(const DangerLevelChange& change)
{
  const Json out = { { "kind", "vessel" }, { "frame", change.Frame }, { "time", change.TimeS },
    { "from", DangerLevelName(change.From) }, { "to", DangerLevelName(change.To) },
    { "class", change.ClassName.empty() ? Json(nullptr) : Json(change.ClassName) },
    { "cause", change.ClassName.empty() ? Json(nullptr) : Json(DangerCauseName(change.Cause)) },
    { "distance_mm", change.DistanceMm } };
  return PackIgtlString(live::LevelDevice, out.dump(), 3, Now());
}

std::string PackLiveMarginChange(const MarginLevelChange& change)
{
  const Json out = { { "kind", "margin" }, { "frame", change.Frame }, { "time", change.TimeS },
    { "from", MarginLevelName(change.From) }, { "to", MarginLevelName(change.To) },
    { "tumour", change.TumourId.empty() ? Json(nullptr) : Json(change.TumourId) }, { "tumour_mm", change.SignedMm } };
  return PackIgtlString(live::LevelDevice, out.dump(), 3, Now());
}

std::string LiveDeviceNameClash(const std::vector<std::string>& classNames)
{
  for (const char* suffix : { live::ClosestSuffix, live::PointSuffix })
  {
    for (const std::string& className : classNames)
    {
      const std::string device = LiveClassDevice(className, suffix);
      for (const char* fixed : { live::FrameDevice, live::LevelDevice, live::HapticDevice, live::PointsDevice, live::StatusDevice })
      {
        if (device == fixed)
        {
          return "class '" + className + "' would be sent as " + device + ", the name of the session's own " +
            "messages: name the class otherwise";
        }
      }
    }
    for (std::size_t i = 0; i < classNames.size(); ++i)
    {
      for (std::size_t j = i + 1; j < classNames.size(); ++j)
      {
        if (LiveClassDevice(classNames[i], suffix) == LiveClassDevice(classNames[j], suffix))
        {
          return "classes '" + classNames[i] + "' and '" + classNames[j] + "' would both be sent as " +
            LiveClassDevice(classNames[i], suffix) + " (an OpenIGTLink device name is at most 20 bytes): one's closest "
            "point would overwrite the other's in Slicer; name them apart in their first " +
            std::to_string(IgtlDeviceNameBytes - std::char_traits<char>::length(suffix)) + " letters";
        }
      }
    }
  }
  return std::string();
}

Json LiveLatencyJson(const RunningQuantiles& latencyMs)
{
  if (latencyMs.Count() == 0)
  {
    return nullptr;
  }
  return { { "median", latencyMs.Quantile(0.5) }, { "p95", latencyMs.Quantile(0.95) }, { "max", latencyMs.Quantile(1.0) },
    { "frames", latencyMs.Count() } };
}

Json LiveLinkJson(const IgtlLinkCounts& counts)
{
  Json out;
  out["messages"] = counts.Messages;
  out["poses"] = counts.Poses;
  out["poses_not_seen_by_the_tracker"] = counts.NotSeen;
  out["poses_dropped"] = counts.Dropped;
  out["rejected"] = counts.Rejected;
  out["ignored"] = counts.Ignored;
  out["connections"] = counts.Connections;
  out["connections_lost"] = counts.ConnectionsLost;
  out["send_failures"] = counts.SendFailures;
  out["version_2_peers"] = counts.Version2Peers;
  return out;
}
} // namespace vp
