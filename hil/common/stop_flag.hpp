// SIGINT/SIGTERM end the host programs of hil/ cleanly: their loops poll
// stop_requested() and then print their JSON summary (docs/sil.md#cli).
#pragma once

#include <csignal>

namespace cvt::hil {

inline volatile std::sig_atomic_t g_stop_requested = 0;

inline void install_stop_handlers() {
  auto on_signal = [](int) { g_stop_requested = 1; };
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

inline bool stop_requested() { return g_stop_requested != 0; }

}  // namespace cvt::hil
