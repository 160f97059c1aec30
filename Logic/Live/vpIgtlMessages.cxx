// The only translation units that include OpenIGTLink are in this folder.
#include "vpIgtlMessages.h"

#include <igtlMessageHeader.h>
#include <igtlPointMessage.h>
#include <igtlQuaternionTrackingDataMessage.h>
#include <igtlStatusMessage.h>
#include <igtlStringMessage.h>
#include <igtlTrackingDataMessage.h>
#include <igtlTransformMessage.h>
#include <igtl_point.h>
#include <igtl_qtdata.h>
#include <igtl_tdata.h>
#include <igtl_transform.h>
#include <igtl_util.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>

namespace vp
{
namespace
{
/// A STATUS body's fixed fields: code (2 bytes), subcode (8), error name (20); the text follows.
constexpr std::size_t StatusFieldsBytes = 30;

std::uint64_t BigEndian(const unsigned char* bytes, int count)
{
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i)
  {
    value = (value << 8) | bytes[i];
  }
  return value;
}

void PutBigEndian(unsigned char* bytes, std::uint64_t value, int count)
{
  for (int i = count - 1; i >= 0; --i, value >>= 8)
  {
    bytes[i] = static_cast<unsigned char>(value & 0xff);
  }
}

std::uint64_t Crc64(const unsigned char* data, std::size_t size)
{
  return crc64(const_cast<unsigned char*>(data), static_cast<igtl_uint64>(size), 0);
}

/// A fixed-size name field: up to its first NUL, printable characters only kept.
std::string NameField(const unsigned char* bytes, std::size_t size)
{
  std::string name;
  for (std::size_t i = 0; i < size && bytes[i] != 0; ++i)
  {
    name += bytes[i] >= 0x20 && bytes[i] < 0x7f ? static_cast<char>(bytes[i]) : '?';
  }
  return name;
}

IgtlPoseMessage Rejected(const std::string& reason)
{
  IgtlPoseMessage m;
  m.What = IgtlPoseMessage::Verdict::Rejected;
  m.Reason = reason;
  return m;
}

IgtlPoseMessage Ignored(const std::string& reason)
{
  IgtlPoseMessage m;
  m.What = IgtlPoseMessage::Verdict::Ignored;
  m.Reason = reason;
  return m;
}

/// The message's header given to the library as version 1 for its content (the library reads
/// version 1 only; a version-2 body's CRC was checked whole before), the content copied in and
/// unpacked: whether it was.
template <typename Message>
bool Unpack(Message* message, const unsigned char* header, const std::vector<unsigned char>& body)
{
  unsigned char v1[IgtlHeaderBytes];
  std::memcpy(v1, header, IgtlHeaderBytes);
  PutBigEndian(v1, 1, 2);
  PutBigEndian(v1 + 42, body.size(), 8);
  PutBigEndian(v1 + 50, Crc64(body.data(), body.size()), 8);
  auto head = igtl::MessageHeader::New();
  head->InitPack();
  std::memcpy(head->GetPackPointer(), v1, IgtlHeaderBytes);
  head->Unpack();
  message->SetMessageHeader(head);
  message->AllocatePack();
  if (static_cast<std::size_t>(message->GetPackBodySize()) != body.size())
  {
    return false;
  }
  std::memcpy(message->GetPackBodyPointer(), body.data(), body.size());
  return (message->Unpack(1) & igtl::MessageHeader::UNPACK_BODY) != 0;
}

std::size_t ElementBytes(igtl::TrackingDataMessage*)
{
  return IGTL_TDATA_ELEMENT_SIZE;
}
std::size_t ElementBytes(igtl::QuaternionTrackingDataMessage*)
{
  return IGTL_QTDATA_ELEMENT_SIZE;
}
int ElementCount(igtl::TrackingDataMessage* m)
{
  return m->GetNumberOfTrackingDataElements();
}
int ElementCount(igtl::QuaternionTrackingDataMessage* m)
{
  return m->GetNumberOfQuaternionTrackingDataElements();
}
igtl::TrackingDataElement::Pointer Element(igtl::TrackingDataMessage* m, int i)
{
  igtl::TrackingDataElement::Pointer e;
  m->GetTrackingDataElement(i, e);
  return e;
}
igtl::QuaternionTrackingDataElement::Pointer Element(igtl::QuaternionTrackingDataMessage* m, int i)
{
  igtl::QuaternionTrackingDataElement::Pointer e;
  m->GetQuaternionTrackingDataElement(i, e);
  return e;
}

/// The tools of a TDATA or QTDATA content, in order: whether it was unpacked.
void ReadTool(igtl::TrackingDataElement* element, IgtlTool& tool)
{
  igtl::Matrix4x4 m;
  element->GetMatrix(m);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      tool.Matrix[static_cast<std::size_t>(4 * r + c)] = m[r][c];
    }
  }
}

void ReadTool(igtl::QuaternionTrackingDataElement* element, IgtlTool& tool)
{
  float p[3], q[4]; // OpenIGTLink's quaternion: x, y, z, w
  element->GetPosition(p);
  element->GetQuaternion(q);
  tool.PositionMm = { p[0], p[1], p[2] };
  tool.QuaternionXyzw = { q[0], q[1], q[2], q[3] };
}

template <typename Message>
bool UnpackTools(const unsigned char* header, const std::vector<unsigned char>& content, std::vector<IgtlTool>& tools)
{
  auto message = Message::New();
  if (!Unpack(message.GetPointer(), header, content))
  {
    return false;
  }
  // Each element begins with its name, 20 bytes: read from the content itself, since the library
  // loses a name that fills all 20 (its copy has no room for the end of the string).
  const std::size_t elementBytes = ElementBytes(message.GetPointer());
  for (int i = 0; i < ElementCount(message.GetPointer()); ++i)
  {
    IgtlTool tool;
    auto element = Element(message.GetPointer(), i);
    tool.Name = NameField(content.data() + static_cast<std::size_t>(i) * elementBytes, IgtlDeviceNameBytes);
    tool.Type = element->GetType();
    ReadTool(element.GetPointer(), tool);
    tools.push_back(tool);
  }
  return true;
}

/// The pose from the message's numbers, or the rejection.
IgtlPoseMessage PoseOf(const double* values, std::size_t count, const SettledReading& reading)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!std::isfinite(values[i]))
    {
      return Rejected("a NaN or infinite number");
    }
  }
  IgtlPoseMessage m;
  const std::string problem = MakeTrackedPose(values, count, reading, m.Pose);
  if (!problem.empty())
  {
    // The reason names the kind of problem, not its numbers, so that counts gather.
    return Rejected(problem.substr(0, problem.find(" (")));
  }
  m.What = IgtlPoseMessage::Verdict::Pose;
  return m;
}

IgtlPoseMessage PoseOfMatrix(const igtl::Matrix4x4& matrix, const SettledReading& reading)
{
  double values[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      values[4 * r + c] = matrix[r][c];
    }
  }
  return PoseOf(values, 16, reading);
}

std::string Packed(igtl::MessageBase* message, const IgtlPacking& packing = {})
{
  message->SetTimeStamp(packing.TimeSeconds, packing.TimeFraction);
  message->Pack();
  const std::string v1(static_cast<const char*>(message->GetPackPointer()), static_cast<std::size_t>(message->GetPackSize()));
  return packing.Version >= 2 ? ToIgtlVersion2(v1, packing.Metadata, packing.MessageId) : v1;
}
} // namespace

double IgtlWallClockS()
{
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

IgtlPacking IgtlStampedAt(double clockS)
{
  // The header's range: whole seconds below 2^32, a fraction below one.
  const double clamped = std::isfinite(clockS) ? std::min(std::max(clockS, 0.0), 4294967295.0) : 0.0;
  IgtlPacking packing;
  const double seconds = std::floor(clamped);
  packing.TimeSeconds = static_cast<std::uint32_t>(seconds);
  packing.TimeFraction = static_cast<std::uint32_t>(std::min(4294967295.0, std::floor((clamped - seconds) * 4294967296.0)));
  return packing;
}

const std::string* IgtlBody::Find(const std::string& key) const
{
  const auto it = std::find_if(this->Metadata.begin(), this->Metadata.end(), [&](const IgtlMetadata& m) { return m.Key == key; });
  return it == this->Metadata.end() ? nullptr : &it->Value;
}

std::string SplitIgtlBody(const unsigned char* header, const std::vector<unsigned char>& body, IgtlBody& split)
{
  const IgtlHeader h = ParseIgtlHeader(header);
  // An empty body's CRC is whatever the sender left there (Slicer's connect STATUS: 0, with 0 bytes).
  if (!body.empty() && Crc64(body.data(), body.size()) != h.Crc)
  {
    return "bad CRC";
  }
  split = IgtlBody();
  if (h.Version < 2)
  {
    split.Content = body;
    return "";
  }
  if (body.size() < IgtlExtendedHeaderBytes)
  {
    return "a version-2 body shorter than its extended header";
  }
  const std::uint64_t extended = BigEndian(body.data(), 2), metaHeader = BigEndian(body.data() + 2, 2),
                      meta = BigEndian(body.data() + 4, 4);
  split.MessageId = static_cast<std::uint32_t>(BigEndian(body.data() + 8, 4));
  if (extended < IgtlExtendedHeaderBytes || extended + metaHeader + meta > body.size() || (metaHeader != 0 && metaHeader < 2))
  {
    return "a version-2 body whose sections do not add up";
  }
  const std::size_t contentEnd = body.size() - static_cast<std::size_t>(metaHeader + meta);
  split.Content.assign(body.begin() + static_cast<std::ptrdiff_t>(extended), body.begin() + static_cast<std::ptrdiff_t>(contentEnd));
  if (metaHeader == 0)
  {
    return "";
  }
  const unsigned char* index = body.data() + contentEnd;
  const std::uint64_t count = BigEndian(index, 2);
  if (metaHeader != 2 + 8 * count)
  {
    return "a version-2 metadata header of the wrong size";
  }
  const unsigned char* data = index + metaHeader;
  std::uint64_t used = 0;
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const unsigned char* entry = index + 2 + 8 * i;
    const std::uint64_t keyBytes = BigEndian(entry, 2), valueBytes = BigEndian(entry + 4, 4);
    if (used + keyBytes + valueBytes > meta)
    {
      return "version-2 metadata longer than its size";
    }
    IgtlMetadata m;
    m.Key.assign(reinterpret_cast<const char*>(data + used), static_cast<std::size_t>(keyBytes));
    m.Encoding = static_cast<unsigned>(BigEndian(entry + 2, 2));
    m.Value.assign(reinterpret_cast<const char*>(data + used + keyBytes), static_cast<std::size_t>(valueBytes));
    used += keyBytes + valueBytes;
    split.Metadata.push_back(std::move(m));
  }
  return used == meta ? "" : "version-2 metadata shorter than its size";
}

std::string ToIgtlVersion2(const std::string& message, const std::vector<IgtlMetadata>& metadata, std::uint32_t messageId)
{
  // OpenIGTLink 3 keeps metadata in a std::map: written in byte order of the keys.
  std::vector<IgtlMetadata> sorted = metadata;
  std::stable_sort(sorted.begin(), sorted.end(), [](const IgtlMetadata& a, const IgtlMetadata& b) { return a.Key < b.Key; });
  std::string index(2 + 8 * sorted.size(), '\0'), values;
  auto* at = reinterpret_cast<unsigned char*>(&index[0]);
  PutBigEndian(at, sorted.size(), 2);
  for (std::size_t i = 0; i < sorted.size(); ++i)
  {
    PutBigEndian(at + 2 + 8 * i, sorted[i].Key.size(), 2);
    PutBigEndian(at + 4 + 8 * i, sorted[i].Encoding, 2);
    PutBigEndian(at + 6 + 8 * i, sorted[i].Value.size(), 4);
    values += sorted[i].Key + sorted[i].Value;
  }
  std::string extended(IgtlExtendedHeaderBytes, '\0');
  auto* ext = reinterpret_cast<unsigned char*>(&extended[0]);
  PutBigEndian(ext, IgtlExtendedHeaderBytes, 2);
  PutBigEndian(ext + 2, index.size(), 2);
  PutBigEndian(ext + 4, values.size(), 4);
  PutBigEndian(ext + 8, messageId, 4);
  const std::string body = extended + message.substr(IgtlHeaderBytes) + index + values;
  std::string header = message.substr(0, IgtlHeaderBytes);
  auto* h = reinterpret_cast<unsigned char*>(&header[0]);
  PutBigEndian(h, 2, 2);
  PutBigEndian(h + 42, body.size(), 8);
  PutBigEndian(h + 50, Crc64(reinterpret_cast<const unsigned char*>(body.data()), body.size()), 8);
  return header + body;
}

IgtlHeader ParseIgtlHeader(const unsigned char* bytes)
{
  IgtlHeader h;
  h.Version = static_cast<unsigned>(BigEndian(bytes, 2));
  h.Type = NameField(bytes + 2, 12);
  h.Device = NameField(bytes + 14, 20);
  h.TimeSeconds = static_cast<std::uint32_t>(BigEndian(bytes + 34, 4));
  h.TimeFraction = static_cast<std::uint32_t>(BigEndian(bytes + 38, 4));
  h.BodyBytes = BigEndian(bytes + 42, 8);
  h.Crc = BigEndian(bytes + 50, 8);
  return h;
}

namespace
{
/// Whether a status the tracker sent says it sees the tool: none sent, or OK (PLUS's and Slicer's
/// word; MISSING, OUT_OF_VIEW, ... say it does not).
bool Seen(const std::string* status)
{
  return !status || *status == "OK";
}

IgtlPoseMessage LostPose()
{
  IgtlPoseMessage m;
  m.What = IgtlPoseMessage::Verdict::Pose;
  m.Pose.Lost = true;
  return m;
}

/// The size a content of this type must have: its elements whole (0: any).
bool ContentSizeFits(const std::string& type, std::size_t size)
{
  if (type == "TRANSFORM")
  {
    return size == IGTL_TRANSFORM_SIZE;
  }
  const std::size_t element = type == "QTDATA" ? IGTL_QTDATA_ELEMENT_SIZE : IGTL_TDATA_ELEMENT_SIZE;
  return size > 0 && size % element == 0;
}

std::string ContentSizeProblem(const std::string& type)
{
  return type == "TRANSFORM" ? "a TRANSFORM body not of 48 bytes" : "a " + type + " body not a whole number of elements";
}

/// The named tool's pose in a QTDATA or TDATA content, or why not.
IgtlPoseMessage ToolPose(const unsigned char* header, const IgtlBody& split, const std::string& type, const std::string& toolName,
  const SettledReading& reading)
{
  std::vector<IgtlTool> tools;
  if (!(type == "QTDATA" ? UnpackTools<igtl::QuaternionTrackingDataMessage>(header, split.Content, tools)
                         : UnpackTools<igtl::TrackingDataMessage>(header, split.Content, tools)))
  {
    return Rejected("bad CRC");
  }
  for (const IgtlTool& tool : tools)
  {
    if (tool.Name != toolName)
    {
      continue;
    }
    if (!Seen(split.Find(toolName + "Status")))
    {
      return LostPose();
    }
    if (type == "QTDATA")
    {
      const double values[7] = { tool.PositionMm[0], tool.PositionMm[1], tool.PositionMm[2], tool.QuaternionXyzw[3],
        tool.QuaternionXyzw[0], tool.QuaternionXyzw[1], tool.QuaternionXyzw[2] };
      return PoseOf(values, 7, reading);
    }
    return PoseOf(tool.Matrix.data(), 16, reading);
  }
  return Ignored("no element " + toolName);
}

/// What one message says about the tool, before its time stamp is taken.
IgtlPoseMessage DecodePose(const unsigned char* header, const IgtlHeader& h, const std::vector<unsigned char>& body,
  const std::string& toolName, const SettledReading& reading)
{
  if (h.Type != "TRANSFORM" && h.Type != "QTDATA" && h.Type != "TDATA")
  {
    return Ignored("type " + h.Type);
  }
  if (h.Version != 1 && h.Version != 2)
  {
    return Rejected("header version " + std::to_string(h.Version) + " (1 and 2 are read)");
  }
  if (h.Type == "TRANSFORM" && h.Device != toolName)
  {
    return Ignored("device " + h.Device);
  }
  if (h.Version == 1 && !ContentSizeFits(h.Type, body.size()))
  {
    return Rejected(ContentSizeProblem(h.Type));
  }
  IgtlBody split;
  const std::string problem = SplitIgtlBody(header, body, split);
  if (!problem.empty())
  {
    return Rejected(problem);
  }
  if (!ContentSizeFits(h.Type, split.Content.size()))
  {
    return Rejected(ContentSizeProblem(h.Type));
  }
  if (h.Type != "TRANSFORM")
  {
    return ToolPose(header, split, h.Type, toolName, reading);
  }
  const std::string* valid = split.Find("TransformValid");
  if (!Seen(split.Find("TransformStatus")) || (valid && *valid == "0"))
  {
    return LostPose(); // PLUS sends an identity for a tool it does not see: never computed
  }
  auto message = igtl::TransformMessage::New();
  if (!Unpack(message.GetPointer(), header, split.Content))
  {
    return Rejected("bad CRC");
  }
  igtl::Matrix4x4 matrix;
  message->GetMatrix(matrix);
  return PoseOfMatrix(matrix, reading);
}
} // namespace

IgtlPoseMessage DecodeIgtlPose(const unsigned char* header, const std::vector<unsigned char>& body, const std::string& toolName,
  const SettledReading& reading)
{
  const IgtlHeader h = ParseIgtlHeader(header);
  IgtlPoseMessage m = DecodePose(header, h, body, toolName, reading);
  m.Pose.SourceClockS = h.TimeSeconds + h.TimeFraction / 4294967296.0;
  return m;
}

namespace
{
/// A message's content split from its body (version 2's extended header and metadata off),
/// checked before the library reads it (fits: its size and whatever the library would trust; the
/// content is hostile) and unpacked into message: the problem, or "" (sizeProblem when the
/// content does not fit, unpackProblem when the library refuses it).
template <typename Message>
std::string UnpackContent(const unsigned char* header, const std::vector<unsigned char>& body, Message* message,
  const std::function<bool(const std::vector<unsigned char>&)>& fits, const std::string& sizeProblem,
  const std::string& unpackProblem, IgtlBody& split)
{
  std::string problem = SplitIgtlBody(header, body, split);
  if (!problem.empty())
  {
    return problem;
  }
  if (!fits(split.Content))
  {
    return sizeProblem;
  }
  return Unpack(message, header, split.Content) ? std::string() : unpackProblem;
}
} // namespace

std::string DecodeIgtlTransform(const unsigned char* header, const std::vector<unsigned char>& body, std::array<double, 16>& matrix)
{
  IgtlBody split;
  auto message = igtl::TransformMessage::New();
  const std::string problem = UnpackContent(header, body, message.GetPointer(),
    [](const std::vector<unsigned char>& c) { return c.size() == IGTL_TRANSFORM_SIZE; }, ContentSizeProblem("TRANSFORM"),
    "bad CRC", split);
  if (problem.empty())
  {
    igtl::Matrix4x4 m;
    message->GetMatrix(m);
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        matrix[static_cast<std::size_t>(4 * r + c)] = m[r][c];
      }
    }
  }
  return problem;
}

std::string DecodeIgtlStatus(const unsigned char* header, const std::vector<unsigned char>& body, IgtlStatus& status)
{
  IgtlBody split;
  auto message = igtl::StatusMessage::New();
  const std::string unreadable = "a STATUS body that cannot be read";
  // The text after the fixed fields ends with its NUL, which the library's strlen relies on.
  const std::string problem = UnpackContent(header, body, message.GetPointer(),
    [](const std::vector<unsigned char>& c) { return c.size() > StatusFieldsBytes && c.back() == 0; }, unreadable, unreadable,
    split);
  if (problem.empty())
  {
    status.Code = message->GetCode();
    status.Subcode = message->GetSubCode();
    status.ErrorName = NameField(reinterpret_cast<const unsigned char*>(message->GetErrorName()), 20);
    status.Text = message->GetStatusString();
  }
  return problem;
}

std::string DecodeIgtlString(const unsigned char* header, const std::vector<unsigned char>& body, unsigned& encoding, std::string& text)
{
  IgtlBody split;
  auto message = igtl::StringMessage::New();
  const std::string unreadable = "a STRING body that cannot be read";
  // Encoding (2 bytes), length (2), then that many bytes: the library copies what the length says.
  const std::string problem = UnpackContent(header, body, message.GetPointer(),
    [](const std::vector<unsigned char>& c) { return c.size() >= 4 && 4 + BigEndian(c.data() + 2, 2) <= c.size(); }, unreadable,
    unreadable, split);
  if (problem.empty())
  {
    encoding = message->GetEncoding();
    text = message->GetString();
  }
  return problem;
}

std::string DecodeIgtlPoints(const unsigned char* header, const std::vector<unsigned char>& body, std::vector<IgtlPoint>& points)
{
  IgtlBody split;
  auto message = igtl::PointMessage::New();
  const std::string unreadable = "a POINT body not a whole number of points";
  const std::string problem = UnpackContent(header, body, message.GetPointer(),
    [](const std::vector<unsigned char>& c) { return c.size() % IGTL_POINT_ELEMENT_SIZE == 0; }, unreadable, unreadable, split);
  for (int i = 0; problem.empty() && i < message->GetNumberOfPointElement(); ++i)
  {
    igtl::PointElement::Pointer element;
    message->GetPointElement(i, element);
    IgtlPoint p;
    // Names from the content itself (a name filling its field comes back empty from the library):
    // name 64 bytes, group 32, then colour, position, radius, and the owner's 20 at the end.
    const unsigned char* raw = split.Content.data() + static_cast<std::size_t>(i) * IGTL_POINT_ELEMENT_SIZE;
    p.Name = NameField(raw, 64);
    p.Group = NameField(raw + 64, 32);
    element->GetRGBA(p.Rgba.data());
    igtlFloat32 position[3];
    element->GetPosition(position);
    p.PositionMm = { position[0], position[1], position[2] };
    p.RadiusMm = element->GetRadius();
    p.Owner = NameField(raw + IGTL_POINT_ELEMENT_SIZE - 20, 20);
    points.push_back(p);
  }
  return problem;
}

std::string DecodeIgtlTools(const unsigned char* header, const std::vector<unsigned char>& body, std::vector<IgtlTool>& tools)
{
  IgtlBody split;
  std::string problem = SplitIgtlBody(header, body, split);
  const std::string type = ParseIgtlHeader(header).Type;
  if (problem.empty() && !ContentSizeFits(type, split.Content.size()))
  {
    problem = ContentSizeProblem(type);
  }
  if (problem.empty() && !(type == "QTDATA" ? UnpackTools<igtl::QuaternionTrackingDataMessage>(header, split.Content, tools)
                                            : UnpackTools<igtl::TrackingDataMessage>(header, split.Content, tools)))
  {
    problem = "bad CRC";
  }
  return problem;
}

namespace
{
void CheckDeviceName(const std::string& device)
{
  if (device.size() > IgtlDeviceNameBytes)
  {
    throw std::invalid_argument("OpenIGTLink device name '" + device + "' is " + std::to_string(device.size()) +
      " bytes; the wire holds " + std::to_string(IgtlDeviceNameBytes));
  }
}
} // namespace

std::string PackIgtlString(const std::string& device, const std::string& text, unsigned encoding, const IgtlPacking& packing)
{
  CheckDeviceName(device);
  auto message = igtl::StringMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetEncoding(static_cast<igtlUint16>(encoding)); // IANA MIBenum: 3 US-ASCII, 106 UTF-8
  message->SetString(text.c_str());
  return Packed(message.GetPointer(), packing);
}

std::string PackIgtlPoints(const std::string& device, const std::vector<IgtlPoint>& points, const IgtlPacking& packing)
{
  CheckDeviceName(device);
  auto message = igtl::PointMessage::New();
  message->SetDeviceName(device.c_str());
  for (const IgtlPoint& p : points)
  {
    auto element = igtl::PointElement::New();
    element->SetName(p.Name.c_str());
    element->SetGroupName(p.Group.c_str());
    element->SetRGBA(p.Rgba[0], p.Rgba[1], p.Rgba[2], p.Rgba[3]);
    igtlFloat32 position[3] = { static_cast<igtlFloat32>(p.PositionMm[0]), static_cast<igtlFloat32>(p.PositionMm[1]),
      static_cast<igtlFloat32>(p.PositionMm[2]) };
    element->SetPosition(position);
    element->SetRadius(static_cast<igtlFloat32>(p.RadiusMm));
    element->SetOwner(p.Owner.c_str());
    message->AddPointElement(element);
  }
  return Packed(message.GetPointer(), packing);
}

std::string PackIgtlTransform(const std::string& device, const std::array<double, 16>& matrix, const IgtlPacking& packing)
{
  CheckDeviceName(device);
  auto message = igtl::TransformMessage::New();
  message->SetDeviceName(device.c_str());
  igtl::Matrix4x4 m;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[r][c] = static_cast<float>(matrix[static_cast<std::size_t>(4 * r + c)]);
    }
  }
  message->SetMatrix(m);
  return Packed(message.GetPointer(), packing);
}

std::string PackIgtlStatus(const std::string& device, const IgtlStatus& status, const IgtlPacking& packing)
{
  CheckDeviceName(device);
  auto message = igtl::StatusMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetCode(status.Code);
  message->SetSubCode(status.Subcode);
  message->SetErrorName(status.ErrorName.c_str());
  message->SetStatusString(status.Text.c_str());
  return Packed(message.GetPointer(), packing);
}

std::string PackIgtlStartTracking(int resolutionMs)
{
  auto matrices = igtl::StartTrackingDataMessage::New();
  matrices->SetDeviceName("");
  matrices->SetResolution(resolutionMs);
  auto quaternions = igtl::StartQuaternionTrackingDataMessage::New();
  quaternions->SetDeviceName("");
  quaternions->SetResolution(resolutionMs);
  return Packed(matrices.GetPointer()) + Packed(quaternions.GetPointer());
}
} // namespace vp
