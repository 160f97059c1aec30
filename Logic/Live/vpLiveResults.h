#ifndef vpLiveResults_h
#define vpLiveResults_h

#include "vpIgtlLink.h"
#include "vpRunningQuantiles.h"
#include "vpTrackedFrame.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace vp
{
/// The device names of what a live session sends back, as 3D Slicer's OpenIGTLinkIF makes
/// nodes of them with no code of its own: a text node of the frame, a point list of the tip and
/// the closest points.
namespace live
{
/// STRING: every frame as JSON (LiveFrameJson), and {"state": "lost", ...} when tracking is lost.
constexpr const char* FrameDevice = "VesselProximity";
/// STRING: each change of the overall danger level, as JSON, when it happens.
constexpr const char* LevelDevice = "VesselProximityLevel";
/// STRING: with haptics on, each frame's force for a haptic device's bridge: {"force_n",
/// "direction" (unit, RAS), "depth_mm", "rate_mm_s"}.
constexpr const char* HapticDevice = "VesselProximityForce";
/// POINT: "tip", then per class in range its closest point (named for the class), RAS, mm,
/// coloured by the class's level; with tumours, last, the closest point of the tumour that sets
/// the margin's level (named for the tumour, group "tumour"), coloured as the danger level of a
/// vessel that near: danger when the margin is violated or the tip inside, caution when near.
constexpr const char* PointsDevice = "VesselProximityPoint";
/// STATUS: the tracking state when it changes: code 1 (OK, "Tracking") from the first frame and
/// after a loss, code 16 (not present, "TrackingLost") when tracking is lost.
constexpr const char* StatusDevice = "VesselProximity";
/// Per class in range, as SlicerIGT scenes are built: a TRANSFORM "<Class>Closest" whose
/// translation places the class's closest point (RAS, mm; no rotation), to attach a marker or a
/// model to, and a POINT "<Class>Point" of that point alone, coloured by the class's level (Slicer
/// colours a point list by its first point). <Class> is the class's name in CamelCase, cut to fit
/// 20 bytes with the suffix: PortalVeinClosest, HepaticArteryClosest, HepaticVeinClosest,
/// PortalVeinPoint, HepaticArteryPoint, HepaticVeinPoint (LiveClassDevice).
constexpr const char* ClosestSuffix = "Closest";
constexpr const char* PointSuffix = "Point";
// OpenIGTLink gives a device name 20 bytes: a longer one reaches the peer cut.
static_assert(std::char_traits<char>::length(FrameDevice) <= IgtlDeviceNameBytes);
static_assert(std::char_traits<char>::length(LevelDevice) <= IgtlDeviceNameBytes);
static_assert(std::char_traits<char>::length(HapticDevice) <= IgtlDeviceNameBytes);
static_assert(std::char_traits<char>::length(PointsDevice) <= IgtlDeviceNameBytes);
} // namespace live

/// One frame as the peer reads it: {"state": "tracking", "frame", "time", "space": "RAS", "tip",
/// "level", "level_class", "error_bound_mm", "nearest": {"class", "distance_mm"} or null,
/// "classes": {"<class>": {"distance_mm", "inside", "level", "point", "surface_mm",
/// "penetration_depth_mm", "penetration_volume_mm3"}}, with haptics on "haptic" (as the
/// VesselProximityForce message), and with tumours "tumour": {"level" (the margin's), "id" and
/// "tumour_mm" of the tumour that sets it, "tumours": {"<id>": {"tumour_mm" (negative inside),
/// "level", "point", "surface_mm"}}}: points in RAS (what Slicer shows), null
/// where a class is out of range or a quantity was not computed.
std::string LiveFrameJson(const TrackedFrame& frame);
/// A class's device name with a suffix (live::ClosestSuffix, live::PointSuffix), within 20 bytes.
std::string LiveClassDevice(const std::string& className, const char* suffix);
/// The frame's messages, packed: the STRING, the POINT list, each class's TRANSFORM and POINT,
/// and with haptics on the force. Every message is stamped with the time it is packed (the
/// reply's time, UTC).
std::string PackLiveFrame(const TrackedFrame& frame);
/// Tracking lost: {"state": "lost", "time", "since_pose_ms"}.
std::string PackLiveLost(double timeS, double sincePoseMs);
/// The tracking state as a STATUS (live::StatusDevice).
std::string PackLiveStatus(bool tracking);
/// A level change: {"frame", "time", "from", "to", "class", "distance_mm"}.
std::string PackLiveLevelChange(const DangerLevelChange& change);
/// A change of the resection margin's level, on the same device: {"kind": "margin", "frame",
/// "time", "from", "to", "tumour", "tumour_mm"} (a vessel level's change says "kind": "vessel").
std::string PackLiveMarginChange(const MarginLevelChange& change);
/// Why two of these classes cannot be sent apart (their device names, cut to 20 bytes, are the
/// same), or "" when every class has its own.
std::string LiveDeviceNameClash(const std::vector<std::string>& classNames);

/// What a live run adds to summary.json: "latency_ms", pose in -> results out, {median, p95, max,
/// frames} (null without a frame), and "link", the link's counts {messages, poses,
/// poses_dropped, rejected and ignored by reason, connections, connections_lost, send_failures}.
nlohmann::ordered_json LiveLatencyJson(const RunningQuantiles& latencyMs);
nlohmann::ordered_json LiveLinkJson(const IgtlLinkCounts& counts);
} // namespace vp

#endif
