// The bridge as a program on a SocketCAN interface (docs/sil.md#cli): the
// command line, the candump log, real-time pacing on CLOCK_MONOTONIC, the
// idle and duration ends and the JSON summary, for any plant behind
// cvt::sil::BasicBridge. cvtplant-bridge runs it with the scene's real-time
// plant; a host program with another plant (cvtplant-reference-bridge, the
// multibody reference) adds its own options and summary fields. Host only:
// a program, not the heap-free bridge.
#pragma once

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/port/socketcan_transport.hpp"
#include "cvtplant/sil/bridge.hpp"
#include "cvtplant/sil/latency_stats.hpp"
#include "stop_flag.hpp"

namespace cvt::hil {

struct BridgeOptions {
  std::string iface = "vcan0";
  std::string scene = "tip-in";
  bool realtime = false;
  double duration_s = 0;
  double idle_exit_s = 0;
  std::string log, summary, ready_file;
  bool log_sim_clock = false;
  int sched_fifo = 0;
  cvt::sil::CmdTimeoutReaction cmd_reaction = cvt::sil::CmdTimeoutReaction::Dbc;
};

// What a plant's program adds to the common bridge program.
template <class Plant>
struct BridgeProgram {
  const char* name;         // "cvtplant-bridge"
  const char* description;  // the lines after "usage:" in --help
  const char* extra_usage;  // the plant's own options in --help ("" for none)
  // The plant's own options, each with a value, and how to take one (a bad
  // value ends the program through bad_usage).
  std::vector<std::string> extra_flags;
  std::function<void(const std::string& flag, const char* value)> parse_extra;
  // The bridge, once the command line is parsed.
  std::function<std::unique_ptr<cvt::sil::BasicBridge<Plant>>(cvt::port::CanTransport&, cvt::port::Clock&,
                                                              cvt::sil::FrameSink*)>
      make_bridge;
  // More summary fields, each line starting with two spaces and ending with ",\n".
  std::function<void(std::FILE*, const cvt::sil::BasicBridge<Plant>&)> summary_extra;
};

[[noreturn]] inline void bad_usage(const char* prog, const std::string& msg) {
  std::fprintf(stderr, "%s: %s (see --help)\n", prog, msg.c_str());
  std::exit(2);
}

inline double parse_seconds(const char* prog, const std::string& flag, const char* v) {
  char* end = nullptr;
  errno = 0;
  const double d = std::strtod(v, &end);
  if (end == v || *end != '\0' || errno != 0 || !(d >= 0) || d > 1e6)
    bad_usage(prog, flag + ": expected seconds in [0, 1e6], got '" + v + "'");
  return d;
}

inline const char* kBridgeUsage =
    "  --iface NAME          SocketCAN interface (default vcan0)\n"
    "  --scene NAME          built-in scene loaded at start (default tip-in);\n"
    "                        SimCtrl Reset can select another\n"
    "  --mode MODE           lockstep: wait for SimCtrl Step requests (default)\n"
    "                        realtime: pace one frame per scene frame from the start\n"
    "  --duration-s S        stop after S s of simulated time (0 = until a signal)\n"
    "  --idle-exit-s S       lock-step: exit when no frame arrived for S s (0 = never)\n"
    "  --log FILE            candump -L style log of every frame the bridge sent\n"
    "  --log-clock CLOCK     log timestamps: host (CLOCK_MONOTONIC, default) or sim\n"
    "  --summary FILE        write the JSON summary to FILE (default stdout)\n"
    "  --sched-fifo PRIO     real time: try SCHED_FIFO at PRIO (1..99) and mlockall\n"
    "  --cmd-timeout-reaction R\n"
    "                        what the plant applies while CtrlCmd is timed out:\n"
    "                        dbc (default): the DBC's ramps from the last applied\n"
    "                        values (clamp to 20 kN at 50 kN/s, torque to 0 at\n"
    "                        250 N m/s); hold-last: keep the last applied values\n"
    "  --ready-file FILE     created once the bridge serves the bus (interface open, scene\n"
    "                        loaded, priority set, real time started)\n";

template <class Plant>
BridgeOptions parse_bridge_options(int argc, char** argv, const BridgeProgram<Plant>& prog) {
  BridgeOptions o;
  const char* name = prog.name;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::printf("usage: %s [options]\n%s\n%s%s  -h, --help            this text\n", name, prog.description,
                  kBridgeUsage, prog.extra_usage);
      std::printf("Exit status: 0 done, 1 run failure (interface, scene), 2 bad command line.\n");
      std::exit(0);
    }
    static const char* const kFlags[] = {"--iface", "--scene", "--mode", "--duration-s", "--idle-exit-s", "--log",
                                         "--log-clock", "--summary", "--ready-file", "--sched-fifo",
                                         "--cmd-timeout-reaction"};
    bool known = false, extra = false;
    for (const char* k : kFlags) known = known || a == k;
    for (const std::string& k : prog.extra_flags) extra = extra || a == k;
    if (!known && !extra)
      bad_usage(name, a.rfind("--", 0) == 0 ? "unknown option '" + a + "'" : "unexpected argument '" + a + "'");
    if (i + 1 >= argc) bad_usage(name, a + ": missing value");
    const char* v = argv[i + 1];
    if (a == "--iface") o.iface = v;
    else if (a == "--scene") o.scene = v;
    else if (a == "--mode") {
      const std::string m = v;
      if (m == "realtime") o.realtime = true;
      else if (m != "lockstep") bad_usage(name, "--mode: expected lockstep or realtime, got '" + m + "'");
    } else if (a == "--duration-s") o.duration_s = parse_seconds(name, a, v);
    else if (a == "--idle-exit-s") o.idle_exit_s = parse_seconds(name, a, v);
    else if (a == "--log") o.log = v;
    else if (a == "--log-clock") {
      const std::string c = v;
      if (c == "sim") o.log_sim_clock = true;
      else if (c != "host") bad_usage(name, "--log-clock: expected host or sim, got '" + c + "'");
    } else if (a == "--cmd-timeout-reaction") {
      const std::string r = v;
      if (r == "hold-last") o.cmd_reaction = cvt::sil::CmdTimeoutReaction::HoldLast;
      else if (r != "dbc") bad_usage(name, "--cmd-timeout-reaction: expected dbc or hold-last, got '" + r + "'");
    } else if (a == "--summary") o.summary = v;
    else if (a == "--ready-file") o.ready_file = v;
    else if (a == "--sched-fifo") {
      char* end = nullptr;
      const long p = std::strtol(v, &end, 10);
      if (end == v || *end != '\0' || p < 1 || p > 99)
        bad_usage(name, "--sched-fifo: expected 1..99, got '" + std::string(v) + "'");
      o.sched_fifo = static_cast<int>(p);
    } else {
      prog.parse_extra(a, v);
    }
    ++i;
  }
  if (cvt::find_builtin_scene(o.scene.c_str()) == nullptr) bad_usage(name, "--scene: no built-in scene '" + o.scene + "'");
  return o;
}

// candump -L format: "(sec.usec) IFACE ID#HEX" (docs/sil.md#log).
class CandumpLog final : public cvt::sil::FrameSink {
 public:
  CandumpLog(std::FILE* f, std::string iface, bool sim_clock) : f_(f), iface_(std::move(iface)), sim_(sim_clock) {}
  void on_tx(const cvt::can::CanFrame& fr, std::int64_t host_ns, std::int64_t sim_ns) noexcept override {
    const std::int64_t t_ns = sim_ ? sim_ns : host_ns;
    std::fprintf(f_, "(%lld.%06lld) %s %03X#", static_cast<long long>(t_ns / 1000000000),
                 static_cast<long long>((t_ns % 1000000000) / 1000), iface_.c_str(), static_cast<unsigned>(fr.id));
    for (int i = 0; i < fr.dlc; ++i) std::fprintf(f_, "%02X", fr.data[i]);
    std::fputc('\n', f_);
  }

 private:
  std::FILE* f_;
  std::string iface_;
  bool sim_;
};

struct RtReport {
  bool ran = false;
  bool fifo_requested = false, fifo_granted = false, mlocked = false;
  std::string fifo_error;
  std::int64_t period_ns = 0;
  cvt::sil::LatencySummary jitter;
};

template <class Plant>
void print_bridge_summary(std::FILE* out, const BridgeOptions& o, const BridgeProgram<Plant>& prog,
                          const cvt::sil::BasicBridge<Plant>& b, const cvt::port::SocketCanTransport& bus,
                          const RtReport& rt) {
  const auto& rx = b.rx();
  const auto& tx = b.tx();
  const auto tc = bus.counters();
  const cvt::Scene* s = b.plant().scene();
  std::fprintf(out, "{\n  \"scene\": \"%s\",\n  \"iface\": \"%s\",\n", s ? s->name : "", o.iface.c_str());
  std::fprintf(out, "  \"final_mode\": \"%s\",\n  \"plant_fault\": \"%s\",\n", cvt::can::to_string(b.mode()),
               b.plant().fault_detail());
  if (prog.summary_extra) prog.summary_extra(out, b);
  std::fprintf(out,
               "  \"frames\": %ld,\n  \"sim_time_s\": %.6f,\n  \"steps_requested\": %llu,\n  \"groups_sent\": %llu,\n"
               "  \"groups_resent\": %llu,\n",
               b.plant().frames(), static_cast<double>(b.sim_ns()) * 1e-9,
               static_cast<unsigned long long>(b.steps_requested()), static_cast<unsigned long long>(b.groups_sent()),
               static_cast<unsigned long long>(b.groups_resent()));
  auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  std::fprintf(out,
               "  \"rx\": {\"accepted\": %llu, \"rejected\": %llu, \"not_data_frame\": %llu, \"unknown_id\": %llu, "
               "\"wrong_dlc\": %llu, \"wrong_crc\": %llu, \"repeated\": %llu, \"wrong_sequence\": %llu, "
               "\"out_of_range\": %llu, \"invalid_enum\": %llu, \"error_frames\": %llu, \"stale_discarded\": %llu, "
               "\"plant_ids_ignored\": %llu, \"requests_ignored\": %llu, \"resync_withheld\": %llu, "
               "\"requests_resent\": %llu},\n",
               u(rx.accepted), u(rx.rejected()), u(rx.not_data_frame), u(rx.unknown_id), u(rx.wrong_dlc),
               u(rx.wrong_crc), u(rx.repeated), u(rx.wrong_sequence), u(rx.out_of_range), u(rx.invalid_enum),
               u(rx.error_frames), u(rx.stale_discarded), u(rx.plant_ids_ignored), u(rx.requests_ignored),
               u(rx.resync_withheld), u(rx.requests_resent));
  std::fprintf(out,
               "  \"tx\": {\"sent\": %llu, \"failed\": %llu, \"bus_off_refused\": %llu, \"saturated\": %llu, "
               "\"enobufs_retries\": %llu, \"dropped\": %llu},\n",
               u(tx.sent), u(tx.failed), u(tx.bus_off_refused), u(tx.saturated), u(tc.tx_enobufs_retries),
               u(tc.tx_dropped));
  std::fprintf(out, "  \"bus\": {\"bus_off_events\": %llu, \"rx_kernel_drops\": %llu, \"rx_invalid\": %llu},\n",
               u(tc.bus_off_events), u(tc.rx_kernel_drops), u(tc.rx_invalid));
  std::fprintf(out, "  \"cmd\": {\"lost_frames\": %llu, \"resyncs\": %llu, \"superseded\": %llu},\n",
               u(b.cmd_checker().lost_frames()), u(b.cmd_checker().resyncs()), u(rx.cmd_superseded));
  std::fprintf(out, "  \"cmd_timeouts\": %llu,\n  \"load_timeouts\": %llu,\n  \"cmd_timeout_reaction\": \"%s\",\n",
               u(b.cmd_timeouts()), u(b.load_timeouts()), cvt::sil::to_string(b.cmd_timeout_reaction()));
  std::fprintf(out, "  \"shift_timeouts\": %llu,\n  \"stop_refined_frames\": %llu,\n  \"realtime_refused\": %llu,\n",
               u(b.shift_timeouts()), u(static_cast<std::uint64_t>(b.plant().stop_refined_frames())),
               u(b.realtime_refused()));
  std::fprintf(out, "  \"realtime\": ");
  if (!rt.ran) {
    std::fprintf(out, "null\n}\n");
    return;
  }
  std::fprintf(out,
               "{\"period_ns\": %lld, \"periods\": %zu, \"overruns\": %llu, \"sched_fifo_requested\": %s, "
               "\"sched_fifo\": %s, \"sched_fifo_error\": \"%s\", \"mlockall\": %s,\n"
               "    \"jitter_ns\": {\"p50\": %lld, \"p99\": %lld, \"p99_9\": %lld, \"max\": %lld}}\n}\n",
               static_cast<long long>(rt.period_ns), rt.jitter.n, u(b.rt_overruns()),
               rt.fifo_requested ? "true" : "false", rt.fifo_granted ? "true" : "false", rt.fifo_error.c_str(),
               rt.mlocked ? "true" : "false", static_cast<long long>(rt.jitter.p50_ns),
               static_cast<long long>(rt.jitter.p99_ns), static_cast<long long>(rt.jitter.p999_ns),
               static_cast<long long>(rt.jitter.max_ns));
}

inline void try_realtime_priority(int prio, RtReport& rt) {
  rt.fifo_requested = true;
  sched_param sp{};
  sp.sched_priority = prio;
  if (sched_setscheduler(0, SCHED_FIFO, &sp) == 0) {
    rt.fifo_granted = true;
  } else {
    rt.fifo_error = std::string("sched_setscheduler: ") + std::strerror(errno);
  }
  rt.mlocked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
}

// The whole program: parse, open, load, serve until a signal, the duration
// or the idle time, then the JSON summary.
template <class Plant>
int bridge_program_main(int argc, char** argv, const BridgeProgram<Plant>& prog) {
  const BridgeOptions o = parse_bridge_options(argc, argv, prog);
  const char* name = prog.name;
  install_stop_handlers();

  cvt::port::SocketCanTransport bus;
  if (bus.open(o.iface.c_str()) != 0) {
    std::fprintf(stderr, "%s: %s: %s\n", name, o.iface.c_str(), bus.error_text());
    return 1;
  }
  std::FILE* logf = nullptr;
  if (!o.log.empty() && (logf = std::fopen(o.log.c_str(), "w")) == nullptr) {
    std::fprintf(stderr, "%s: --log %s: %s\n", name, o.log.c_str(), std::strerror(errno));
    return 1;
  }
  CandumpLog log(logf, o.iface, o.log_sim_clock);
  cvt::port::PosixMonotonicClock clock;
  const std::unique_ptr<cvt::sil::BasicBridge<Plant>> owned =
      prog.make_bridge(bus, clock, logf != nullptr ? &log : nullptr);
  cvt::sil::BasicBridge<Plant>& bridge = *owned;
  bridge.set_cmd_timeout_reaction(o.cmd_reaction);
  if (!bridge.load_scene(*cvt::find_builtin_scene(o.scene.c_str()))) {
    std::fprintf(stderr, "%s: scene %s: %s\n", name, o.scene.c_str(), bridge.plant().load_refusal());
    return 1;
  }
  RtReport rt;
  std::vector<std::int64_t> lateness;
  // Priority and locked memory first: mlockall can take seconds in a starved
  // VM, and neither the command deadline (monitored from real-time entry)
  // nor a peer waiting for the ready file should count that time.
  if (o.sched_fifo > 0) try_realtime_priority(o.sched_fifo, rt);
  if (o.realtime) {
    lateness.reserve(static_cast<std::size_t>(o.duration_s * 1e9 / static_cast<double>(bridge.frame_ns())) + 16);
    if (!bridge.start_realtime()) {
      std::fprintf(stderr, "%s: --mode realtime: %s\n", name, bridge.plant().realtime_refusal());
      return 2;
    }
  }
  if (!o.ready_file.empty()) {
    if (std::FILE* r = std::fopen(o.ready_file.c_str(), "w")) std::fclose(r);
  }
  const std::int64_t end_ns = static_cast<std::int64_t>(o.duration_s * 1e9 + 0.5);
  std::int64_t last_rx_ns = clock.now_ns();
  std::uint64_t seen = 0, refused = 0;
  bool fault_told = false;
  while (!stop_requested()) {
    if (bridge.mode() == cvt::can::PlantMode::RealTime) {
      rt.ran = true;
      rt.period_ns = bridge.frame_ns();
      cvt::sil::pace_realtime(bridge, clock, end_ns, &g_stop_requested,
                              [&](std::int64_t ns) { lateness.push_back(ns); });
      if (end_ns != 0 && bridge.sim_ns() >= end_ns) break;
      continue;
    }
    bridge.service(100000000);
    // What the bus cannot carry goes to stderr (the plant's log): why a
    // RunRealTime was refused, and the whole reason of a plant fault.
    if (bridge.realtime_refused() != refused) {
      refused = bridge.realtime_refused();
      std::fprintf(stderr, "%s: SimCtrl RunRealTime refused: %s\n", name, bridge.plant().realtime_refusal());
    }
    if (bridge.plant().faulted() != fault_told) {
      fault_told = bridge.plant().faulted();
      if (fault_told)
        std::fprintf(stderr, "%s: plant fault %s: %s\n", name, cvt::can::to_string(bridge.plant().fault_code()),
                     bridge.plant().fault_message());
    }
    const std::uint64_t now_seen = bridge.rx().accepted + bridge.rx().rejected() + bridge.rx().error_frames;
    if (now_seen != seen) {
      seen = now_seen;
      last_rx_ns = clock.now_ns();
    } else if (o.idle_exit_s > 0 && clock.now_ns() - last_rx_ns > static_cast<std::int64_t>(o.idle_exit_s * 1e9)) {
      break;
    }
    if (end_ns != 0 && bridge.sim_ns() >= end_ns) break;
  }
  if (rt.ran) rt.jitter = cvt::sil::summarize_latencies(lateness);
  if (logf != nullptr) std::fclose(logf);
  std::FILE* out = stdout;
  if (!o.summary.empty() && (out = std::fopen(o.summary.c_str(), "w")) == nullptr) {
    std::fprintf(stderr, "%s: --summary %s: %s\n", name, o.summary.c_str(), std::strerror(errno));
    return 1;
  }
  print_bridge_summary(out, o, prog, bridge, bus, rt);
  if (out != stdout) std::fclose(out);
  return 0;
}

}  // namespace cvt::hil
