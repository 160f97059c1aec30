// OpenIGTLink header versions 1 and 2 (issue 53): every message of ../shared/data/igtl (written
// by the OpenIGTLink 3 library itself) read with the values its manifest gives, the ones we write
// written byte for byte as the library wrote them, and a pose whose status is not OK taken as lost.
#include "vpAnalyticShapes.h"
#include "vpIgtlMessages.h"
#include "vpModelTestSupport.h"
#include "vpPoseReading.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <tuple>

namespace
{
using vp::test::Slurp;

struct Message
{
  std::string Bytes;
  const unsigned char* Header() const { return reinterpret_cast<const unsigned char*>(this->Bytes.data()); }
  std::vector<unsigned char> Body() const { return std::vector<unsigned char>(this->Bytes.begin() + vp::IgtlHeaderBytes, this->Bytes.end()); }
};

class IgtlVersion2 : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const std::string data = vp::test::TestDataDir();
    if (data.empty() || !std::filesystem::exists(data + "/igtl/manifest.json"))
    {
      GTEST_SKIP() << "VP_TEST_DATA not set: the OpenIGTLink messages are in ../shared/data/igtl";
    }
    this->Folder = data + "/igtl/";
    this->Manifest = nlohmann::json::parse(Slurp(this->Folder + "manifest.json"));
  }
  Message Read(const std::string& file) const { return { Slurp(this->Folder + file) }; }
  std::string Folder;
  nlohmann::json Manifest;
};

/// OpenIGTLink's CRC (ECMA-182: polynomial 0x42F0E1EBA9EA3693, init 0, not reflected), written
/// here from the protocol, independently of the code under test, put into the header.
void Restamp(std::string& message)
{
  std::uint64_t crc = 0;
  for (std::size_t i = vp::IgtlHeaderBytes; i < message.size(); ++i)
  {
    crc ^= static_cast<std::uint64_t>(static_cast<unsigned char>(message[i])) << 56;
    for (int b = 0; b < 8; ++b)
    {
      crc = crc & (1ull << 63) ? (crc << 1) ^ 0x42F0E1EBA9EA3693ull : crc << 1;
    }
  }
  for (int k = 0; k < 8; ++k)
  {
    message[50 + static_cast<std::size_t>(k)] = static_cast<char>((crc >> (56 - 8 * k)) & 0xff);
  }
}

std::uint64_t Hex(const std::string& text)
{
  return std::stoull(text, nullptr, 16);
}

void ExpectMatrix(const std::array<double, 16>& m, const nlohmann::json& rows, const std::string& what)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      // float32 printed with %.9g: equal once both are float32
      EXPECT_EQ(static_cast<float>(m[static_cast<std::size_t>(4 * r + c)]), rows[r][c].get<float>()) << what << " [" << r << "][" << c << "]";
    }
  }
}

/// The packing a file's header and metadata say.
vp::IgtlPacking PackingOf(const nlohmann::json& entry)
{
  vp::IgtlPacking packing;
  packing.Version = entry["header_version"].get<unsigned>();
  packing.TimeSeconds = entry["timestamp"]["seconds"].get<std::uint32_t>();
  packing.TimeFraction = entry["timestamp"]["fraction"].get<std::uint32_t>();
  packing.MessageId = entry["message_id"].is_null() ? 0 : entry["message_id"].get<std::uint32_t>();
  for (const auto& m : entry["metadata"].is_null() ? nlohmann::json::array() : entry["metadata"])
  {
    packing.Metadata.push_back({ m["key"].get<std::string>(), m["value"].get<std::string>(), m["encoding"].get<unsigned>() });
  }
  return packing;
}

// Every file: its header, its version-2 sections (message id, metadata with encodings) and its
// content as the manifest gives them.
TEST_F(IgtlVersion2, EveryMessageIsReadWithItsValues)
{
  ASSERT_EQ(this->Manifest["files"].size(), 23u);
  for (const auto& entry : this->Manifest["files"])
  {
    const std::string file = entry["file"];
    SCOPED_TRACE(file);
    const Message m = this->Read(file);
    ASSERT_EQ(m.Bytes.size(), entry["file_size"].get<std::size_t>());
    const vp::IgtlHeader h = vp::ParseIgtlHeader(m.Header());
    EXPECT_EQ(h.Version, entry["header_version"].get<unsigned>());
    EXPECT_EQ(h.Type, entry["message_type"].get<std::string>());
    EXPECT_EQ(h.Device, entry["device_name"].get<std::string>());
    EXPECT_EQ(h.TimeSeconds, entry["timestamp"]["seconds"].get<std::uint32_t>());
    EXPECT_EQ(h.TimeFraction, entry["timestamp"]["fraction"].get<std::uint32_t>());
    EXPECT_EQ(h.BodyBytes, entry["body_size"].get<std::uint64_t>());
    EXPECT_EQ(h.Crc, Hex(entry["crc64"]));
    vp::IgtlBody split;
    ASSERT_EQ(vp::SplitIgtlBody(m.Header(), m.Body(), split), "");
    if (h.Version == 2)
    {
      EXPECT_EQ(split.MessageId, entry["message_id"].get<std::uint32_t>());
      EXPECT_EQ(vp::ToIgtlVersion2(std::string(58, '\0'), {}, 0).size(), 58u + 12u + 2u) << "an empty metadata block";
    }
    const nlohmann::json metadata = entry["metadata"].is_null() ? nlohmann::json::array() : entry["metadata"];
    ASSERT_EQ(split.Metadata.size(), metadata.size());
    for (std::size_t i = 0; i < metadata.size(); ++i)
    {
      EXPECT_EQ(split.Metadata[i].Key, metadata[i]["key"].get<std::string>());
      EXPECT_EQ(split.Metadata[i].Value, metadata[i]["value"].get<std::string>());
      EXPECT_EQ(split.Metadata[i].Encoding, metadata[i]["encoding"].get<unsigned>());
    }
    const nlohmann::json& content = entry["content"];
    if (h.Type == "TRANSFORM")
    {
      std::array<double, 16> matrix{};
      ASSERT_EQ(vp::DecodeIgtlTransform(m.Header(), m.Body(), matrix), "");
      ExpectMatrix(matrix, content["matrix"], file);
    }
    else if (h.Type == "STATUS")
    {
      vp::IgtlStatus status;
      ASSERT_EQ(vp::DecodeIgtlStatus(m.Header(), m.Body(), status), "");
      EXPECT_EQ(status.Code, content["code"].get<int>());
      EXPECT_EQ(status.Subcode, content["subcode"].get<long long>());
      EXPECT_EQ(status.ErrorName, content["error_name"].get<std::string>());
      EXPECT_EQ(status.Text, content["status_string"].get<std::string>());
    }
    else if (h.Type == "STRING")
    {
      unsigned encoding = 0;
      std::string text;
      ASSERT_EQ(vp::DecodeIgtlString(m.Header(), m.Body(), encoding, text), "");
      EXPECT_EQ(encoding, content["encoding"].get<unsigned>());
      EXPECT_EQ(text, content["string"].get<std::string>());
    }
    else if (h.Type == "POINT")
    {
      std::vector<vp::IgtlPoint> points;
      ASSERT_EQ(vp::DecodeIgtlPoints(m.Header(), m.Body(), points), "");
      ASSERT_EQ(points.size(), content["points"].size());
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        const auto& p = content["points"][i];
        EXPECT_EQ(points[i].Name, p["name"].get<std::string>());
        EXPECT_EQ(points[i].Group, p["group"].get<std::string>());
        EXPECT_EQ(points[i].Owner, p["owner"].get<std::string>());
        EXPECT_EQ(static_cast<float>(points[i].RadiusMm), p["radius"].get<float>());
        for (int k = 0; k < 4; ++k)
        {
          EXPECT_EQ(points[i].Rgba[k], p["rgba"][k].get<int>());
        }
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(static_cast<float>(points[i].PositionMm[k]), p["position"][k].get<float>());
        }
      }
    }
    else
    {
      std::vector<vp::IgtlTool> tools;
      ASSERT_EQ(vp::DecodeIgtlTools(m.Header(), m.Body(), tools), "");
      ASSERT_EQ(tools.size(), content["tools"].size());
      for (std::size_t i = 0; i < tools.size(); ++i)
      {
        const auto& t = content["tools"][i];
        EXPECT_EQ(tools[i].Name, t["name"].get<std::string>());
        EXPECT_EQ(tools[i].Type, t["type"].get<int>());
        if (h.Type == "TDATA")
        {
          ExpectMatrix(tools[i].Matrix, t["matrix"], file);
          continue;
        }
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(static_cast<float>(tools[i].PositionMm[k]), t["position"][k].get<float>());
        }
        for (int k = 0; k < 4; ++k)
        {
          EXPECT_EQ(static_cast<float>(tools[i].QuaternionXyzw[k]), t["quaternion_xyzw"][k].get<float>());
        }
      }
    }
  }
}

// What we write (TRANSFORM, STRING, POINT, STATUS), in either version, is byte for byte what the
// library wrote for the same content, time stamp, metadata and message id.
TEST_F(IgtlVersion2, WhatWeWriteIsTheLibrarysBytes)
{
  int compared = 0;
  for (const auto& entry : this->Manifest["files"])
  {
    const std::string file = entry["file"], type = entry["message_type"], device = entry["device_name"];
    if (entry["origin"] != "library Pack()" || type == "TDATA" || type == "QTDATA")
    {
      continue;
    }
    SCOPED_TRACE(file);
    const nlohmann::json& content = entry["content"];
    const vp::IgtlPacking packing = PackingOf(entry);
    std::string written;
    if (type == "TRANSFORM")
    {
      std::array<double, 16> matrix{};
      for (int r = 0; r < 4; ++r)
      {
        for (int c = 0; c < 4; ++c)
        {
          matrix[static_cast<std::size_t>(4 * r + c)] = content["matrix"][r][c].get<float>();
        }
      }
      written = vp::PackIgtlTransform(device, matrix, packing);
    }
    else if (type == "STRING")
    {
      written = vp::PackIgtlString(device, content["string"], content["encoding"].get<unsigned>(), packing);
    }
    else if (type == "STATUS")
    {
      vp::IgtlStatus status{ content["code"].get<int>(), content["subcode"].get<long long>(), content["error_name"], content["status_string"] };
      written = vp::PackIgtlStatus(device, status, packing);
    }
    else
    {
      std::vector<vp::IgtlPoint> points;
      for (const auto& p : content["points"])
      {
        vp::IgtlPoint point;
        point.Name = p["name"];
        point.Group = p["group"];
        point.Owner = p["owner"];
        point.RadiusMm = p["radius"].get<float>();
        for (int k = 0; k < 4; ++k)
          point.Rgba[k] = static_cast<unsigned char>(p["rgba"][k].get<int>());
        for (int k = 0; k < 3; ++k)
          point.PositionMm[k] = p["position"][k].get<float>();
        points.push_back(point);
      }
      written = vp::PackIgtlPoints(device, points, packing);
    }
    EXPECT_EQ(written, this->Read(file).Bytes);
    ++compared;
  }
  EXPECT_EQ(compared, 18);
}

// A pose whose status says the tracker does not see the tool (PLUS's MISSING with the identity it
// sends, a TDATA or QTDATA element's status) is a lost pose, never a frame; OK, no status, a
// larger extended header: the pose.
TEST_F(IgtlVersion2, APoseTheTrackerDoesNotSeeIsLost)
{
  const vp::SettledReading reading = vp::SettlePoseReading(vp::PoseReading());
  const auto decode = [&](const std::string& file, const std::string& tool) {
    const Message m = this->Read(file);
    return vp::DecodeIgtlPose(m.Header(), m.Body(), tool, reading);
  };
  for (const char* file : { "transform_v1.bin", "transform_v2_slicer.bin", "transform_v2_plus_ok.bin", "transform_v2_nometa.bin",
         "transform_v2_msgid.bin", "transform_v2_exthdr16.bin" })
  {
    const vp::IgtlPoseMessage p = decode(file, "StylusToTracker");
    ASSERT_EQ(p.What, vp::IgtlPoseMessage::Verdict::Pose) << file << ": " << p.Reason;
    EXPECT_FALSE(p.Pose.Lost) << file;
    EXPECT_NEAR(p.Pose.ModelToWorld[3], 10.5, 1e-6) << file;
    EXPECT_NEAR(p.Pose.ModelToWorld[7], -20.25, 1e-6) << file;
    EXPECT_EQ(p.Pose.SourceClockS, 1700000000.5) << file << ": the header's time stamp";
  }
  const vp::IgtlPoseMessage missing = decode("transform_v2_plus_missing.bin", "StylusToTracker");
  ASSERT_EQ(missing.What, vp::IgtlPoseMessage::Verdict::Pose);
  EXPECT_TRUE(missing.Pose.Lost);
  EXPECT_FALSE(decode("tdata_v2.bin", "StylusToTracker").Pose.Lost);
  EXPECT_TRUE(decode("tdata_v2.bin", "ProbeToTracker").Pose.Lost) << "ProbeToTrackerStatus = MISSING";
  EXPECT_FALSE(decode("qtdata_v2.bin", "StylusToTracker").Pose.Lost);
  EXPECT_TRUE(decode("qtdata_v2.bin", "ProbeToTracker").Pose.Lost) << "ProbeToTrackerStatus = OUT_OF_VIEW";
  EXPECT_FALSE(decode("qtdata_v1.bin", "ProbeToTracker").Pose.Lost) << "version 1 has no status: seen";

  // A byte changed anywhere in a version-2 body (its metadata too) fails the CRC; sections that do
  // not add up are refused, never read past.
  Message bent = this->Read("transform_v2_slicer.bin");
  bent.Bytes[bent.Bytes.size() - 3] ^= 0x20;
  EXPECT_EQ(vp::DecodeIgtlPose(bent.Header(), bent.Body(), "StylusToTracker", reading).Reason, "bad CRC");
  for (const auto& [offset, value, expected] : { std::make_tuple(58 + 5, 0xff, "a version-2 body whose sections do not add up"),
         std::make_tuple(58 + 1, 3, "a version-2 body whose sections do not add up"),
         std::make_tuple(58 + 12 + 48 + 1, 2, "a version-2 metadata header of the wrong size") })
  {
    Message lying = this->Read("transform_v2_msgid.bin");
    lying.Bytes[static_cast<std::size_t>(offset)] = static_cast<char>(value);
    Restamp(lying.Bytes); // a CRC that fits: the sections themselves must be checked
    vp::IgtlBody split;
    EXPECT_EQ(vp::SplitIgtlBody(lying.Header(), lying.Body(), split), expected) << offset;
  }
}

// Content that lies about itself is refused, never read past: a STRING whose length field
// exceeds its bytes, a STATUS whose text has no end; and a tool name that fills its 20 bytes
// (which the library's element loses) is read whole and tracked.
TEST_F(IgtlVersion2, LyingContentIsRefusedAndAWholeNameIsRead)
{
  Message text = this->Read("string_v1_ascii.bin");
  text.Bytes[58 + 2] = static_cast<char>(0xff); // the length field: 65,280 bytes and more
  Restamp(text.Bytes);
  unsigned encoding = 0;
  std::string read;
  EXPECT_EQ(vp::DecodeIgtlString(text.Header(), text.Body(), encoding, read), "a STRING body that cannot be read");

  Message status = this->Read("status_v1_full.bin");
  status.Bytes.back() = 'x'; // the text's end gone
  Restamp(status.Bytes);
  vp::IgtlStatus fields;
  EXPECT_EQ(vp::DecodeIgtlStatus(status.Header(), status.Body(), fields), "a STATUS body that cannot be read");

  Message tools = this->Read("tdata_v1.bin");
  const std::string name = "StylusToTrackerTool1"; // 20 bytes, no room for an end
  ASSERT_EQ(name.size(), vp::IgtlDeviceNameBytes);
  std::copy(name.begin(), name.end(), tools.Bytes.begin() + 58);
  Restamp(tools.Bytes);
  std::vector<vp::IgtlTool> read2;
  ASSERT_EQ(vp::DecodeIgtlTools(tools.Header(), tools.Body(), read2), "");
  EXPECT_EQ(read2.at(0).Name, name);
  const vp::IgtlPoseMessage pose =
    vp::DecodeIgtlPose(tools.Header(), tools.Body(), name, vp::SettlePoseReading(vp::PoseReading()));
  EXPECT_EQ(pose.What, vp::IgtlPoseMessage::Verdict::Pose) << pose.Reason;
}

// A peer configured as 3D Slicer and PlusServer are by default: its version-2 STATUS on connect,
// then version-2 TRANSFORMs with their status (PLUS's MISSING for a tool it does not see, with
// the identity): every OK pose is a frame, every MISSING one a lost pose, and the peer is answered
// in version 2 from its first message on.
TEST_F(IgtlVersion2, ASlicerConfiguredPeersStreamIsTrackedAndAnsweredInVersion2)
{
  const std::string dir = vp::test::MakeTempDir("igtl_v2_live");
  const double centre[3] = { 10.5, -20.25, 50.0 };
  const std::string vessel = vp::test::WriteMeshFile(dir, "portal_vein.stl", vp::MakeSphere(centre, 10.0, 24, 48));
  const int port = vp::test::FreePort();
  const pid_t peer = vp::test::StartProgram(VP_IGTL_PEER,
    { "replay", std::to_string(port), "50", dir + "/replies.txt", this->Folder + "status_v2_connect.bin",
      this->Folder + "transform_v2_slicer.bin*20", this->Folder + "transform_v2_plus_missing.bin*10",
      this->Folder + "transform_v2_plus_ok.bin*20" },
    dir + "/peer.out", dir + "/peer.err");
  ASSERT_TRUE(vp::test::WaitForText(dir + "/peer.out", "port ")) << vp::test::Slurp(dir + "/peer.err");
  const auto live = vp::test::RunTool(dir, "live --vessels portal_vein=" + vessel + " --scalpel " + std::string(VP_SOURCE_DIR) +
      "/Resources/CusaHandpiece.stl --no-surface --tool-name StylusToTracker --igtl 127.0.0.1:" + std::to_string(port) +
      " --results-to tracker --duration-s 2.5 -o " + dir + "/out");
  EXPECT_EQ(vp::test::WaitFor(peer, 10.0), 0) << vp::test::Slurp(dir + "/peer.err");
  ASSERT_EQ(live.ExitCode, 0) << live.Err;
  const nlohmann::json summary = nlohmann::json::parse(Slurp(dir + "/out/summary.json"));
  EXPECT_EQ(summary["frames"], 40) << summary.dump();
  EXPECT_EQ(summary["poses_lost"], 11) << "ten MISSING, and the stream gone quiet once it ended";
  EXPECT_EQ(summary["link"]["poses_not_seen_by_the_tracker"], 10);
  EXPECT_EQ(summary["link"]["version_2_peers"], 1);
  EXPECT_EQ(summary["link"]["rejected"].size(), 0u) << summary["link"].dump();
  // Its replies (asked for with --results-to tracker): every result in version 2, and no request
  // to start streaming (STT_TDATA), since it streamed at once as PlusServer does.
  std::istringstream replies(Slurp(dir + "/replies.txt"));
  int version2 = 0;
  for (std::string line; std::getline(replies, line);)
  {
    EXPECT_EQ(line[0], '2') << line;
    EXPECT_EQ(line.find("STT_"), std::string::npos) << line;
    version2 += line[0] == '2' ? 1 : 0;
  }
  EXPECT_GT(version2, 40);
  // Each reply's header carries the pose's own time stamp (the peer's messages: 1700000000.5 s),
  // its metadata the time it was sent.
  const std::string raw = Slurp(dir + "/replies.txt.bin");
  int stamped = 0;
  for (std::size_t at = 0; at + vp::IgtlHeaderBytes <= raw.size();)
  {
    const auto* header = reinterpret_cast<const unsigned char*>(raw.data() + at);
    const vp::IgtlHeader h = vp::ParseIgtlHeader(header);
    const std::vector<unsigned char> body(raw.begin() + static_cast<std::ptrdiff_t>(at + vp::IgtlHeaderBytes),
      raw.begin() + static_cast<std::ptrdiff_t>(at + vp::IgtlHeaderBytes + h.BodyBytes));
    vp::IgtlBody split;
    ASSERT_EQ(vp::SplitIgtlBody(header, body, split), "");
    const std::string* sent = split.Find("ReplyTime");
    ASSERT_NE(sent, nullptr) << h.Type << " " << h.Device;
    EXPECT_NEAR(std::stod(*sent), static_cast<double>(std::time(nullptr)), 30.0);
    if (h.Type == "TRANSFORM")
    {
      EXPECT_EQ(h.TimeSeconds, 1700000000u);
      EXPECT_EQ(h.TimeFraction, 0x80000000u);
      ++stamped;
    }
    at += vp::IgtlHeaderBytes + h.BodyBytes;
  }
  EXPECT_GT(stamped, 0) << "the closest points' transforms";

  // By default the tracker is sent nothing at all (a PlusServer would log each unknown type).
  const int again = vp::test::FreePort();
  const pid_t quiet = vp::test::StartProgram(VP_IGTL_PEER,
    { "replay", std::to_string(again), "50", dir + "/quiet.txt", this->Folder + "transform_v2_slicer.bin*20" }, dir + "/quiet.out",
    "/dev/null");
  ASSERT_TRUE(vp::test::WaitForText(dir + "/quiet.out", "port "));
  const auto byDefault = vp::test::RunTool(dir, "live --vessels portal_vein=" + vessel + " --scalpel " + std::string(VP_SOURCE_DIR) +
      "/Resources/CusaHandpiece.stl --no-surface --tool-name StylusToTracker --igtl 127.0.0.1:" + std::to_string(again) +
      " --duration-s 1.2");
  EXPECT_EQ(vp::test::WaitFor(quiet, 10.0), 0);
  ASSERT_EQ(byDefault.ExitCode, 0) << byDefault.Err;
  EXPECT_NE(byDefault.Out.find("20 frames"), std::string::npos) << byDefault.Out;
  EXPECT_EQ(Slurp(dir + "/quiet.txt"), "") << "the tracker was sent results (or a hello it did not need: it spoke version 2)";

  // A tracker that speaks version 1 (PlusServer to a new client) is told once, as Slicer tells it,
  // that we speak version 2: a version-2 STATUS, and nothing else.
  const int third = vp::test::FreePort();
  const pid_t v1 = vp::test::StartProgram(VP_IGTL_PEER,
    { "replay", std::to_string(third), "50", dir + "/hello.txt", this->Folder + "transform_v1.bin*10" }, dir + "/hello.out", "/dev/null");
  ASSERT_TRUE(vp::test::WaitForText(dir + "/hello.out", "port "));
  const auto hello = vp::test::RunTool(dir, "live --vessels portal_vein=" + vessel + " --scalpel " + std::string(VP_SOURCE_DIR) +
      "/Resources/CusaHandpiece.stl --no-surface --tool-name StylusToTracker --igtl 127.0.0.1:" + std::to_string(third) +
      " --duration-s 0.8");
  EXPECT_EQ(vp::test::WaitFor(v1, 10.0), 0);
  ASSERT_EQ(hello.ExitCode, 0) << hello.Err;
  EXPECT_EQ(Slurp(dir + "/hello.txt"), "2 STATUS \n");
  std::filesystem::remove_all(dir);
}
} // namespace
