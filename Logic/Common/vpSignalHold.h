#ifndef vpSignalHold_h
#define vpSignalHold_h

namespace vp
{
/// Holds the signals that end a process (SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2,
/// SIGALRM, SIGPIPE, SIGXFSZ) while it lives: the first that comes is recorded (Pending()), not
/// acted on, and raised again when the last hold ends, so that work in progress ends whole. A
/// signal the process ignores (nohup's SIGHUP) stays ignored. Holds nest.
class SignalHold
{
public:
  SignalHold();
  ~SignalHold();
  SignalHold(const SignalHold&) = delete;
  SignalHold& operator=(const SignalHold&) = delete;

  /// Whether a held signal came.
  static bool Pending();
  /// The held signal was the expected end of the work (a live session's Ctrl-C): it is not
  /// raised again when the hold ends. Returns the signal (0: none came).
  static int Answer();
};
} // namespace vp

#endif
