// cvtplant-sil: the SIL harness (docs/sil.md#scenarios). It plays two nodes
// on the bus, each with its own socket: the Harness (SimCtrl lock-step
// requests, HarnessLoad) and the example Controller (hil/controller). For
// each scenario it resets the bridge, runs the closed loop in 10 ms
// lock-step periods (the ratio scenarios also in real time, the bridge
// pacing the plant), checks the pass/fail criteria and writes a CSV trace;
// all results go to one JUnit XML file. `bench` measures lock-step round
// trips per second. The scenarios, criteria, reports and the runner are in
// hil/sil/{include,src}; this file parses the command line and wires the
// nodes together.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/port/socketcan_transport.hpp"
#include "cvtplant/sil/harness/example_controller.hpp"
#include "cvtplant/sil/harness/report.hpp"
#include "cvtplant/sil/harness/runner.hpp"

namespace {

using namespace cvt::sil::harness;

const char kUsage[] =
    "usage: cvtplant-sil run   [--iface NAME|--loopback] [--scenario NAME|all] [--out DIR] [--junit FILE] [--safety X]\n"
    "                          [--reply-timeout-ms T] [--mode lockstep|realtime|both]\n"
    "                          [--loopback-frame-cost-us US]\n"
    "       cvtplant-sil bench [--iface NAME|--loopback] [--steps N] [--with-controller] [--reply-timeout-ms T]\n"
    "Drives cvtplant-bridge with the example controller over SocketCAN.\n"
    "  --iface NAME        interface (default vcan0)\n"
    "  --loopback          no SocketCAN: the bridge runs in-process on the loopback bus\n"
    "  --scenario NAME     ratio-sweep, kick-down, slip-recovery, tip-in, load-step, clamp-loss,\n"
    "                      lost-frames, frozen-controller, controller-restart, controller-flood\n"
    "                      or all (default all)\n"
    "  --mode M            lockstep (default): the harness steps the plant; realtime: the ratio\n"
    "                      scenarios with the bridge pacing the plant at 1 kHz (on the wall clock;\n"
    "                      with --loopback on a virtual clock); both: each scenario in lock-step,\n"
    "                      a ratio scenario then again in real time. A real-time run whose plant\n"
    "                      overran more than 1 % of its frames reports the motion criteria as skipped\n"
    "  --loopback-frame-cost-us US  real time on the loopback bus: each plant frame's work takes US us\n"
    "                      of virtual time (default 0; above 1000 the plant cannot keep time)\n"
    "  --reply-timeout-ms T  send a request again when its answer is not complete after T ms\n"
    "                      (default 1000; 20 with --loopback, whose answers are immediate)\n"
    "  --out DIR           per-scenario CSV traces (default .)\n"
    "  --junit FILE        JUnit XML report of every criterion\n"
    "  --safety X          override the controller's safety factor (default 1.3)\n"
    "  --steps N           bench: lock-step round trips (default 5000)\n"
    "  --with-controller   bench: a CtrlCmd from the controller before each Step\n"
    "Exit status: 0 all criteria passed, 1 a criterion failed or the bridge did not answer, 2 bad command line.\n";

[[noreturn]] void bad_usage(const std::string& msg) {
  std::fprintf(stderr, "cvtplant-sil: %s (see --help)\n", msg.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) bad_usage("missing subcommand run or bench");
  const std::string cmd = argv[1];
  if (cmd == "-h" || cmd == "--help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd != "run" && cmd != "bench") bad_usage("unknown subcommand '" + cmd + "'");
  std::string iface = "vcan0", scenario = "all", out_dir = ".", junit, mode = "lockstep";
  long steps = 5000;
  bool with_controller = false, loopback = false;
  double reply_timeout_ms = 0;  // 0: the default for the transport
  std::int64_t frame_cost_ns = 0;
  cvtctl::ClampLawParams law;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--with-controller" || a == "--loopback") {
      (a == "--loopback" ? loopback : with_controller) = true;
      continue;
    }
    if (a != "--iface" && a != "--scenario" && a != "--out" && a != "--junit" && a != "--safety" && a != "--steps" &&
        a != "--reply-timeout-ms" && a != "--mode" && a != "--loopback-frame-cost-us")
      bad_usage("unknown option '" + a + "'");
    if (i + 1 >= argc) bad_usage(a + ": missing value");
    const std::string v = argv[++i];
    char* end = nullptr;
    if (a == "--iface") iface = v;
    else if (a == "--scenario") scenario = v;
    else if (a == "--out") out_dir = v;
    else if (a == "--junit") junit = v;
    else if (a == "--loopback-frame-cost-us") {
      const double us = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(us >= 0 && us <= 100000))
        bad_usage("--loopback-frame-cost-us: expected 0..100000, got '" + v + "'");
      frame_cost_ns = static_cast<std::int64_t>(us * 1e3 + 0.5);
    } else if (a == "--mode") {
      mode = v;
      if (mode != "lockstep" && mode != "realtime" && mode != "both")
        bad_usage("--mode: expected lockstep, realtime or both, got '" + v + "'");
    }
    else if (a == "--safety") {
      law.safety = std::strtof(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(law.safety > 0.1f && law.safety < 10.0f))
        bad_usage("--safety: expected a number in (0.1, 10), got '" + v + "'");
    } else if (a == "--reply-timeout-ms") {
      reply_timeout_ms = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(reply_timeout_ms >= 1 && reply_timeout_ms <= 10000))
        bad_usage("--reply-timeout-ms: expected 1..10000, got '" + v + "'");
    } else if (a == "--steps") {
      steps = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || steps < 1 || steps > 10000000)
        bad_usage("--steps: expected 1..10000000, got '" + v + "'");
    }
  }
  std::vector<Scenario> chosen;
  for (const Scenario& s : scenarios())
    if (scenario == "all" || scenario == s.name) chosen.push_back(s);
  if (chosen.empty()) bad_usage("--scenario: expected " + scenario_names() + ", got '" + scenario + "'");
  // Real time runs the ratio scenarios (docs/sil.md#ratio-realtime); the
  // fault scenarios need the harness's control of every step.
  const bool lockstep_runs = mode != "realtime", realtime_runs = mode != "lockstep";
  if (mode == "realtime" && scenario != "all" && !chosen.front().ratio_target)
    bad_usage("--mode realtime: runs ratio-sweep, kick-down or slip-recovery, not '" + scenario + "'");
  if (frame_cost_ns > 0 && (!loopback || !realtime_runs))
    bad_usage("--loopback-frame-cost-us: needs --loopback and --mode realtime or both");
  if (reply_timeout_ms == 0) reply_timeout_ms = loopback ? 20 : 1000;
  // Traces are part of the result: a directory that cannot be made is an
  // error now, not a silently missing CSV later.
  std::error_code mkdir_error;
  std::filesystem::create_directories(out_dir, mkdir_error);
  if (mkdir_error) {
    std::fprintf(stderr, "cvtplant-sil: --out %s: %s\n", out_dir.c_str(), mkdir_error.message().c_str());
    return 1;
  }

  // Three nodes on one bus: the plant (in-process only with --loopback),
  // harness and controller, each with its own transport.
  std::unique_ptr<InProcessBus> loop;
  std::unique_ptr<PlantUnderTest> plant;
  cvt::port::SocketCanTransport harness_sock, controller_sock;
  cvt::port::CanTransport* harness_bus = nullptr;
  cvt::port::CanTransport* controller_bus = nullptr;
  if (loopback) {
    loop = std::make_unique<InProcessBus>();
    plant = std::make_unique<LoopbackBridgePlant>(*loop, frame_cost_ns);
    harness_bus = &loop->harness_node();
    controller_bus = &loop->controller_node();
  } else {
    if (harness_sock.open(iface.c_str()) != 0 || controller_sock.open(iface.c_str()) != 0) {
      std::fprintf(stderr, "cvtplant-sil: %s: %s%s\n", iface.c_str(), harness_sock.error_text(),
                   controller_sock.error_text());
      return 1;
    }
    plant = std::make_unique<BusPlant>();
    harness_bus = &harness_sock;
    controller_bus = &controller_sock;
  }
  // The harness's transport through a fault injector, which the fault
  // scenarios arm (docs/sil.md#fault-scenarios); otherwise it passes frames.
  FaultInjector harness_faults(*harness_bus);
  HarnessNode h(harness_faults, static_cast<std::int64_t>(reply_timeout_ms * 1e6), plant->idle());
  // --safety sets the clamping margin of both laws (ClampLaw, RatioLaw).
  cvtctl::RatioLawParams ratio_law;
  ratio_law.clamp = law;
  ExampleController ctl(*controller_bus, law, ratio_law);
  if (!h.sync()) {
    std::fprintf(stderr, "cvtplant-sil: the bridge on %s does not answer SimCtrl\n", loopback ? "loopback" : iface.c_str());
    return 1;
  }
  if (cmd == "bench") return bench(h, with_controller ? &ctl.node() : nullptr, steps);

  // Real-time pacing: the bridge process on the wall clock, or the
  // in-process bridge one frame per virtual millisecond.
  const RealTimeBus rt_bus = plant->realtime();
  RunConfig cfg;
  cfg.out_dir = out_dir;
  cfg.capacity = law;
  std::vector<ScenarioResult> results;
  bool all_pass = true;
  for (const Scenario& s : chosen) {
    if (lockstep_runs) {
      results.push_back(run_lockstep(s, h, harness_faults, ctl, cfg));
      all_pass = all_pass && results.back().pass();
      print_result(results.back(), s.what);
    }
    if (realtime_runs && s.ratio_target) {
      results.push_back(run_realtime(s, h, ctl, cfg, rt_bus));
      all_pass = all_pass && results.back().pass();
      print_result(results.back(), s.what);
    }
  }
  if (!junit.empty() && !write_junit(junit, results)) {
    std::fprintf(stderr, "cvtplant-sil: --junit %s: %s\n", junit.c_str(), std::strerror(errno));
    return 1;
  }
  return all_pass ? 0 : 1;
}
