#ifndef vpClock_h
#define vpClock_h

#include <chrono>

namespace vp
{
/// Milliseconds since an arbitrary origin (steady clock): for the stage and frame times reports
/// give.
inline double NowMs()
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace vp

#endif
