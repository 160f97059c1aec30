// The only translation units that include OpenIGTLink are in this folder.
#include "vpIgtlMessages.h"

#include <igtlMessageHeader.h>
#include <igtlPointMessage.h>
#include <igtlQuaternionTrackingDataMessage.h>
#include <igtlStringMessage.h>
#include <igtlTrackingDataMessage.h>
#include <igtlTransformMessage.h>
#include <igtl_qtdata.h>
#include <igtl_tdata.h>
#include <igtl_transform.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace vp
{
namespace
{
std::uint64_t BigEndian(const unsigned char* bytes, int count)
{
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i)
  {
    value = (value << 8) | bytes[i];
  }
  return value;
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

/// The message's header given to the library, its body copied in and unpacked with the CRC
/// checked: whether the body was unpacked.
template <typename Message>
bool Unpack(Message* message, const unsigned char* header, const std::vector<unsigned char>& body)
{
  auto head = igtl::MessageHeader::New();
  head->InitPack();
  std::memcpy(head->GetPackPointer(), header, IgtlHeaderBytes);
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

std::string Packed(igtl::MessageBase* message)
{
  message->Pack();
  return std::string(static_cast<const char*>(message->GetPackPointer()), static_cast<std::size_t>(message->GetPackSize()));
}
} // namespace

IgtlHeader ParseIgtlHeader(const unsigned char* bytes)
{
  IgtlHeader h;
  h.Version = static_cast<unsigned>(BigEndian(bytes, 2));
  h.Type = NameField(bytes + 2, 12);
  h.Device = NameField(bytes + 14, 20);
  h.BodyBytes = BigEndian(bytes + 42, 8);
  return h;
}

IgtlPoseMessage DecodeIgtlPose(const unsigned char* header, const std::vector<unsigned char>& body, const std::string& toolName,
  const SettledReading& reading)
{
  const IgtlHeader h = ParseIgtlHeader(header);
  if (h.Type != "TRANSFORM" && h.Type != "QTDATA" && h.Type != "TDATA")
  {
    return Ignored("type " + h.Type);
  }
  if (h.Version != 1)
  {
    return Rejected("header version " + std::to_string(h.Version) + " (1 is read)");
  }
  if (h.Type == "TRANSFORM")
  {
    if (h.Device != toolName)
    {
      return Ignored("device " + h.Device);
    }
    if (body.size() != IGTL_TRANSFORM_SIZE)
    {
      return Rejected("a TRANSFORM body not of 48 bytes");
    }
    auto message = igtl::TransformMessage::New();
    if (!Unpack(message.GetPointer(), header, body))
    {
      return Rejected("bad CRC");
    }
    igtl::Matrix4x4 matrix;
    message->GetMatrix(matrix);
    return PoseOfMatrix(matrix, reading);
  }
  if (h.Type == "QTDATA")
  {
    if (body.empty() || body.size() % IGTL_QTDATA_ELEMENT_SIZE != 0)
    {
      return Rejected("a QTDATA body not a whole number of elements");
    }
    auto message = igtl::QuaternionTrackingDataMessage::New();
    if (!Unpack(message.GetPointer(), header, body))
    {
      return Rejected("bad CRC");
    }
    for (int i = 0; i < message->GetNumberOfQuaternionTrackingDataElements(); ++i)
    {
      igtl::QuaternionTrackingDataElement::Pointer element;
      message->GetQuaternionTrackingDataElement(i, element);
      if (toolName == element->GetName())
      {
        float p[3], q[4]; // OpenIGTLink's quaternion: x, y, z, w
        element->GetPosition(p);
        element->GetQuaternion(q);
        const double values[7] = { p[0], p[1], p[2], q[3], q[0], q[1], q[2] };
        return PoseOf(values, 7, reading);
      }
    }
    return Ignored("no element " + toolName);
  }
  if (body.empty() || body.size() % IGTL_TDATA_ELEMENT_SIZE != 0)
  {
    return Rejected("a TDATA body not a whole number of elements");
  }
  auto message = igtl::TrackingDataMessage::New();
  if (!Unpack(message.GetPointer(), header, body))
  {
    return Rejected("bad CRC");
  }
  for (int i = 0; i < message->GetNumberOfTrackingDataElements(); ++i)
  {
    igtl::TrackingDataElement::Pointer element;
    message->GetTrackingDataElement(i, element);
    if (toolName == element->GetName())
    {
      igtl::Matrix4x4 matrix;
      element->GetMatrix(matrix);
      return PoseOfMatrix(matrix, reading);
    }
  }
  return Ignored("no element " + toolName);
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

std::string PackIgtlString(const std::string& device, const std::string& text)
{
  CheckDeviceName(device);
  auto message = igtl::StringMessage::New();
  message->SetDeviceName(device.c_str());
  message->SetEncoding(3); // US-ASCII (IANA MIBenum): the JSON is written in ASCII
  message->SetString(text.c_str());
  return Packed(message.GetPointer());
}

std::string PackIgtlPoints(const std::string& device, const std::vector<IgtlPoint>& points)
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
    element->SetRadius(1.0f);
    message->AddPointElement(element);
  }
  return Packed(message.GetPointer());
}

std::string PackIgtlTransform(const std::string& device, const std::array<double, 16>& matrix)
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
  return Packed(message.GetPointer());
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
