// Ctrl-C during a long render: the first SIGINT asks the work to stop and keep what it has;
// a second one ends the program at once (the handler resets itself, SA_RESETHAND).
#pragma once
#include <atomic>

namespace bounce::app {

// Exit code of a run stopped by Ctrl-C: 128 + SIGINT, what shells report for it.
constexpr int kInterruptedExit = 130;

// Installs the SIGINT handler for its lifetime and restores the previous one after.
class InterruptRequest {
 public:
  InterruptRequest();
  ~InterruptRequest();
  InterruptRequest(const InterruptRequest&) = delete;
  InterruptRequest& operator=(const InterruptRequest&) = delete;

  // Set by the handler; lock-free, so storing it in a signal handler is safe.
  const std::atomic<bool>& flag() const;
  bool requested() const { return flag().load(); }
};

}  // namespace bounce::app
