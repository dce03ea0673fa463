// cvtplant-reference-bridge: the multibody reference as the plant on a
// SocketCAN interface (docs/sil.md#reference-plant): the bridge's program
// (hil/common/bridge_program.hpp: the same DBC, E2E, diagnostics, lock-step
// protocol and summary as cvtplant-bridge) with cvt::cosim::ReferencePlant
// behind it. Real time is refused unless the reference keeps time.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include "bridge_program.hpp"
#include "cvtplant/cosim/reference_plant.hpp"

namespace {

using Plant = cvt::cosim::ReferencePlant;
constexpr const char* kName = "cvtplant-reference-bridge";

double number(const std::string& flag, const char* v, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double d = std::strtod(v, &end);
  if (end == v || *end != '\0' || errno != 0 || !(d >= lo && d <= hi)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: expected %g..%g, got '%s'", flag.c_str(), lo, hi, v);
    cvt::hil::bad_usage(kName, buf);
  }
  return d;
}

std::string json_text(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    o += c;
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  cvt::cosim::ReferenceOptions ro;
  cvt::hil::BridgeProgram<Plant> prog;
  prog.name = kName;
  prog.description =
      "Runs the multibody chain CVT reference (docs/mbd.md) as the plant of a built-in scene on a\n"
      "SocketCAN interface, with the messages of hil/cvtplant.dbc: the scene's reference inputs from\n"
      "the validation module's mapping, the real-time plant's actuators in front of its sheaves.\n"
      "Lock-step; real time only when the reference keeps time (it does not on this project's hosts).\n";
  prog.extra_usage =
      "  --rtol R              the reference's BDF tolerance (default 5e-7)\n"
      "  --ledger-tol X        relative energy-ledger residual that faults the plant (default 1e-6)\n"
      "  --max-steps-per-frame N  integrator steps a 1 ms frame may take before it faults (default 200000)\n"
      "  --release-cache DIR   keep each scene's release state (its start-up, seconds of CPU) in DIR\n"
      "  --inject-fault KIND@T test hook: report fault KIND (ledger, torn_chain, runaway, step_cap,\n"
      "                        solver, state, input) at T s of simulated time\n";
  prog.extra_flags = {"--rtol", "--ledger-tol", "--max-steps-per-frame", "--release-cache", "--inject-fault"};
  prog.parse_extra = [&ro](const std::string& flag, const char* v) {
    if (flag == "--rtol") ro.stepper.rtol = number(flag, v, 1e-12, 1e-2);
    else if (flag == "--ledger-tol") ro.stepper.ledger_tol = number(flag, v, 1e-15, 1.0);
    else if (flag == "--max-steps-per-frame")
      ro.stepper.max_steps_per_frame = static_cast<long long>(number(flag, v, 1, 1e9));
    else if (flag == "--release-cache") ro.release_cache_dir = v;
    else if (flag == "--inject-fault") {
      const std::string s = v;
      const std::size_t at = s.find('@');
      if (at == std::string::npos) cvt::hil::bad_usage(kName, "--inject-fault: expected KIND@T, got '" + s + "'");
      try {
        ro.inject.kind = cvt::cosim::step_fault_by_name(s.substr(0, at));
      } catch (const std::invalid_argument& e) {
        cvt::hil::bad_usage(kName, std::string("--inject-fault: ") + e.what());
      }
      if (ro.inject.kind == cvt::mbd::StepFault::none)
        cvt::hil::bad_usage(kName, "--inject-fault: 'none' is no fault");
      ro.inject.at_s = number(flag, s.c_str() + at + 1, 0, 1e6);
    }
  };
  prog.make_bridge = [&ro](cvt::port::CanTransport& bus, cvt::port::Clock& clock, cvt::sil::FrameSink* sink) {
    return std::make_unique<cvt::sil::BasicBridge<Plant>>(bus, clock, sink, ro);
  };
  prog.summary_extra = [](std::FILE* out, const cvt::sil::BasicBridge<Plant>& b) {
    const Plant& p = b.plant();
    std::fprintf(out,
                 "  \"reference\": {\"fault_message\": \"%s\", \"step_cpu_s\": %.3f, \"reset_cpu_s\": %.3f, "
                 "\"release_from_cache\": %s, \"rtol\": %g},\n",
                 json_text(p.fault_message()).c_str(), p.step_cpu_s(), p.reset_cpu_s(),
                 p.release_from_cache() ? "true" : "false", p.options().stepper.rtol);
  };
  return cvt::hil::bridge_program_main(argc, argv, prog);
}
