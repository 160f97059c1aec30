// A test process that crashes prints where: ctest otherwise shows only "SegFault" and the test's
// name, and a crash that happens once in many CI runs (a rendering test, November 2026) cannot be
// told apart from a bug of ours without the stack. Linked into every test executable.
//
// Sanitizer builds keep their own handlers (they report more, and better).
#include <csignal>
#include <cstring>
#include <execinfo.h>
#include <initializer_list>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define VP_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define VP_SANITIZED 1
#endif
#endif

namespace
{
#ifndef VP_SANITIZED
void PrintBacktraceAndDie(int signal)
{
  // Only async-signal-safe calls: write and backtrace_symbols_fd (backtrace is loaded already,
  // see below, so it does not allocate here).
  const char* name = strsignal(signal);
  const char head[] = "\n*** test process received signal: ";
  (void)!write(STDERR_FILENO, head, sizeof head - 1);
  (void)!write(STDERR_FILENO, name, std::strlen(name));
  (void)!write(STDERR_FILENO, "; stack:\n", 9);
  void* frames[64];
  const int n = backtrace(frames, 64);
  backtrace_symbols_fd(frames, n, STDERR_FILENO);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

struct InstallCrashBacktrace
{
  InstallCrashBacktrace()
  {
    // The first call loads libgcc's unwinder, which a signal handler must not do.
    void* warm[1];
    backtrace(warm, 1);
    for (int s : { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT })
    {
      std::signal(s, PrintBacktraceAndDie);
    }
  }
} installCrashBacktrace;
#endif
} // namespace
