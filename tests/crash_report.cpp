// A test process that dies on a signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) prints which
// signal, its si_code and fault address, the running GoogleTest case and a backtrace to stderr
// before it dies, so that CTest's log of a rare crash says where it happened. A CI run once
// ended with "Bus error" and nothing else (docs/testing.md, "Crashes").
#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

namespace {

constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT};

// The handler formats into a fixed buffer and writes with write(2); the test name lookup and
// backtrace_symbols_fd are not async-signal-safe in theory, but the process is dying anyway and
// they work in practice for a report.
void reportAndDie(int signal, siginfo_t* info, void*) {
  char line[512];
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  int n = std::snprintf(line, sizeof line,
                        "\n*** test process got signal %d (%s), si_code %d, address %p, in %s.%s\n",
                        signal, strsignal(signal), info ? info->si_code : 0,
                        info ? info->si_addr : nullptr, test ? test->test_suite_name() : "-",
                        test ? test->name() : "-");
  if (n > 0) (void)!::write(STDERR_FILENO, line, size_t(n));
  void* frames[64];
  int count = backtrace(frames, 64);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // Die of the same signal, so that CTest reports it as before.
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

struct CrashReporter {
  CrashReporter() {
    struct sigaction action {};
    action.sa_sigaction = reportAndDie;
    action.sa_flags = SA_SIGINFO | SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    for (int signal : kSignals) sigaction(signal, &action, nullptr);
  }
};

const CrashReporter crashReporter;

}  // namespace
