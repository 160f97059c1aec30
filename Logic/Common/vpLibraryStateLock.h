#ifndef vpLibraryStateLock_h
#define vpLibraryStateLock_h

#include <mutex>

namespace vp
{
/// The lock taken around the libraries' process-wide state that is not safe on two threads at
/// once: std::cerr redirected while FCL builds a tree (it says its failures there), ITK's object
/// factories and NrrdIO's error buffers while a labelmap is read (ITK warns on std::cerr too).
/// A cohort's cases run on threads of their own and take their turns here; a single case never
/// waits.
inline std::mutex& LibraryStateLock()
{
  static std::mutex lock;
  return lock;
}
} // namespace vp

#endif
