// SIGINT and SIGTERM during a long command (docs/cli.md#interruption).
#include "cvtplant/files/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace cvt::files {

namespace {

std::atomic<int> g_signal{0};     // the first signal caught, 0: none
std::atomic<int> g_immediate{0};  // ImmediateInterrupts scopes alive
static_assert(std::atomic<int>::is_always_lock_free, "the flag is set in a signal handler");

void die_of(int sig) {
  // The default action, delivered when the handler returns (the signal is
  // blocked while it runs): the process ends as if it had no handler.
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

extern "C" void on_interrupt(int sig) {
  if (g_signal.load() != 0 || g_immediate.load() != 0) {
    die_of(sig);
    return;
  }
  g_signal.store(sig);
}

}  // namespace

void catch_interrupts() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool interrupted() noexcept { return g_signal.load() != 0; }
int interrupt_signal() noexcept { return g_signal.load(); }
int interrupted_exit_status() noexcept { return 128 + g_signal.load(); }

const char* interrupt_signal_name() noexcept {
  switch (g_signal.load()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}

ImmediateInterrupts::ImmediateInterrupts() {
  g_immediate.fetch_add(1);
  if (const int sig = g_signal.load(); sig != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

ImmediateInterrupts::~ImmediateInterrupts() { g_immediate.fetch_sub(1); }

}  // namespace cvt::files
