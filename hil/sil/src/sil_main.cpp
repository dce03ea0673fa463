// cvtplant-sil: the SIL harness (docs/sil.md#scenarios). It plays the
// scenarios on the bus against a plant and a controller under test: the
// example controller run in-process on its own socket, or a controller of
// the user's own on the bus (--controller external, docs/sil.md#external-lockstep).
// For each scenario it resets the plant, runs the closed loop in 10 ms
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
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/files/paths.hpp"
#include "cvtplant/files/replace.hpp"
#include "cvtplant/port/socketcan_transport.hpp"
#include "cvtplant/sil/harness/child_process.hpp"
#include "cvtplant/sil/harness/example_controller.hpp"
#include "cvtplant/sil/harness/extensions.hpp"
#include "cvtplant/sil/harness/external_controller.hpp"
#include "cvtplant/sil/harness/report.hpp"
#include "cvtplant/sil/harness/runner.hpp"

namespace {

using namespace cvt::sil::harness;

const char kUsage[] =
    "usage: cvtplant-sil run   [--iface NAME|--loopback] [--scenario NAME[,NAME...]|all] [--out DIR] [--junit FILE]\n"
    "                          [--mode lockstep|realtime|both] [--t-end S] [--reply-timeout-ms T]\n"
    "                          [--controller example|external] [--controller-cmd CMD] [--controller-timeout-ms T]\n"
    "                          [--plant NAME] [--plant-option NAME=VALUE]... [--plant-cmd CMD] [--safety X]\n"
    "                          [--clamp-floor N] [--loopback-frame-cost-us US]\n"
    "       cvtplant-sil bench [--iface NAME|--loopback] [--steps N] [--with-controller] [--reply-timeout-ms T]\n"
    "Plays the SIL scenarios against a plant on a CAN bus and a controller under test,\n"
    "judges their criteria and writes CSV traces and a JUnit report (docs/sil.md).\n"
    "  --iface NAME        SocketCAN interface (default vcan0): vcan0, or a real one (can0)\n"
    "  --loopback          no SocketCAN: the bridge and the example controller run in-process\n"
    "                      on the loopback bus\n"
    "  --scenario NAMES    ratio-sweep, kick-down, slip-recovery, tip-in, load-step, clamp-loss,\n"
    "                      lost-frames, frozen-controller, controller-restart, controller-flood,\n"
    "                      a comma-separated list of them, or all (default all)\n"
    "  --mode M            lockstep (default): the harness steps the plant; realtime: the ratio\n"
    "                      scenarios with the bridge pacing the plant at 1 kHz (on the wall clock;\n"
    "                      with --loopback on a virtual clock); both: each scenario in lock-step,\n"
    "                      a ratio scenario then again in real time. A real-time run whose plant\n"
    "                      overran more than 1 % of its frames reports the motion criteria as skipped\n"
    "  --t-end S           cut every scenario at S s of simulated time (at least each scenario's\n"
    "                      shortest run that still judges every criterion; an end-stop criterion\n"
    "                      beyond the cut is reported as not judged)\n"
    "  --allow-partial     --t-end may cut below that: the scenario's first seconds, judged on\n"
    "                      the bus, slip, safety factor, watchdog and timeout only (the rest not judged)\n"
    "  --controller C      example (default): the example controller, run by the harness;\n"
    "                      external: a controller on the bus (docs/sil.md#external-lockstep): each\n"
    "                      period the harness sends HarnessDemand and waits for its CtrlCmd\n"
    "                      (and CtrlShiftCmd) before the Step. Not the scenarios whose faults\n"
    "                      are inside the controller (clamp-loss, lost-frames, frozen-controller,\n"
    "                      controller-restart, controller-flood: all leaves them out)\n"
    "  --controller-cmd CMD  start CMD (sh -c) as the external controller for the runs and stop\n"
    "                      it after them, its output into DIR/controller.log; implies\n"
    "                      --controller external\n"
    "  --controller-timeout-ms T  lock-step: how long to wait for the controller's commands of a\n"
    "                      period (default 1000; the first period of a run waits at least 10 s)\n"
    "  --plant NAME        the plant the scenarios run against (docs/sil.md#plants), default rom:\n"
    "                      with --loopback in this process; on an interface the plant's bridge\n"
    "                      program must be on the bus (or started with --plant-cmd)\n"
    "  --plant-option NAME=VALUE  a setting of the --plant (below), repeatable\n"
    "  --plant-cmd CMD     start CMD (sh -c) as the plant, e.g. 'cvtplant-bridge --iface vcan0',\n"
    "                      wait until it answers (30 s at most) and stop it after the runs; its\n"
    "                      output into DIR/plant.log\n"
    "  --loopback-frame-cost-us US  real time on the loopback bus: each plant frame's work takes US us\n"
    "                      of virtual time (default 0; above 1000 the plant cannot keep time)\n"
    "  --reply-timeout-ms T  send a request again when its answer is not complete after T ms\n"
    "                      (default 1000; 20 with --loopback, whose answers are immediate)\n"
    "  --out DIR           per-scenario CSV traces (default .)\n"
    "  --junit FILE        JUnit XML report of every criterion\n"
    "  --safety X          the example controller's safety factor (default 1.3)\n"
    "  --clamp-floor N     the example ratio law's clamping floor on each pulley [N] (default 12500)\n"
    "  --steps N           bench: lock-step round trips (default 5000)\n"
    "  --with-controller   bench: a CtrlCmd from the controller before each Step\n"
    "Exit status: 0 all criteria passed, 1 a criterion failed or the plant did not answer, 2 bad command line.\n";

[[noreturn]] void bad_usage(const std::string& msg) {
  std::fprintf(stderr, "cvtplant-sil: %s (see --help)\n", msg.c_str());
  std::exit(2);
}

double number(const std::string& flag, const std::string& v, double lo, double hi) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || !(d >= lo && d <= hi)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: expected %g..%g, got '", flag.c_str(), lo, hi);
    bad_usage(buf + v + "'");
  }
  return d;
}

}  // namespace

void print_usage() {
  std::fputs(kUsage, stdout);
  for (const Subcommand& c : subcommands()) std::fputs(c.usage.c_str(), stdout);
  std::printf("Plants (--plant):\n");
  for (const PlantKind& k : plant_kinds()) {
    std::printf("  %-19s %s\n", k.name.c_str(), k.what.c_str());
    std::fputs(k.options_usage.c_str(), stdout);
  }
}

std::string subcommand_names() {
  std::string n = "run, bench";
  for (const Subcommand& c : subcommands()) n += ", " + c.name;
  return n;
}

int main(int argc, char** argv) {
  if (argc < 2) bad_usage("missing subcommand (" + subcommand_names() + ")");
  const std::string cmd = argv[1];
  if (cmd == "-h" || cmd == "--help") {
    print_usage();
    return 0;
  }
  for (const Subcommand& c : subcommands())
    if (cmd == c.name) return c.main(argc, argv);
  if (cmd != "run" && cmd != "bench") bad_usage("unknown subcommand '" + cmd + "' (" + subcommand_names() + ")");
  std::string iface = "vcan0", scenario = "all", out_dir = ".", junit, mode = "lockstep", controller = "example";
  std::string controller_cmd, plant_cmd, plant_name = "rom";
  std::vector<std::string> plant_options;
  long steps = 5000;
  bool with_controller = false, loopback = false, safety_given = false, allow_partial = false, junit_given = false;
  double reply_timeout_ms = 0;  // 0: the default for the transport
  double t_end_s = 0, controller_timeout_ms = 1000;
  std::int64_t frame_cost_ns = 0;
  cvtctl::ClampLawParams law;
  float clamp_floor_N = cvtctl::production_clamp_law().clamp_min_N;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      print_usage();
      return 0;
    }
    if (a == "--with-controller" || a == "--loopback" || a == "--allow-partial") {
      (a == "--loopback" ? loopback : a == "--allow-partial" ? allow_partial : with_controller) = true;
      continue;
    }
    static const char* const kValueFlags[] = {
        "--iface", "--scenario", "--out", "--junit", "--safety", "--clamp-floor", "--steps", "--reply-timeout-ms", "--mode",
        "--loopback-frame-cost-us", "--controller", "--controller-cmd", "--controller-timeout-ms", "--plant-cmd",
        "--t-end", "--plant", "--plant-option"};
    bool known = false;
    for (const char* k : kValueFlags) known = known || a == k;
    if (!known) bad_usage("unknown option '" + a + "'");
    if (i + 1 >= argc) bad_usage(a + ": missing value");
    const std::string v = argv[++i];
    if (a == "--iface") iface = v;
    else if (a == "--scenario") scenario = v;
    else if (a == "--out") out_dir = v;
    else if (a == "--junit") {
      junit = v;
      junit_given = true;
    }
    else if (a == "--controller-cmd") controller_cmd = v;
    else if (a == "--plant-cmd") plant_cmd = v;
    else if (a == "--plant-option") plant_options.push_back(v);
    else if (a == "--plant") {
      plant_name = v;
      if (find_plant_kind(v) == nullptr)
        bad_usage("--plant: expected " + plant_kind_names() + " (this build's plants), got '" + v + "'");
    }
    else if (a == "--loopback-frame-cost-us") frame_cost_ns = static_cast<std::int64_t>(number(a, v, 0, 100000) * 1e3 + 0.5);
    else if (a == "--mode") {
      mode = v;
      if (mode != "lockstep" && mode != "realtime" && mode != "both")
        bad_usage("--mode: expected lockstep, realtime or both, got '" + v + "'");
    } else if (a == "--controller") {
      controller = v;
      if (controller != "example" && controller != "external")
        bad_usage("--controller: expected example or external, got '" + v + "'");
    } else if (a == "--safety") {
      char* end = nullptr;
      law.safety = std::strtof(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(law.safety > 0.1f && law.safety < 10.0f))
        bad_usage("--safety: expected a number in (0.1, 10), got '" + v + "'");
      safety_given = true;
    } else if (a == "--clamp-floor") {
      clamp_floor_N = static_cast<float>(number(a, v, 100, 40000));
      safety_given = true;
    } else if (a == "--reply-timeout-ms") reply_timeout_ms = number(a, v, 1, 10000);
    else if (a == "--controller-timeout-ms") controller_timeout_ms = number(a, v, 1, 600000);
    else if (a == "--t-end") t_end_s = number(a, v, 0.01, 1e5);
    else if (a == "--steps") steps = static_cast<long>(number(a, v, 1, 10000000));
  }
  if (!controller_cmd.empty()) controller = "external";
  const bool external = controller == "external";
  if (external && loopback)
    bad_usage("--controller external: needs a CAN interface (--iface): the controller is another program");
  if (external && safety_given)
    bad_usage("--safety, --clamp-floor: set the example controller's margin, not an external one's");
  if (external && cmd == "bench") bad_usage("bench: runs the example controller only");
  if (loopback && !plant_cmd.empty()) bad_usage("--plant-cmd: the loopback bus has its plant in this process");

  // The chosen scenarios, in the table's order; an external controller
  // cannot show the faults inside a controller (with all: left out).
  ExternalOptions ext_opt;
  ext_opt.answer_timeout_ns = static_cast<std::int64_t>(controller_timeout_ms * 1e6);
  std::vector<Scenario> chosen;
  std::vector<std::string> left_out;
  const std::string selection_error = select_scenarios(
      scenario, t_end_s, chosen,
      [external](const Scenario& s, std::string& why) { return !external || ExternalController::accepts(s, why); },
      &left_out, "--controller external: ", allow_partial);
  if (!selection_error.empty()) bad_usage(selection_error);
  // Real time runs the ratio scenarios (docs/sil.md#ratio-realtime); the
  // fault scenarios need the harness's control of every step.
  const bool lockstep_runs = mode != "realtime", realtime_runs = mode != "lockstep";
  if (mode == "realtime" && scenario != "all")
    for (const Scenario& s : chosen)
      if (!s.ratio_target)
        bad_usage("--mode realtime: runs ratio-sweep, kick-down or slip-recovery, not '" + std::string(s.name) + "'");
  if (frame_cost_ns > 0 && (!loopback || !realtime_runs))
    bad_usage("--loopback-frame-cost-us: needs --loopback and --mode realtime or both");
  const PlantKind& kind = *find_plant_kind(plant_name);
  if (cmd == "bench" && plant_name != "rom") bad_usage("bench: measures the bus with the real-time plant (--plant rom)");
  if (reply_timeout_ms == 0) reply_timeout_ms = loopback ? 20 : kind.bus_reply_timeout_ms;
  PlantKindOptions kind_opt;
  kind_opt.out_dir = out_dir;
  kind_opt.frame_cost_ns = frame_cost_ns;
  if (!plant_options.empty() && !loopback)
    bad_usage("--plant-option: sets the plant in this process (--loopback); a plant on a bus takes its options on "
              "its own command line");
  for (const std::string& po : plant_options) {
    if (!kind.check_option) bad_usage("--plant-option: the plant " + plant_name + " has no options");
    const std::string why = kind.check_option(po);
    if (!why.empty()) bad_usage("--plant-option: " + why);
  }
  kind_opt.options = plant_options;
  RunConfig cfg;
  cfg.out_dir = out_dir;
  // Every file the run writes, before it starts: the JUnit report never
  // over a trace, no path empty or with a control character
  // (docs/cli.md#files).
  if (cmd == "run") {
    try {
      cvt::files::CommandFiles files;
      if (const std::string why = cvt::files::path_problem(out_dir); !why.empty())
        throw cvt::files::PathError("--out: " + why);
      for (const Scenario& s : chosen) {
        if (lockstep_runs) files.output("--out (scenario " + std::string(s.name) + ")", trace_path(cfg, s, false));
        if (realtime_runs && s.ratio_target)
          files.output("--out (scenario " + std::string(s.name) + ", real time)", trace_path(cfg, s, true));
      }
      if (!controller_cmd.empty()) files.output("--controller-cmd (its log)", out_dir + "/controller.log");
      if (!plant_cmd.empty()) files.output("--plant-cmd (its log)", out_dir + "/plant.log");
      if (!junit.empty() || junit_given) files.output("--junit", junit);
    } catch (const cvt::files::PathError& e) {
      bad_usage(e.what());
    }
  }
  // Traces are part of the result: a directory that cannot be made is an
  // error now, not a silently missing CSV later. One that another run makes
  // at the same moment is fine.
  try {
    cvt::files::make_directories(out_dir, "--out");
  } catch (const cvt::files::PathError& e) {
    std::fprintf(stderr, "cvtplant-sil: %s\n", e.what());
    return 1;
  }
  // A plant that cannot keep time is not run in real time (docs/sil.md#reference-realtime).
  if (realtime_runs && kind.realtime_refusal)
    for (const Scenario& s : chosen) {
      if (!s.ratio_target) continue;
      const std::string why = kind.realtime_refusal(s, kind_opt);
      if (!why.empty()) {
        std::fprintf(stderr, "cvtplant-sil: --mode %s with --plant %s: %s\n", mode.c_str(), plant_name.c_str(),
                     why.c_str());
        return 2;
      }
    }

  // The nodes: the plant (in-process only with --loopback), the harness and
  // the controller port, each with its own transport: the example
  // controller's socket, or the harness's port for an external controller.
  std::unique_ptr<InProcessBus> loop;
  std::unique_ptr<PlantUnderTest> plant;
  cvt::port::SocketCanTransport harness_sock, controller_sock;
  cvt::port::CanTransport* harness_bus = nullptr;
  cvt::port::CanTransport* controller_bus = nullptr;
  if (loopback) {
    loop = std::make_unique<InProcessBus>();
    plant = kind.in_process(*loop, kind_opt);
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
  ChildProcess plant_proc, controller_proc;
  if (!plant_cmd.empty() && !plant_proc.start(plant_cmd, out_dir + "/plant.log")) {
    std::fprintf(stderr, "cvtplant-sil: --plant-cmd: %s\n", plant_proc.error().c_str());
    return 1;
  }
  // The harness's transport through a fault injector, which the fault
  // scenarios arm (docs/sil.md#fault-scenarios); otherwise it passes frames.
  FaultInjector harness_faults(*harness_bus);
  HarnessNode h(harness_faults, static_cast<std::int64_t>(reply_timeout_ms * 1e6), plant->idle());
  // A plant this harness started may take a while to open its socket.
  if (!h.sync(plant_cmd.empty() ? 5 : 30)) {
    const std::string why = plant_cmd.empty() || plant_proc.running() ? "" : " (--plant-cmd: " + plant_proc.ended() + ")";
    std::fprintf(stderr, "cvtplant-sil: the plant on %s does not answer SimCtrl%s\n",
                 loopback ? "loopback" : iface.c_str(), why.c_str());
    return 1;
  }
  // --safety sets the clamping margin of both laws (ClampLaw, RatioLaw).
  const cvtctl::RatioLawParams ratio_law = example_ratio_law(law, clamp_floor_N);
  std::unique_ptr<ControllerUnderTest> ctl;
  ExampleController* example = nullptr;
  if (external) {
    ctl = std::make_unique<ExternalController>(*controller_bus, ext_opt);
  } else {
    auto e = std::make_unique<ExampleController>(*controller_bus, law, ratio_law);
    example = e.get();
    ctl = std::move(e);
  }
  if (cmd == "bench") return bench(h, with_controller ? &example->node() : nullptr, steps);
  if (!controller_cmd.empty() && !controller_proc.start(controller_cmd, out_dir + "/controller.log")) {
    std::fprintf(stderr, "cvtplant-sil: --controller-cmd: %s\n", controller_proc.error().c_str());
    return 1;
  }
  for (const std::string& n : left_out)
    std::printf("not run: %s (its faults are inside the controller: the example controller only)\n", n.c_str());
  if (external && !static_cast<ExternalController&>(*ctl).wait_ready()) {
    const std::string why =
        controller_cmd.empty() || controller_proc.running() ? "" : " (--controller-cmd: " + controller_proc.ended() + ")";
    std::fprintf(stderr, "cvtplant-sil: no controller answered HarnessDemand on %s within 10 s%s\n", iface.c_str(),
                 why.c_str());
    if (!controller_cmd.empty()) controller_proc.stop();
    if (!plant_cmd.empty()) plant_proc.stop();
    return 1;
  }

  // Real-time pacing: the bridge process on the wall clock, or the
  // in-process bridge one frame per virtual millisecond.
  const RealTimeBus rt_bus = plant->realtime();
  cfg.plant = plant.get();
  std::vector<ScenarioResult> results;
  bool all_pass = true;
  for (const Scenario& s : chosen) {
    if (lockstep_runs) {
      results.push_back(run_lockstep(s, h, harness_faults, *ctl, cfg));
      all_pass = all_pass && results.back().pass();
      print_result(results.back(), s.what);
    }
    if (realtime_runs && s.ratio_target) {
      results.push_back(run_realtime(s, h, *ctl, cfg, rt_bus));
      all_pass = all_pass && results.back().pass();
      print_result(results.back(), s.what);
    }
  }
  // A started controller that ended before the runs did is reported.
  if (!controller_cmd.empty()) {
    const bool was_running = controller_proc.running();
    const std::string how = controller_proc.stop();
    const std::string said = was_running ? "ran through every run, stopped" : "ended by itself before the end, " + how;
    std::printf("controller (%s): %s; its output in %s/controller.log\n", controller_cmd.c_str(), said.c_str(),
                out_dir.c_str());
  }
  if (!plant_cmd.empty()) {
    const std::string how = plant_proc.stop();
    std::printf("plant (%s): %s; its output in %s/plant.log\n", plant_cmd.c_str(), how.c_str(), out_dir.c_str());
  }
  if (!junit.empty() && !write_junit(junit, results)) {
    std::fprintf(stderr, "cvtplant-sil: --junit %s: %s\n", junit.c_str(), std::strerror(errno));
    return 1;
  }
  return all_pass ? 0 : 1;
}
