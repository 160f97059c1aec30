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
/// The bytes of an OpenIGTLink header (versions 1 and 2 alike).
constexpr std::size_t IgtlHeaderBytes = 58;
/// The bytes of the extended header a version-2 body begins with, as OpenIGTLink 3 writes it (a
/// reader honours a larger one).
constexpr std::size_t IgtlExtendedHeaderBytes = 12;
/// The most bytes of a device name (and of a TDATA, QTDATA or POINT element's name) on the wire.
constexpr std::size_t IgtlDeviceNameBytes = 20;

/// An OpenIGTLink header as its bytes say, before anything is trusted: the body's size is the
/// sender's word for it (64 bits, big-endian), checked by whoever reads that many bytes.
struct IgtlHeader
{
  unsigned Version = 0;
  std::string Type;   ///< "TRANSFORM", "QTDATA", ...
  std::string Device; ///< the device name
  std::uint32_t TimeSeconds = 0;  ///< the time stamp: whole seconds
  std::uint32_t TimeFraction = 0; ///< and 2^-32 s
  std::uint64_t BodyBytes = 0;
  std::uint64_t Crc = 0;
};
IgtlHeader ParseIgtlHeader(const unsigned char* bytes);

/// One metadata entry of a version-2 message; the value's encoding is an IANA MIBenum (3 US-ASCII,
/// 106 UTF-8).
struct IgtlMetadata
{
  std::string Key;
  std::string Value;
  unsigned Encoding = 3;
  bool operator==(const IgtlMetadata& o) const { return this->Key == o.Key && this->Value == o.Value && this->Encoding == o.Encoding; }
};

/// A body as its header's version lays it out: version 1 is its content alone; version 2 an
/// extended header (its size first, then the metadata's sizes and the message id), the content,
/// the metadata header and the metadata (keys and values back to back).
struct IgtlBody
{
  std::vector<unsigned char> Content;
  std::vector<IgtlMetadata> Metadata;
  std::uint32_t MessageId = 0;
  /// The value of a metadata key, or null.
  const std::string* Find(const std::string& key) const;
};
/// Splits a received body by its header's version, its CRC (OpenIGTLink's crc64, over the whole
/// body in either version) checked: an empty string, or the reason it cannot be read.
std::string SplitIgtlBody(const unsigned char* header, const std::vector<unsigned char>& body, IgtlBody& split);

/// How a message is put on the wire: its header version (2 with an extended header and metadata,
/// written in the key order OpenIGTLink 3 writes them), its time stamp and message id.
struct IgtlPacking
{
  unsigned Version = 1;
  std::uint32_t TimeSeconds = 0;
  std::uint32_t TimeFraction = 0;
  std::vector<IgtlMetadata> Metadata; ///< version 2 only
  std::uint32_t MessageId = 0;        ///< version 2 only
};
/// Now, in seconds since 1970 (UTC), and a packing stamped with such a time (OpenIGTLink's whole
/// seconds and 2^-32 fractions): a tracker server stamps its poses, a reply its results.
double IgtlWallClockS();
IgtlPacking IgtlStampedAt(double clockS);
/// A version-1 message (header and body) rewritten as version 2 with the metadata and message id:
/// what a peer that speaks version 2 is answered in.
std::string ToIgtlVersion2(const std::string& message, const std::vector<IgtlMetadata>& metadata, std::uint32_t messageId);

/// What one message says about the tool.
struct IgtlPoseMessage
{
  enum class Verdict
  {
    Pose,     ///< the tool's pose, in Pose; Pose.Lost when the tracker says it does not see the tool
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
/// version 1 or 2, the body's size for its type, the CRC. A version-2 pose whose status is not OK
/// (TRANSFORM's TransformStatus or TransformValid 0, as PLUS and Slicer send them; a TDATA or
/// QTDATA element's <name>Status) is a lost pose: the tracker does not see the tool.
IgtlPoseMessage DecodeIgtlPose(const unsigned char* header, const std::vector<unsigned char>& body, const std::string& toolName,
  const SettledReading& reading);

/// One named point of a POINT message (position in the receiver's frame, mm).
struct IgtlPoint
{
  std::string Name;
  std::string Group;
  std::array<unsigned char, 4> Rgba{ 255, 255, 255, 255 };
  std::array<double, 3> PositionMm{};
  double RadiusMm = 1.0;
  std::string Owner;
};

/// A STATUS message's fields (OpenIGTLink's codes: 1 OK, 13 not ready, ...).
struct IgtlStatus
{
  int Code = 1;
  long long Subcode = 0;
  std::string ErrorName;
  std::string Text;
};

/// One tool of a TDATA (its matrix) or QTDATA (its position and quaternion) message.
struct IgtlTool
{
  std::string Name;
  int Type = 0; ///< 1 tracker, 2 6D, 3 3D, 4 5D
  std::array<double, 16> Matrix{};             ///< TDATA, row-major
  std::array<double, 3> PositionMm{};          ///< QTDATA
  std::array<double, 4> QuaternionXyzw{};      ///< QTDATA
};

/// Each type's content, read from a message of either version (the body split and its CRC
/// checked): an empty string, or the reason it cannot be read.
std::string DecodeIgtlTransform(const unsigned char* header, const std::vector<unsigned char>& body, std::array<double, 16>& matrix);
std::string DecodeIgtlStatus(const unsigned char* header, const std::vector<unsigned char>& body, IgtlStatus& status);
std::string DecodeIgtlString(const unsigned char* header, const std::vector<unsigned char>& body, unsigned& encoding, std::string& text);
std::string DecodeIgtlPoints(const unsigned char* header, const std::vector<unsigned char>& body, std::vector<IgtlPoint>& points);
std::string DecodeIgtlTools(const unsigned char* header, const std::vector<unsigned char>& body, std::vector<IgtlTool>& tools);

/// Messages packed as OpenIGTLink sends them (header and body, CRC set), ready to be written to
/// a socket one after another. A device name over IgtlDeviceNameBytes is refused
/// (std::invalid_argument): the wire would carry it cut.
std::string PackIgtlString(const std::string& device, const std::string& text, unsigned encoding = 3, const IgtlPacking& packing = {});
std::string PackIgtlPoints(const std::string& device, const std::vector<IgtlPoint>& points, const IgtlPacking& packing = {});
std::string PackIgtlTransform(const std::string& device, const std::array<double, 16>& matrix, const IgtlPacking& packing = {});
std::string PackIgtlStatus(const std::string& device, const IgtlStatus& status, const IgtlPacking& packing = {});
/// The requests a tracking-data server waits for before it streams (STT_TDATA and STT_QTDATA, one
/// pose every resolutionMs): sent to a server on connecting; one that streams TRANSFORMs
/// unasked ignores them, as OpenIGTLink has a receiver ignore any type it does not know.
std::string PackIgtlStartTracking(int resolutionMs);
} // namespace vp

#endif
