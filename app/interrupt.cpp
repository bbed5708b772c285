#include "interrupt.h"

#include <csignal>

namespace bounce::app {

namespace {

std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "stored from a signal handler");

struct sigaction previousAction;

void onInterrupt(int) {
  interrupted.store(true);
}

}  // namespace

InterruptRequest::InterruptRequest() {
  interrupted.store(false);
  struct sigaction action = {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second Ctrl-C: the default action, the program ends
  sigaction(SIGINT, &action, &previousAction);
}

InterruptRequest::~InterruptRequest() {
  sigaction(SIGINT, &previousAction, nullptr);
}

const std::atomic<bool>& InterruptRequest::flag() const {
  return interrupted;
}

}  // namespace bounce::app
