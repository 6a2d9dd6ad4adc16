// throng CLI interrupt handling — see signal.hpp. The handler only touches lock-free atomics and
// async-signal-safe calls (signal, raise).
#include "signal.hpp"

#include <atomic>
#include <csignal>

#include <signal.h>

namespace throng::cli {
namespace {

std::atomic<int> gSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "signal flag must be lock-free");

struct sigaction gPreviousInt {};
struct sigaction gPreviousTerm {};

extern "C" void onInterrupt(int sig) {
  if (gSignal.exchange(sig) != 0) {
    // Second signal: the user insists; die with the default action.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

}  // namespace

InterruptGuard::InterruptGuard() {
  gSignal.store(0);
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // writer threads keep going; the run loop polls the flag per tick
  sigaction(SIGINT, &action, &gPreviousInt);
  sigaction(SIGTERM, &action, &gPreviousTerm);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &gPreviousInt, nullptr);
  sigaction(SIGTERM, &gPreviousTerm, nullptr);
}

bool InterruptGuard::requested() { return gSignal.load(std::memory_order_relaxed) != 0; }

int InterruptGuard::signal() { return gSignal.load(std::memory_order_relaxed); }

const std::atomic<int>& InterruptGuard::flag() { return gSignal; }

}  // namespace throng::cli
