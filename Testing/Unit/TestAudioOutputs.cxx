// The sound outputs (issue 52): the sonification table and its file, and a recording tracked with
// --audio-wav and --osc: the WAV analysed (silence while safe, beeps faster from caution to
// danger, a tone in the breach, the two-tone of tracking lost) and liblo's own oscdump receiving
// the frames' values as frames.csv has them.
#include "vpAnalyticShapes.h"
#include "vpInputError.h"
#include "vpModelTestSupport.h"
#include "vpSonification.h"
#include "vpWavAudioOutput.h"
#include "vpTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace
{
using vp::test::RunTool;
using vp::test::Slurp;

TEST(Sonification, TheDefaultTableAndAFileOverIt)
{
  const vp::Sonification s = vp::Sonification::Default();
  EXPECT_TRUE(s.ForLevel(vp::DangerLevel::Safe).Silent());
  EXPECT_TRUE(s.ForMargin(vp::MarginLevel::Clear).Silent());
  // Beeps faster and higher from caution to danger; a tone inside.
  EXPECT_EQ(s.ForLevel(vp::DangerLevel::Caution).BeepsPerSecond, 2.0);
  EXPECT_EQ(s.ForLevel(vp::DangerLevel::Warning).BeepsPerSecond, 4.0);
  EXPECT_EQ(s.ForLevel(vp::DangerLevel::Danger).BeepsPerSecond, 8.0);
  EXPECT_LT(s.ForLevel(vp::DangerLevel::Caution).PitchHz, s.ForLevel(vp::DangerLevel::Warning).PitchHz);
  EXPECT_LT(s.ForLevel(vp::DangerLevel::Warning).PitchHz, s.ForLevel(vp::DangerLevel::Danger).PitchHz);
  EXPECT_TRUE(s.ForLevel(vp::DangerLevel::Breach).Continuous());
  EXPECT_EQ(s.ForMargin(vp::MarginLevel::Violated).Wave, vp::Timbre::Triangle);
  EXPECT_EQ(s.ForLost().AltPitchHz, 784.0);

  const std::string tmp = vp::test::MakeTempDir("sonification");
  std::ofstream(tmp + "/sound.json") << R"({"levels": {"caution": {"beeps_per_second": 1.5, "timbre": "triangle"}},
    "lost": {"pitch_hz": 500}})";
  const vp::Sonification read = vp::Sonification::Read(tmp + "/sound.json");
  EXPECT_EQ(read.ForLevel(vp::DangerLevel::Caution).BeepsPerSecond, 1.5);
  EXPECT_EQ(read.ForLevel(vp::DangerLevel::Caution).Wave, vp::Timbre::Triangle);
  EXPECT_EQ(read.ForLevel(vp::DangerLevel::Caution).PitchHz, 660.0) << "what the file leaves out stays";
  EXPECT_EQ(read.ForLost().PitchHz, 500.0);
  EXPECT_EQ(read.ForLost().AltPitchHz, 784.0);

  // Each bad entry is refused in one line naming the file and the entry.
  const std::pair<const char*, const char*> bad[] = {
    { R"({"levels": {"cuation": {}}})", "levels.cuation: unknown" },
    { R"({"levels": {"danger": {"pitch_hz": 10}}})", "levels.danger: a pitch of 10" },
    { R"({"levels": {"danger": {"timbre": "saw"}}})", "levels.danger.timbre: \"saw\" is not sine, square or triangle" },
    { R"({"margin": {"near": {"duty": 0}}})", "margin.near.duty: 0 would never sound" },
    { R"({"lost": {"gain": 2}})", "lost.gain: 2 is not a number from 0 to 1" },
    { R"({"volume": 1})", "volume: unknown" },
    { R"([1])", "not a JSON object" },
  };
  for (const auto& [text, expected] : bad)
  {
    std::ofstream(tmp + "/bad.json") << text;
    try
    {
      vp::Sonification::Read(tmp + "/bad.json");
      ADD_FAILURE() << text << " was accepted";
    }
    catch (const vp::InputError& e)
    {
      EXPECT_EQ(std::string(e.what()).rfind(tmp + "/bad.json: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(tmp);
}

// A recording longer than a WAV can hold is refused in one line naming the file, not attempted.
TEST(WavAudioOutput, ARecordingLongerThanAWavHoldsIsRefused)
{
  vp::WavAudioOutput wav("/tmp/never-written.wav", vp::Sonification::Default());
  vp::TrackedFrame frame;
  wav.OnFrame(frame);
  frame.TimeS = 2.0 * vp::WavAudioOutput::MaximumSeconds;
  wav.OnFrame(frame);
  try
  {
    wav.OnEnd();
    ADD_FAILURE() << "a 24 h WAV was attempted";
  }
  catch (const vp::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("/tmp/never-written.wav: the recording spans 24"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(vp::test::FileExists("/tmp/never-written.wav"));
}

/// The samples of a 16-bit mono PCM WAV, in [-1, 1], and its rate.
std::vector<double> ReadWav(const std::string& file, int& rateHz)
{
  const std::string bytes = Slurp(file);
  std::vector<double> samples;
  rateHz = 0;
  if (bytes.size() < 12 || bytes.compare(0, 4, "RIFF") != 0 || bytes.compare(8, 4, "WAVE") != 0)
  {
    return samples;
  }
  for (std::size_t at = 12; at + 8 <= bytes.size();)
  {
    std::uint32_t size = 0;
    std::memcpy(&size, bytes.data() + at + 4, 4);
    const std::string id = bytes.substr(at, 4);
    if (id == "fmt ")
    {
      std::uint16_t format = 0, channels = 0, bits = 0;
      std::memcpy(&format, bytes.data() + at + 8, 2);
      std::memcpy(&channels, bytes.data() + at + 10, 2);
      std::memcpy(&rateHz, bytes.data() + at + 12, 4);
      std::memcpy(&bits, bytes.data() + at + 22, 2);
      EXPECT_EQ(format, 1);
      EXPECT_EQ(channels, 1);
      EXPECT_EQ(bits, 16);
    }
    else if (id == "data")
    {
      for (std::size_t i = 0; i + 1 < size && at + 8 + i + 1 < bytes.size(); i += 2)
      {
        std::int16_t v = 0;
        std::memcpy(&v, bytes.data() + at + 8 + i, 2);
        samples.push_back(v / 32768.0);
      }
    }
    at += 8 + size + (size & 1);
  }
  return samples;
}

/// The loudness of each millisecond: its largest sample.
std::vector<double> Envelope(const std::vector<double>& samples, int rateHz, double fromS, double toS)
{
  std::vector<double> env;
  const std::size_t block = static_cast<std::size_t>(rateHz / 1000);
  for (auto i = static_cast<std::size_t>(fromS * rateHz); i + block <= std::min(samples.size(), static_cast<std::size_t>(toS * rateHz)); i += block)
  {
    double peak = 0.0;
    for (std::size_t k = i; k < i + block; ++k)
    {
      peak = std::max(peak, std::fabs(samples[k]));
    }
    env.push_back(peak);
  }
  return env;
}

/// Beeps that begin within the span, per second.
double OnsetsPerSecond(const std::vector<double>& samples, int rateHz, double fromS, double toS)
{
  int onsets = 0;
  bool on = true; // a beep already sounding at the start is not an onset
  for (double e : Envelope(samples, rateHz, fromS, toS))
  {
    onsets += !on && e > 0.05 ? 1 : 0;
    on = e > 0.05 ? true : e < 0.01 ? false : on;
  }
  return onsets / (toS - fromS);
}

/// The pitch of a span of a tone, from its zero crossings.
double PitchHz(const std::vector<double>& samples, int rateHz, double fromS, double toS)
{
  int crossings = 0;
  for (auto i = static_cast<std::size_t>(fromS * rateHz) + 1; i < static_cast<std::size_t>(toS * rateHz) && i < samples.size(); ++i)
  {
    crossings += (samples[i - 1] < 0.0) != (samples[i] < 0.0) ? 1 : 0;
  }
  return crossings / 2.0 / (toS - fromS);
}

class AudioOutputs : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = vp::test::MakeTempDir("audio");
    const double centre[3] = { 0, 0, 0 };
    this->Vessel = vp::test::WriteMeshFile(this->Dir, "portal_vein.stl", vp::MakeSphere(centre, 10.0, 48, 96));
    const double z[3] = { 0, 0, 1 };
    const double shaft[3] = { 0, 0, -40 };
    this->Tool = vp::test::WriteMeshFile(this->Dir, "Tool.stl", vp::MakeCappedCylinder(shaft, z, 1.5, 80.0, 16));
    std::ofstream(this->Dir + "/Tool.json") << R"({"tip_mm": [0, 0, 0], "axis": [0, 0, 1]})";
    this->Poses = this->WriteApproach();
  }
  void TearDown() override { std::filesystem::remove_all(this->Dir); }

  /// A PLUS recording in the folder at 20 Hz, the tool pointing down -x, its tip held at each
  /// phase's x for its count of frames (x 0: the tracker lost the tool, status MISSING).
  std::string WriteSequence(const std::string& name, const std::vector<std::pair<double, int>>& phases)
  {
    std::string text;
    int frame = 0;
    for (const auto& [x, count] : phases)
    {
      for (int i = 0; i < count; ++i, ++frame)
      {
        char line[300];
        std::snprintf(line, sizeof line,
          "Seq_Frame%04d_ToolToTrackerTransform = 0 0 -1 %g  0 1 0 0  1 0 0 0  0 0 0 1\n"
          "Seq_Frame%04d_ToolToTrackerTransformStatus = %s\nSeq_Frame%04d_Timestamp = %g\n",
          frame, x, frame, x == 0.0 ? "MISSING" : "OK", frame, 0.05 * frame);
        text += line;
      }
    }
    const std::string file = this->Dir + "/" + name;
    std::ofstream(file) << "ObjectType = Image\nNDims = 3\nDimSize = 0 0 " << frame
                        << "\nDefaultFrameTransformName = ToolToTrackerTransform\n"
                        << text << "ElementDataFile = LOCAL\n";
    return file;
  }

  /// The tip 15 mm off a sphere's wall (safe), then 7 (caution), 3.5 (warning), 1 (danger), 5 mm
  /// inside it (breach), the tool lost by the tracker for a second, then back at 15 mm.
  std::string WriteApproach()
  {
    this->LostFromS = 0.05 * 180;
    this->LostToS = 0.05 * 200;
    return this->WriteSequence("approach.igs.mha", { { 25.0, 30 }, { 17.0, 40 }, { 13.5, 40 }, { 11.0, 40 }, { 5.0, 30 }, { 0.0, 20 }, { 25.0, 20 } });
  }

  std::string Track(const std::string& extra)
  {
    return "track --vessels portal_vein=" + this->Vessel + " --scalpel " + this->Tool + " --poses " + this->Poses +
      " --no-surface -o " + this->Dir + "/run " + extra;
  }

  /// Each frame's time and level (frames.csv).
  std::vector<std::pair<double, std::string>> FrameLevels()
  {
    std::vector<std::pair<double, std::string>> levels;
    std::istringstream csv(Slurp(this->Dir + "/run/frames.csv"));
    std::string line;
    std::getline(csv, line);
    const std::vector<std::string> header = vp::test::SplitCsvLine(line);
    const auto level = std::find(header.begin(), header.end(), "danger_level") - header.begin();
    while (std::getline(csv, line))
    {
      const std::vector<std::string> cells = vp::test::SplitCsvLine(line);
      levels.emplace_back(std::stod(cells[1]), cells[level]);
    }
    return levels;
  }

  std::string Dir, Vessel, Tool, Poses;
  double LostFromS = 0.0, LostToS = 0.0;
};

// The WAV in the recording's time: silent while safe, beeps faster from caution through warning
// to danger (at the table's rates), a tone without a gap in the breach, the two-tone at the gap.
TEST_F(AudioOutputs, TheRecordingsSoundFollowsItsLevelsAndItsTrackingGap)
{
  const std::string wav = this->Dir + "/run.wav";
  const auto run = RunTool(this->Dir, this->Track("--audio-wav " + wav));
  ASSERT_EQ(run.ExitCode, 0) << run.Err;
  int rate = 0;
  const std::vector<double> samples = ReadWav(wav, rate);
  ASSERT_EQ(rate, 44100);
  const auto frames = this->FrameLevels();
  ASSERT_EQ(frames.size(), 200u) << "220 poses, 20 lost";
  EXPECT_NEAR(samples.size() / 44100.0, frames.back().first, 1e-3) << "from the first pose's time to the last's";

  // Each span of one level, from a little after it begins to where the next begins.
  std::map<std::string, double> rates;
  for (std::size_t i = 0; i < frames.size();)
  {
    std::size_t j = i;
    while (j < frames.size() && frames[j].second == frames[i].second)
    {
      ++j;
    }
    const double from = frames[i].first + 0.03;
    const double to = j < frames.size() ? std::min(frames[j].first, j > 0 && frames[j].first - frames[j - 1].first > 0.06 ? this->LostFromS : 1e9)
                                        : frames.back().first;
    const std::string level = frames[i].second;
    if (level == "safe")
    {
      const auto env = Envelope(samples, rate, from, to);
      EXPECT_LT(*std::max_element(env.begin(), env.end()), 1e-3) << "silence while safe, " << from << " to " << to << " s";
    }
    else if (level == "breach")
    {
      const auto env = Envelope(samples, rate, from, to);
      EXPECT_GT(*std::min_element(env.begin(), env.end()), 0.1) << "a tone without a gap in the breach";
    }
    else
    {
      rates[level] = OnsetsPerSecond(samples, rate, from, to);
    }
    i = j;
  }
  ASSERT_EQ(rates.size(), 3u);
  EXPECT_LT(rates["caution"], rates["warning"]);
  EXPECT_LT(rates["warning"], rates["danger"]);
  EXPECT_NEAR(rates["caution"], 2.0, 0.5);
  EXPECT_NEAR(rates["warning"], 4.0, 0.75);
  EXPECT_NEAR(rates["danger"], 8.0, 1.0);

  // Tracking lost: a tone that never stops, at 988 Hz, then 784 Hz, every half second.
  const auto lostEnv = Envelope(samples, rate, this->LostFromS + 0.02, this->LostToS - 0.01);
  EXPECT_GT(*std::min_element(lostEnv.begin(), lostEnv.end()), 0.1);
  EXPECT_NEAR(PitchHz(samples, rate, this->LostFromS + 0.02, this->LostFromS + 0.22), 988.0, 20.0);
  EXPECT_NEAR(PitchHz(samples, rate, this->LostFromS + 0.27, this->LostFromS + 0.47), 784.0, 20.0);

  const nlohmann::json summary = nlohmann::json::parse(Slurp(this->Dir + "/run/summary.json"));
  EXPECT_EQ(summary["outputs"]["audio_wav"]["written"], true);
  EXPECT_EQ(summary["outputs"]["audio_wav"]["starts_at_time_s"], 0.0);
}

// liblo's oscdump hears every message: each frame's distance as frames.csv has it (the newest
// wins when frames come faster than they are sent), every change of level in order, tracking
// lost and found again.
TEST_F(AudioOutputs, OscdumpReceivesTheFramesValues)
{
  const int port = vp::test::FreePort(SOCK_DGRAM);
  const std::string dump = this->Dir + "/oscdump.txt";
  const pid_t oscdump = vp::test::StartProgram("/usr/bin/oscdump", { "-L", std::to_string(port) }, dump);
  ASSERT_GT(oscdump, 0);
  usleep(300000); // oscdump binds its port
  // A tumour beside the path: its margin goes out too.
  const double lesion[3] = { 20.0, 9.0, 0.0 };
  const std::string tumour = vp::test::WriteMeshFile(this->Dir, "lesion.stl", vp::MakeSphere(lesion, 3.0, 24, 48));
  const auto run = RunTool(this->Dir, this->Track("--tumour " + tumour + " --osc 127.0.0.1:" + std::to_string(port)));
  usleep(200000);
  kill(oscdump, SIGTERM);
  waitpid(oscdump, nullptr, 0);
  ASSERT_EQ(run.ExitCode, 0) << run.Err;

  std::vector<std::string> levelNames, states;
  std::vector<std::pair<std::string, double>> distances;
  std::vector<std::pair<double, double>> margins; // level, signed mm
  std::istringstream lines(Slurp(dump));
  for (std::string line; std::getline(lines, line);)
  {
    std::istringstream words(line);
    std::string tag, address, types;
    words >> tag >> address >> types;
    if (address == "/vesselproximity/distance")
    {
      std::string name;
      double mm = 0.0;
      words >> name >> mm;
      distances.emplace_back(name, mm);
    }
    else if (address == "/vesselproximity/level")
    {
      double level = 0.0;
      std::string name;
      words >> level >> name;
      if (levelNames.empty() || levelNames.back() != name)
      {
        levelNames.push_back(name);
      }
    }
    else if (address == "/vesselproximity/margin")
    {
      double level = 0.0, mm = 0.0;
      std::string id;
      words >> level >> id >> mm;
      margins.emplace_back(level, mm);
    }
    else if (address == "/vesselproximity/state")
    {
      std::string state;
      words >> state;
      if (states.empty() || states.back() != state)
      {
        states.push_back(state);
      }
    }
  }
  // frames.csv: the nearest class, its distance and whether the tip is inside it.
  std::istringstream csv(Slurp(this->Dir + "/run/frames.csv"));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = vp::test::SplitCsvLine(line);
  const auto column = [&](const std::string& name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
  std::vector<double> signedMm;
  std::vector<std::string> frameLevels;
  std::vector<std::pair<std::string, double>> frameMargins;
  while (std::getline(csv, line))
  {
    const std::vector<std::string> cells = vp::test::SplitCsvLine(line);
    frameMargins.emplace_back(cells[column("margin_level")], std::stod(cells[column("tumour_mm")]));
    signedMm.push_back(std::stod(cells[column("nearest_mm")]) * (cells[column("portal_vein_inside")] == "1" ? -1.0 : 1.0));
    if (frameLevels.empty() || frameLevels.back() != cells[column("danger_level")])
    {
      frameLevels.push_back(cells[column("danger_level")]);
    }
  }
  ASSERT_FALSE(distances.empty()) << Slurp(dump).substr(0, 500);
  std::size_t row = 0;
  for (const auto& [name, mm] : distances)
  {
    EXPECT_EQ(name, "\"portal_vein\"");
    while (row < signedMm.size() && std::fabs(signedMm[row] - mm) > 1e-3)
    {
      ++row; // a frame whose distance a newer one replaced before it was sent
    }
    ASSERT_LT(row, signedMm.size()) << "a distance no frame had, or out of order: " << mm;
  }
  // Each margin message is a frame's: its level's number and the tip's signed distance.
  ASSERT_FALSE(margins.empty());
  std::size_t m = 0;
  for (const auto& [level, mm] : margins)
  {
    while (m < frameMargins.size() && !(std::fabs(frameMargins[m].second - mm) < 1e-3 &&
             frameMargins[m].first == vp::MarginLevelName(static_cast<vp::MarginLevel>(static_cast<int>(level)))))
    {
      ++m;
    }
    ASSERT_LT(m, frameMargins.size()) << "a margin no frame had: " << level << " " << mm;
  }
  for (std::string& name : levelNames)
  {
    name = name.substr(1, name.size() - 2); // oscdump quotes strings
  }
  EXPECT_EQ(levelNames, frameLevels);
  EXPECT_EQ(states, (std::vector<std::string>{ "\"tracking\"", "\"lost\"", "\"tracking\"" }));
  const nlohmann::json summary = nlohmann::json::parse(Slurp(this->Dir + "/run/summary.json"));
  EXPECT_EQ(summary["outputs"]["osc"]["failed"], 0);
  EXPECT_EQ(summary["outputs"]["osc"]["dropped_queue_full"], 0);
  const std::string received = Slurp(dump);
  EXPECT_EQ(summary["outputs"]["osc"]["sent"].get<std::size_t>(), static_cast<std::size_t>(std::count(received.begin(), received.end(), '\n')))
    << "every message sent was received";
}

// The shipped PureData patch, run headless, receives the voices the module sends as its table has
// them for each level, and plays the last one: the danger beeps, 8 a second.
TEST_F(AudioOutputs, TheShippedPureDataPatchPlaysWhatTheModuleSends)
{
  // Safe, caution, warning, then danger until the end: the patch keeps playing the danger voice.
  this->Poses = this->WriteSequence("levels.igs.mha", { { 25.0, 10 }, { 17.0, 10 }, { 13.5, 10 }, { 11.0, 10 } });
  std::filesystem::copy_file(std::string(VP_SOURCE_DIR) + "/Testing/Audio/PrintVoices.pd", this->Dir + "/PrintVoices.pd");
  const int port = vp::test::FreePort(SOCK_DGRAM);
  const std::string patches = std::string(VP_SOURCE_DIR) + "/Resources/Audio";
  const pid_t pd = vp::test::StartProgram("/usr/bin/pd",
    { "-nogui", "-nosound", "-noprefs", "-stderr", "-path", patches, "-open", patches + "/VesselProximity.pd", "-open",
      this->Dir + "/PrintVoices.pd", "-send", "vp-port " + std::to_string(port) },
    "/dev/null", this->Dir + "/pd.txt");
  ASSERT_GT(pd, 0);
  usleep(700000); // the patch opens its port
  const auto run = RunTool(this->Dir, this->Track("--osc 127.0.0.1:" + std::to_string(port)));
  int status = 0;
  waitpid(pd, &status, 0); // the listener quits after 8 s
  ASSERT_EQ(run.ExitCode, 0) << run.Err;

  // What the patch printed, each change once, against the table for the levels frames.csv has.
  const vp::Sonification table = vp::Sonification::Default();
  std::vector<std::vector<double>> expected;
  for (const auto& [timeS, level] : this->FrameLevels())
  {
    vp::DangerLevel l = vp::DangerLevel::Safe;
    for (int k = 0; k < vp::NumberOfDangerLevels; ++k)
    {
      l = level == vp::DangerLevelName(static_cast<vp::DangerLevel>(k)) ? static_cast<vp::DangerLevel>(k) : l;
    }
    const vp::Voice& v = table.ForLevel(l);
    const std::vector<double> voice = { v.PitchHz, v.AltPitchHz, v.BeepsPerSecond, v.Duty, double(static_cast<int>(v.Wave)),
      v.Silent() ? 0.0 : v.Gain };
    if (expected.empty() || expected.back() != voice)
    {
      expected.push_back(voice);
    }
  }
  std::vector<std::vector<double>> printed;
  std::istringstream lines(Slurp(this->Dir + "/pd.txt"));
  for (std::string line; std::getline(lines, line);)
  {
    if (line.rfind("vessel: ", 0) != 0)
    {
      continue;
    }
    std::istringstream values(line.substr(8));
    std::vector<double> voice;
    for (double v; values >> v;)
    {
      voice.push_back(v);
    }
    if (printed.empty() || printed.back() != voice)
    {
      printed.push_back(voice);
    }
  }
  ASSERT_EQ(printed.size(), expected.size()) << Slurp(this->Dir + "/pd.txt");
  for (std::size_t i = 0; i < printed.size(); ++i)
  {
    ASSERT_EQ(printed[i].size(), 6u);
    for (std::size_t k = 0; k < 6; ++k)
    {
      EXPECT_NEAR(printed[i][k], expected[i][k], 1e-4) << "voice " << i << " value " << k;
    }
  }
  // What it played: silence before the first message, then beeps; its last second the danger
  // voice's 8 beeps a second.
  int rate = 0;
  const std::vector<double> samples = ReadWav(this->Dir + "/pd-recording.wav", rate);
  ASSERT_EQ(rate, 44100) << Slurp(this->Dir + "/pd.txt");
  const double lengthS = samples.size() / 44100.0;
  ASSERT_GT(lengthS, 7.0);
  const auto start = Envelope(samples, rate, 0.0, 0.3);
  EXPECT_LT(*std::max_element(start.begin(), start.end()), 1e-3) << "silence before anything was sent";
  EXPECT_NEAR(OnsetsPerSecond(samples, rate, lengthS - 2.0, lengthS - 0.01), 8.0, 1.0);
}

// live --audio through ALSA: a sound device defined by the user's asoundrc (a file plugin over the
// null device) hears the served recording's danger as 8 beeps a second; with no device there,
// the run says so once and tracks on in silence.
TEST_F(AudioOutputs, LiveAudioPlaysOnTheSoundDeviceAndGoesOnWithoutOne)
{
  // Two seconds safe, then two in danger.
  const std::string recording = this->WriteSequence("served.igs.mha", { { 25.0, 40 }, { 11.0, 40 } });
  const std::string raw = this->Dir + "/device.raw";
  std::ofstream(this->Dir + "/.asoundrc") << "pcm.!default { type file slave.pcm \"null\" file \"" << raw << "\" format \"raw\" }\n";
  std::filesystem::create_directories(this->Dir + "/nodevice");
  std::ofstream(this->Dir + "/nodevice/.asoundrc") << "pcm.!default { type hw card 29 }\n";
  for (const bool device : { true, false })
  {
    const int port = vp::test::FreePort();
    const std::string out = this->Dir + (device ? "/with" : "/without");
    const pid_t server = vp::test::StartProgram(VP_EXECUTABLE,
      { "serve", "--poses", recording, "--igtl-listen", std::to_string(port), "--device", "ToolToTracker" }, "/dev/null", out + ".serve");
    ASSERT_TRUE(vp::test::WaitForText(out + ".serve", "waiting for a client")) << Slurp(out + ".serve");
    const auto live = RunTool(this->Dir,
      "live --vessels portal_vein=" + this->Vessel + " --scalpel " + this->Tool + " --no-surface --tool-name ToolToTracker --igtl 127.0.0.1:" +
        std::to_string(port) + " --duration-s 4.5 --audio -o " + out,
      "HOME=" + this->Dir + (device ? "" : "/nodevice"));
    vp::test::WaitFor(server, 10.0);
    ASSERT_EQ(live.ExitCode, 0) << live.Err;
    const nlohmann::json summary = nlohmann::json::parse(Slurp(out + "/summary.json"));
    const nlohmann::json audio = summary.at("outputs").at("audio");
    if (!device)
    {
      const std::string said = "no sound device";
      EXPECT_EQ(live.Err.find(said), live.Err.rfind(said)) << "said once: " << live.Err;
      EXPECT_NE(live.Err.find("live: audio: no sound device 'default' ("), std::string::npos) << live.Err;
      EXPECT_NE(live.Err.find("): tracking goes on without sound"), std::string::npos) << live.Err;
      EXPECT_EQ(summary.at("frames").get<int>(), 80) << "tracking went on";
      EXPECT_NE(audio.at("problem").get<std::string>().find("no sound device"), std::string::npos);
      EXPECT_EQ(audio.at("played_s").get<double>(), 0.0);
      continue;
    }
    EXPECT_EQ(audio.at("problem"), "") << live.Err;
    EXPECT_GT(audio.at("played_s").get<double>(), 3.0);
    // The device's samples (32-bit float): silence first, then the danger voice's beeps.
    const std::string bytes = Slurp(raw);
    std::vector<double> samples(bytes.size() / 4);
    for (std::size_t i = 0; i < samples.size(); ++i)
    {
      float v = 0.0f;
      std::memcpy(&v, bytes.data() + 4 * i, 4);
      samples[i] = v;
    }
    const double lengthS = samples.size() / 44100.0;
    ASSERT_GT(lengthS, 3.0);
    const auto start = Envelope(samples, 44100, 0.0, 0.5);
    EXPECT_LT(*std::max_element(start.begin(), start.end()), 1e-3) << "silence while safe";
    double best = 0.0; // the danger's second, wherever the stream's start put it
    for (double from = 1.5; from + 1.0 < lengthS; from += 0.25)
    {
      best = std::max(best, OnsetsPerSecond(samples, 44100, from, from + 1.0));
    }
    EXPECT_NEAR(best, 8.0, 1.0);
  }
}

// The outputs' options are refused in one line naming the option, before anything is computed.
TEST_F(AudioOutputs, BadOutputOptionsAreRefusedInOneLine)
{
  const std::pair<std::string, std::string> bad[] = {
    { "--osc localhost", "--osc: 'localhost' is not HOST:PORT" },
    { "--osc 127.0.0.1:70000", "--osc: '127.0.0.1:70000' is not HOST:PORT" },
    { "--osc no-such-host.invalid:9000", "--osc: no-such-host.invalid:" },
    { "--sonification " + this->Dir + "/missing.json", this->Dir + "/missing.json: no such file" },
  };
  for (const auto& [option, expected] : bad)
  {
    const auto run = RunTool(this->Dir, this->Track(option));
    EXPECT_EQ(run.ExitCode, 1) << option;
    EXPECT_EQ(std::count(run.Err.begin(), run.Err.end(), '\n'), 1) << run.Err;
    EXPECT_NE(run.Err.find(expected), std::string::npos) << run.Err;
    EXPECT_FALSE(vp::test::FileExists(this->Dir + "/run/summary.json")) << option;
  }
}

// The sound is written after the frames: a WAV named as one of the run's inputs (by its own
// name, by another path to it, by a hard link) would have replaced it with sound.
TEST_F(AudioOutputs, AWavNeverReplacesTheRunsInputs)
{
  std::filesystem::create_directory(this->Dir + "/sub");
  std::filesystem::create_hard_link(this->Poses, this->Dir + "/poses-link.csv");
  const std::string sonification = this->Dir + "/sound.json";
  std::ofstream(sonification) << R"({"levels": {"danger": {"gain": 0.5}}})";
  const std::string posesBefore = Slurp(this->Poses);
  const std::pair<std::string, std::string> inputs[] = {
    { this->Poses, "an input of this run" },
    { this->Dir + "/sub/../" + std::filesystem::path(this->Poses).filename().string(), "the run's input '" + this->Poses + "'" },
    { this->Dir + "/poses-link.csv", "the run's input '" + this->Poses + "'" },
    { this->Vessel, "an input of this run" },
    { this->Dir + "/Tool.json", "an input of this run" },
    { sonification, "an input of this run" },
  };
  for (const auto& [wav, replaced] : inputs)
  {
    const auto run = RunTool(this->Dir, this->Track("--sonification " + sonification + " --audio-wav " + wav));
    EXPECT_EQ(run.ExitCode, 1) << wav;
    EXPECT_EQ(std::count(run.Err.begin(), run.Err.end(), '\n'), 1) << run.Err;
    EXPECT_NE(run.Err.find("--audio-wav: '" + wav + "' would replace " + replaced), std::string::npos) << run.Err;
    EXPECT_FALSE(vp::test::FileExists(this->Dir + "/run/summary.json")) << wav;
  }
  EXPECT_EQ(Slurp(this->Poses), posesBefore);
  // Beside the inputs, the sound is written as asked.
  const auto run = RunTool(this->Dir, this->Track("--audio-wav " + this->Dir + "/sub/run.wav"));
  EXPECT_EQ(run.ExitCode, 0) << run.Err;
  EXPECT_TRUE(vp::test::FileExists(this->Dir + "/sub/run.wav"));
}
} // namespace
