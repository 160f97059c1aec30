// An OpenIGTLink peer for the live tests, written with the library (Debian's libopenigtlink)
// where its example programs do not fit: it serves a pose file at a given rate, as a tracker
// server would, and it sends the malformed messages a broken or hostile peer might.
//
//   vp_igtl_peer serve PORT POSES.csv RATE_HZ DEVICE SENT.csv [PAUSE_AFTER PAUSE_MS]
//     Serves on PORT (0: any; "port N" is printed first), waits for one client, sends each pose
//     of POSES.csv (time,m00..m33) as a TRANSFORM named DEVICE at RATE_HZ, pausing PAUSE_MS after
//     pose PAUSE_AFTER, writes the poses as sent (in float, as the message carries them) to
//     SENT.csv, and exits half a second after the last.
//   vp_igtl_peer hostile PORT DEVICE
//     Serves on PORT, and to its first client sends, between good poses, one message of each
//     malformed kind, then a size field that lies; to its second client, five good poses.
//   vp_igtl_peer replay PORT RATE_HZ REPLIES.txt FILE[*COUNT]...
//     Serves on PORT, waits for one client, sends the bytes of each FILE (a whole message as it
//     goes on the wire) COUNT times (default 1) at RATE_HZ, reads what the client sends back,
//     writing "VERSION TYPE DEVICE" for each message to REPLIES.txt (and its bytes to
//     REPLIES.txt.bin), and exits half a second after
//     the last: a peer that speaks as 3D Slicer or PlusServer do, from their own messages.
#include <igtlOSUtil.h>
#include <igtlQuaternionTrackingDataMessage.h>
#include <igtlServerSocket.h>
#include <igtlStringMessage.h>
#include <igtlTrackingDataMessage.h>
#include <igtlTransformMessage.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

igtl::ServerSocket::Pointer Serve(int port)
{
  auto server = igtl::ServerSocket::New();
  if (server->CreateServer(port) < 0)
  {
    std::cerr << "vp_igtl_peer: cannot serve on port " << port << "\n";
    std::exit(2);
  }
  std::cout << "port " << server->GetServerPort() << std::endl;
  return server;
}

igtl::Socket::Pointer Accept(igtl::ServerSocket* server)
{
  for (int i = 0; i < 200; ++i) // 20 s at most
  {
    igtl::ClientSocket::Pointer socket = server->WaitForConnection(100);
    if (socket.IsNotNull())
    {
      return socket.GetPointer();
    }
  }
  std::cerr << "vp_igtl_peer: no client came\n";
  std::exit(3);
}

std::string Packed(igtl::MessageBase* message)
{
  message->Pack();
  return std::string(static_cast<const char*>(message->GetPackPointer()), static_cast<std::size_t>(message->GetPackSize()));
}

std::string Transform(const std::string& device, const float m[16])
{
  auto message = igtl::TransformMessage::New();
  message->SetDeviceName(device.c_str());
  igtl::Matrix4x4 matrix;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      matrix[r][c] = m[4 * r + c];
    }
  }
  message->SetMatrix(matrix);
  return Packed(message.GetPointer());
}

void Send(igtl::Socket* socket, const std::string& bytes)
{
  socket->Send(bytes.data(), static_cast<int>(bytes.size()));
}

int ServePoses(int port, const std::string& posesFile, double rateHz, const std::string& device, const std::string& sentFile,
  int pauseAfter, int pauseMs)
{
  std::ifstream in(posesFile);
  std::vector<std::vector<float>> poses;
  std::string line;
  std::getline(in, line); // the header
  while (std::getline(in, line))
  {
    std::istringstream fields(line);
    std::vector<float> values;
    for (std::string field; std::getline(fields, field, ',');)
    {
      values.push_back(std::strtof(field.c_str(), nullptr));
    }
    if (values.size() == 17)
    {
      poses.emplace_back(values.begin() + 1, values.end());
    }
  }
  auto server = Serve(port);
  igtl::Socket::Pointer socket = Accept(server);
  const auto start = Clock::now();
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    std::this_thread::sleep_until(start + std::chrono::microseconds(static_cast<long long>(1e6 * static_cast<double>(i) / rateHz)) +
      std::chrono::milliseconds(pauseAfter >= 0 && static_cast<int>(i) > pauseAfter ? pauseMs : 0));
    Send(socket, Transform(device, poses[i].data()));
  }
  std::ofstream sent(sentFile);
  sent << "time,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33\n";
  // Each float as the double it is (17 digits), so that a reader in double gets it exactly.
  sent.precision(std::numeric_limits<double>::max_digits10);
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    sent << 0.001 * static_cast<double>(i + 1);
    for (float v : poses[i])
    {
      sent << "," << static_cast<double>(v);
    }
    sent << "\n";
  }
  sent.close();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  socket->CloseSocket();
  return 0;
}

int Hostile(int port, const std::string& device)
{
  auto server = Serve(port);
  igtl::Socket::Pointer socket = Accept(server);
  const float good[16] = { 1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 };
  const auto pause = [] { std::this_thread::sleep_for(std::chrono::milliseconds(30)); };
  Send(socket, Transform(device, good));
  pause();
  // A bit flipped in the body: the CRC no longer holds.
  std::string crc = Transform(device, good);
  crc[60] ^= 0x10;
  Send(socket, crc);
  // A type nobody knows (the header's type field rewritten; its CRC covers the body only).
  std::string unknown = Transform(device, good);
  std::memset(&unknown[2], 0, 12);
  std::memcpy(&unknown[2], "FOOBAR", 6);
  Send(socket, unknown);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float notANumber[16] = { 1, 0, 0, nan, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  Send(socket, Transform(device, notANumber));
  const float scaled[16] = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };
  Send(socket, Transform(device, scaled));
  Send(socket, Transform("Reference", good));
  // A TRANSFORM whose header says a 40-byte body, and 40 bytes follow.
  std::string shortBody = Transform(device, good).substr(0, 58 + 40);
  for (int i = 0; i < 8; ++i)
  {
    shortBody[42 + i] = i == 7 ? 40 : 0;
  }
  Send(socket, shortBody);
  auto quaternions = igtl::QuaternionTrackingDataMessage::New();
  quaternions->SetDeviceName("Tracker");
  auto element = igtl::QuaternionTrackingDataElement::New();
  element->SetName(device.c_str());
  element->SetPosition(1.0f, 2.0f, 3.0f);
  element->SetQuaternion(0.0f, 0.0f, 0.0f, 2.0f);
  quaternions->AddQuaternionTrackingDataElement(element);
  Send(socket, Packed(quaternions.GetPointer()));
  pause();
  auto tracking = igtl::TrackingDataMessage::New();
  tracking->SetDeviceName("Tracker");
  auto tool = igtl::TrackingDataElement::New();
  tool->SetName(device.c_str());
  igtl::Matrix4x4 matrix;
  igtl::IdentityMatrix(matrix);
  matrix[0][3] = 5.0f;
  tool->SetMatrix(matrix);
  tracking->AddTrackingDataElement(tool);
  Send(socket, Packed(tracking.GetPointer()));
  pause();
  // A size field that lies: no body follows, and none of this size could.
  std::string lie = Transform(device, good).substr(0, 58);
  for (int i = 0; i < 8; ++i)
  {
    lie[42 + i] = static_cast<char>(i == 2 ? 0x7f : 0);
  }
  Send(socket, lie);
  // The reader closes the connection; the second one gets good poses.
  igtl::Socket::Pointer second = Accept(server);
  for (int i = 0; i < 5; ++i)
  {
    float pose[16] = { 1, 0, 0, 1.0f + static_cast<float>(i), 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 };
    Send(second, Transform(device, pose));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  second->CloseSocket();
  socket->CloseSocket();
  return 0;
}
int Replay(int port, double rateHz, const std::string& repliesFile, const std::vector<std::string>& files)
{
  std::vector<std::string> messages;
  for (const std::string& spec : files)
  {
    const std::size_t star = spec.find('*');
    std::ifstream in(spec.substr(0, star), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const int count = star == std::string::npos ? 1 : std::atoi(spec.c_str() + star + 1);
    messages.insert(messages.end(), static_cast<std::size_t>(count), bytes);
  }
  auto server = Serve(port);
  igtl::Socket::Pointer socket = Accept(server);
  socket->SetReceiveTimeout(100);
  std::atomic<bool> stop{ false };
  std::thread reader([&] {
    std::ofstream replies(repliesFile);
    std::ofstream raw(repliesFile + ".bin", std::ios::binary);
    unsigned char header[58];
    while (!stop)
    {
      if (socket->Receive(header, 58) != 58)
      {
        continue;
      }
      std::uint64_t body = 0;
      for (int i = 42; i < 50; ++i)
      {
        body = (body << 8) | header[i];
      }
      std::vector<char> rest(static_cast<std::size_t>(body));
      if (body > 0 && socket->Receive(rest.data(), static_cast<int>(body)) != static_cast<int>(body))
      {
        break;
      }
      raw.write(reinterpret_cast<char*>(header), 58);
      raw.write(rest.data(), static_cast<std::streamsize>(rest.size()));
      raw.flush();
      replies << ((header[0] << 8) | header[1]) << " " << std::string(reinterpret_cast<char*>(header) + 2, 12).c_str() << " "
              << std::string(reinterpret_cast<char*>(header) + 14, 20).c_str() << std::endl;
    }
  });
  const auto start = Clock::now();
  for (std::size_t i = 0; i < messages.size(); ++i)
  {
    std::this_thread::sleep_until(start + std::chrono::microseconds(static_cast<long long>(1e6 * static_cast<double>(i) / rateHz)));
    Send(socket, messages[i]);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  stop = true;
  reader.join();
  socket->CloseSocket();
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "serve" && (argc == 7 || argc == 9))
  {
    return ServePoses(std::atoi(argv[2]), argv[3], std::atof(argv[4]), argv[5], argv[6], argc == 9 ? std::atoi(argv[7]) : -1,
      argc == 9 ? std::atoi(argv[8]) : 0);
  }
  if (mode == "hostile" && argc == 4)
  {
    return Hostile(std::atoi(argv[2]), argv[3]);
  }
  if (mode == "replay" && argc >= 6)
  {
    return Replay(std::atoi(argv[2]), std::atof(argv[3]), argv[4], std::vector<std::string>(argv + 5, argv + argc));
  }
  std::cerr << "usage: vp_igtl_peer serve PORT POSES.csv RATE_HZ DEVICE SENT.csv [PAUSE_AFTER PAUSE_MS] | hostile PORT DEVICE"
               " | replay PORT RATE_HZ REPLIES.txt FILE[*COUNT]...\n";
  return 2;
}
