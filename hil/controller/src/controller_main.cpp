// cvtplant-controller: the example controller as a free-running ECU
// (docs/sil.md#controller): every 10 ms (the CtrlCmd cycle, absolute
// deadlines on the port layer's monotonic clock) it reads the bus and sends
// CtrlCmd. For the bridge's real-time mode; in lock-step, cvtplant-sil runs
// the same ControllerNode in step with the harness.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cvtctl/controller_node.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "stop_flag.hpp"
#include "cvtplant/port/socketcan_transport.hpp"

namespace {

const char kUsage[] =
    "usage: cvtplant-controller [--iface NAME] [--demand-Nm T] [--duration-s S]\n"
    "The example clamping-force controller on SocketCAN, one control period per\n"
    "10 ms of host time, until S seconds passed (0 = until SIGINT/SIGTERM).\n"
    "Prints its counters as JSON at the end. Exit 0, 1 (interface), 2 (usage).\n";

[[noreturn]] void bad_usage(const char* msg, const char* v) {
  std::fprintf(stderr, "cvtplant-controller: %s%s (see --help)\n", msg, v);
  std::exit(2);
}

double number(const char* flag, const char* v, double lo, double hi) {
  char* end = nullptr;
  const double d = std::strtod(v, &end);
  if (end == v || *end != '\0' || !(d >= lo && d <= hi)) {
    std::fprintf(stderr, "cvtplant-controller: %s: expected a number in [%g, %g], got '%s' (see --help)\n", flag, lo,
                 hi, v);
    std::exit(2);
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const char* iface = "vcan0";
  double demand_Nm = 50, duration_s = 0;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (!std::strcmp(a, "-h") || !std::strcmp(a, "--help")) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    const bool known = !std::strcmp(a, "--iface") || !std::strcmp(a, "--demand-Nm") || !std::strcmp(a, "--duration-s");
    if (!known) bad_usage("unknown option ", a);
    if (i + 1 >= argc) bad_usage("missing value for ", a);
    const char* v = argv[++i];
    if (!std::strcmp(a, "--iface")) iface = v;
    else if (!std::strcmp(a, "--demand-Nm")) demand_Nm = number(a, v, -600, 600);
    else duration_s = number(a, v, 0, 1e6);
  }
  cvt::hil::install_stop_handlers();
  cvt::port::SocketCanTransport bus;
  if (bus.open(iface) != 0) {
    std::fprintf(stderr, "cvtplant-controller: %s: %s\n", iface, bus.error_text());
    return 1;
  }
  cvt::port::PosixMonotonicClock clock;
  cvtctl::ControllerNode node(bus);
  constexpr std::int64_t kPeriod_ns = std::int64_t{cvt::can::CtrlCmd::kCycleTime_ms} * 1000000;
  const std::int64_t t0 = clock.now_ns();
  const auto end = t0 + static_cast<std::int64_t>(duration_s * 1e9);
  std::int64_t deadline = t0;
  long periods = 0, late = 0;
  while (!cvt::hil::stop_requested() && (duration_s == 0 || clock.now_ns() < end)) {
    node.poll(0);
    node.control_step(static_cast<float>(demand_Nm));
    ++periods;
    deadline += kPeriod_ns;
    if (clock.now_ns() > deadline) ++late;
    clock.sleep_until(deadline);
  }
  const cvtctl::ControllerCounters& c = node.counters();
  std::printf(
      "{\"periods\": %ld, \"late_periods\": %ld, \"accepted\": %u, \"rejected\": %u, \"error_frames\": %u, "
      "\"invalid_periods\": %u, \"tx_failed\": %u, \"last_clamp_cmd_N\": %.0f}\n",
      periods, late, c.accepted, c.rejected, c.error_frames, c.invalid_periods, c.tx_failed,
      static_cast<double>(node.last_output().clamp_force_cmd_N));
  return 0;
}
