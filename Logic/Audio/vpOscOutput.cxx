#include "vpOscOutput.h"

#include "vpClock.h"
#include "vpInputError.h"

#include <lo/lo.h>
#include <nlohmann/json.hpp>

#include <netdb.h>

#include <cmath>
#include <utility>

namespace vp
{
namespace
{
constexpr std::size_t MaximumPending = 256;
constexpr double RepeatEveryS = 1.0; // the state again, for a patch started late

OscOutput::Message SoundMessage(const char* address, const Voice& v)
{
  OscOutput::Message m;
  m.Address = address;
  m.Types = "ffffff";
  m.Floats = { static_cast<float>(v.PitchHz), static_cast<float>(v.AltPitchHz), static_cast<float>(v.BeepsPerSecond),
    static_cast<float>(v.Duty), static_cast<float>(static_cast<int>(v.Wave)), static_cast<float>(v.Silent() ? 0.0 : v.Gain) };
  return m;
}

OscOutput::Message LevelMessage(const TrackedFrame& frame)
{
  OscOutput::Message m;
  m.Address = "/vesselproximity/level";
  m.Types = "fsss";
  m.Floats = { static_cast<float>(static_cast<int>(frame.Level)) };
  const std::string className =
    frame.LevelClass >= 0 && frame.LevelClass < static_cast<int>(frame.Proximity.Classes.size()) ? frame.Proximity.Classes[frame.LevelClass].ClassName : "";
  m.Strings = { DangerLevelName(frame.Level), DangerCauseName(frame.LevelCause), className };
  return m;
}
} // namespace

OscOutput::OscOutput(const std::string& source, const std::string& host, int port, Sonification sound)
  : Source(source)
  , Where(host + ":" + std::to_string(port))
  , Sound(std::move(sound))
{
  // liblo resolves the host on the first send; asked here, a wrong name is said before tracking.
  addrinfo hints{};
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int status = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
  if (status != 0)
  {
    throw InputError(source, host + ": " + gai_strerror(status));
  }
  freeaddrinfo(found);
  this->Address = lo_address_new(host.c_str(), std::to_string(port).c_str());
  if (!this->Address)
  {
    throw InputError(source, this->Where + ": liblo cannot make an address of it");
  }
  this->Sender = std::thread([this] { this->Send(); });
}

OscOutput::~OscOutput()
{
  {
    std::lock_guard<std::mutex> hold(this->Lock);
    this->Stopping = true;
  }
  this->Wake.notify_all();
  this->Sender.join();
  lo_address_free(static_cast<lo_address>(this->Address));
}

void OscOutput::Queue(Message message)
{
  {
    std::lock_guard<std::mutex> hold(this->Lock);
    if (message.Replaceable)
    {
      for (Message& waiting : this->Pending)
      {
        if (waiting.Replaceable && waiting.Address == message.Address)
        {
          waiting = std::move(message);
          ++this->Count.Replaced;
          return;
        }
      }
    }
    if (this->Pending.size() >= MaximumPending)
    {
      this->Pending.pop_front();
      ++this->Count.Dropped;
    }
    this->Pending.push_back(std::move(message));
  }
  this->Wake.notify_one();
}

bool OscOutput::RepeatDue(double timeS) const
{
  // A time that went back is a recording replayed again: the patch may have started since.
  return timeS - this->LastRepeatS >= RepeatEveryS || timeS < this->LastRepeatS;
}

void OscOutput::QueueState(double timeS, bool lost, const SoundState& sound, bool force)
{
  const bool repeat = force || this->RepeatDue(timeS);
  if (repeat || !this->LastLost || *this->LastLost != lost)
  {
    Message state;
    state.Address = "/vesselproximity/state";
    state.Types = "s";
    state.Strings = { lost ? "lost" : "tracking" };
    this->Queue(std::move(state));
  }
  if (repeat || !this->LastSound || this->LastSound->Vessel != sound.Vessel)
  {
    this->Queue(SoundMessage("/vesselproximity/sound/vessel", sound.Vessel));
  }
  if (repeat || !this->LastSound || this->LastSound->Margin != sound.Margin)
  {
    this->Queue(SoundMessage("/vesselproximity/sound/margin", sound.Margin));
  }
  this->LastLost = lost;
  this->LastSound = sound;
  this->LastRepeatS = repeat ? timeS : this->LastRepeatS;
}

float OscOutput::SignedDistanceOf(const TrackedFrame& frame)
{
  const int nearest = frame.Proximity.NearestIndex();
  const ClassProximity* p = nearest >= 0 ? &frame.Proximity.Classes[nearest] : nullptr;
  return p ? static_cast<float>(p->Inside && *p->Inside ? -p->DistanceMm : p->DistanceMm) : 0.0f;
}

void OscOutput::OnFrame(const TrackedFrame& frame)
{
  const bool repeat = this->RepeatDue(frame.TimeS);
  if (repeat || frame.Level != this->LastLevel || !this->LastLost)
  {
    this->Queue(LevelMessage(frame));
    this->LastLevel = frame.Level;
  }
  this->QueueState(frame.TimeS, false, this->Sound.ForFrame(frame), repeat);
  const int nearest = frame.Proximity.NearestIndex();
  if (nearest >= 0)
  {
    const ClassProximity& p = frame.Proximity.Classes[nearest];
    Message distance;
    distance.Address = "/vesselproximity/distance";
    distance.Replaceable = true;
    distance.Types = "sf";
    distance.Strings = { p.ClassName };
    distance.Floats = { SignedDistanceOf(frame) };
    if (frame.Surface.size() > static_cast<std::size_t>(nearest) && frame.Surface[nearest].InRange)
    {
      distance.Types += "f";
      distance.Floats.push_back(static_cast<float>(frame.Surface[nearest].DistanceMm));
    }
    this->Queue(std::move(distance));
  }
  if (frame.Tumour && frame.Tumour->Worst >= 0)
  {
    const TumourProximity& t = frame.Tumour->Tumours[frame.Tumour->Worst];
    Message margin;
    margin.Address = "/vesselproximity/margin";
    margin.Replaceable = true;
    margin.Types = "fsf";
    margin.Floats = { static_cast<float>(static_cast<int>(frame.Tumour->Level)), static_cast<float>(t.SignedMm) };
    margin.Strings = { t.Id };
    this->Queue(std::move(margin));
  }
}

void OscOutput::OnLost(const TrackedPose& pose)
{
  this->QueueState(pose.TimeS, true, this->Sound.ForLostPose(), false);
}

void OscOutput::OnEnd()
{
  // What was queued goes out before the run's summary counts it.
  std::unique_lock<std::mutex> hold(this->Lock);
  this->Wake.wait_for(hold, std::chrono::seconds(2), [this] { return this->Pending.empty() && !this->Sending; });
}

void OscOutput::Send()
{
  for (;;)
  {
    Message message;
    {
      std::unique_lock<std::mutex> hold(this->Lock);
      this->Wake.wait(hold, [this] { return this->Stopping || !this->Pending.empty(); });
      if (this->Pending.empty())
      {
        return;
      }
      message = std::move(this->Pending.front());
      this->Pending.pop_front();
      this->Sending = true;
    }
    lo_message m = lo_message_new();
    std::size_t f = 0, s = 0;
    for (char type : message.Types)
    {
      if (type == 'f')
        lo_message_add_float(m, message.Floats[f++]);
      else
        lo_message_add_string(m, message.Strings[s++].c_str());
    }
    const int sent = lo_send_message(static_cast<lo_address>(this->Address), message.Address.c_str(), m);
    lo_message_free(m);
    {
      std::lock_guard<std::mutex> hold(this->Lock);
      ++(sent < 0 ? this->Count.Failed : this->Count.Sent);
      this->LastSentMs = NowMs();
      this->Sending = false;
    }
    this->Wake.notify_all();
  }
}

OscOutput::Counts OscOutput::GetCounts() const
{
  std::lock_guard<std::mutex> hold(this->Lock);
  return this->Count;
}

double OscOutput::GetLastSentMs() const
{
  std::lock_guard<std::mutex> hold(this->Lock);
  return this->LastSentMs;
}

void OscOutput::Report(nlohmann::ordered_json& outputs) const
{
  const Counts c = this->GetCounts();
  outputs["osc"] = { { "to", this->Where }, { "sent", c.Sent }, { "failed", c.Failed }, { "dropped_queue_full", c.Dropped },
    { "replaced_by_newer", c.Replaced } };
}

std::string OscOutput::Problems() const
{
  const Counts c = this->GetCounts();
  if (c.Failed == 0 && c.Dropped == 0)
  {
    return "";
  }
  return "OSC to " + this->Where + ": " + std::to_string(c.Failed) + " message(s) not sent, " + std::to_string(c.Dropped) +
    " dropped (queue full)";
}
} // namespace vp
