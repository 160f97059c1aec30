#ifndef vpIgtlMessages_h
#define vpIgtlMessages_h

#include "vpPoseReading.h"
#include "vpPoseFile.h"
#include "vpTrackedFrame.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vp
{
/// The bytes of an OpenIGTLink header (version 1, as OpenIGTLink 2 and PLUS send it).
constexpr std::size_t IgtlHeaderBytes = 58;
/// The most bytes of a device name (and of a TDATA, QTDATA or POINT element's name) on the wire.
constexpr std::size_t IgtlDeviceNameBytes = 20;

/// An OpenIGTLink header as its bytes say, before anything is trusted: the body's size is the
/// sender's word for it (64 bits, big-endian), checked by whoever reads that many bytes.
struct IgtlHeader
{
  unsigned Version = 0;
  std::string Type;   ///< "TRANSFORM", "QTDATA", ...
  std::string Device; ///< the device name
  std::uint64_t BodyBytes = 0;
};
IgtlHeader ParseIgtlHeader(const unsigned char* bytes);

/// What one message says about the tool.
struct IgtlPoseMessage
{
  enum class Verdict
  {
    Pose,     ///< the tool's pose, in Pose
    Ignored,  ///< another type, or another tool: not an error (Reason says which)
    Rejected, ///< malformed or implausible: skipped and counted (Reason says why)
  };
  Verdict What = Verdict::Ignored;
  /// A few words, the same for the same cause ("bad CRC", "type STRING"): counts are kept by it.
  std::string Reason;
  TrackedPose Pose; ///< TimeS left 0: the receiver stamps the arrival
};

/// The tool's pose in one message (header and body as received): a TRANSFORM whose device name is
/// toolName, or the element named toolName of a QTDATA or TDATA message. Every check a pose file's
/// pose gets (vp::MakeTrackedPose: finite, orthonormal and proper, a unit quaternion, within the
/// coordinate limits; read as reading says, registration included) and the message's own: header
/// version 1, the body's size for its type, the CRC (OpenIGTLink's own unpacking).
IgtlPoseMessage DecodeIgtlPose(const unsigned char* header, const std::vector<unsigned char>& body, const std::string& toolName,
  const SettledReading& reading);

/// One named point of a POINT message (position in the receiver's frame, mm).
struct IgtlPoint
{
  std::string Name;
  std::string Group;
  std::array<unsigned char, 4> Rgba{ 255, 255, 255, 255 };
  std::array<double, 3> PositionMm{};
};

/// Messages packed as OpenIGTLink sends them (header and body, CRC set), ready to be written to
/// a socket one after another. A device name over IgtlDeviceNameBytes is refused
/// (std::invalid_argument): the wire would carry it cut.
std::string PackIgtlString(const std::string& device, const std::string& text);
std::string PackIgtlPoints(const std::string& device, const std::vector<IgtlPoint>& points);
std::string PackIgtlTransform(const std::string& device, const std::array<double, 16>& matrix);
/// The requests a tracking-data server waits for before it streams (STT_TDATA and STT_QTDATA, one
/// pose every resolutionMs): sent to a server on connecting; one that streams TRANSFORMs
/// unasked ignores them, as OpenIGTLink has a receiver ignore any type it does not know.
std::string PackIgtlStartTracking(int resolutionMs);
} // namespace vp

#endif
