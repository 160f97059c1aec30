#ifndef vpVirtualDisplay_h
#define vpVirtualDisplay_h

#include <string>
#include <sys/types.h>

namespace vp
{
/// An X display for rendering where there is none. Debian's VTK renders through X only, so a
/// headless machine (CI, a server running the demo) needs one: when DISPLAY is unset this starts
/// Xvfb on a free display number (Xvfb -displayfd picks it), points DISPLAY at it, and stops it
/// when destroyed. When DISPLAY is set it does nothing.
class VirtualDisplay
{
public:
  VirtualDisplay() = default;
  ~VirtualDisplay();
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  /// Returns true when a display is usable afterwards (already there, or Xvfb started);
  /// otherwise false with the reason in GetProblem() (Xvfb not installed, failed to start).
  bool Ensure();
  const std::string& GetProblem() const { return this->Problem; }
  /// The DISPLAY in use, e.g. ":99"; empty before Ensure().
  const std::string& GetDisplay() const { return this->Display; }
  bool StartedXvfb() const { return this->Pid > 0; }

private:
  pid_t Pid = -1;
  std::string Display;
  std::string Problem;
};
} // namespace vp

#endif
