#include "vpSignalHold.h"

#include <atomic>
#include <csignal>

namespace vp
{
namespace
{
const int HeldSignals[] = { SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGPIPE, SIGXFSZ };
constexpr int HeldCount = static_cast<int>(sizeof(HeldSignals) / sizeof(HeldSignals[0]));
volatile std::sig_atomic_t PendingSignal = 0;
struct sigaction PreviousActions[HeldCount];
std::atomic<int> Holders{ 0 }; // nested holds of a cohort's worker threads inside its own

extern "C" void RecordSignal(int signal)
{
  // A file past the size limit (SIGXFSZ) or a reader gone (SIGPIPE) is the write's own failure,
  // which its EFBIG or EPIPE reports in a line: no reason to end the process afterwards.
  if (signal == SIGXFSZ || signal == SIGPIPE)
  {
    return;
  }
  if (PendingSignal == 0)
  {
    PendingSignal = signal;
  }
}
} // namespace

SignalHold::SignalHold()
{
  if (Holders++ > 0)
  {
    return;
  }
  PendingSignal = 0;
  struct sigaction record = {};
  record.sa_handler = RecordSignal;
  record.sa_flags = SA_RESTART;
  sigemptyset(&record.sa_mask);
  for (int i = 0; i < HeldCount; ++i)
  {
    sigaction(HeldSignals[i], nullptr, &PreviousActions[i]);
    if (PreviousActions[i].sa_handler != SIG_IGN) // nohup's SIGHUP stays ignored
    {
      sigaction(HeldSignals[i], &record, nullptr);
    }
  }
}

SignalHold::~SignalHold()
{
  if (--Holders > 0)
  {
    return;
  }
  for (int i = 0; i < HeldCount; ++i)
  {
    sigaction(HeldSignals[i], &PreviousActions[i], nullptr);
  }
  // A signal that came meanwhile is raised again, to act as it would have.
  if (const int signal = PendingSignal)
  {
    PendingSignal = 0;
    std::raise(signal);
  }
}

bool SignalHold::Pending()
{
  return PendingSignal != 0;
}

int SignalHold::Answer()
{
  const int signal = PendingSignal;
  PendingSignal = 0;
  return signal;
}
} // namespace vp
