// cvtplant-bridge: a built-in scene's real-time plant on a SocketCAN
// interface (docs/sil.md#bridge). Lock-step by default: it waits for SimCtrl
// requests. `--mode realtime` paces frames on CLOCK_MONOTONIC with absolute
// deadlines. On SIGINT/SIGTERM or at the end of --duration-s it prints a JSON
// summary. The program around the bridge is hil/common/bridge_program.hpp.
#include <memory>

#include "bridge_program.hpp"

int main(int argc, char** argv) {
  cvt::hil::BridgeProgram<cvt::sil::ScenePlant> prog;
  prog.name = "cvtplant-bridge";
  prog.description =
      "Runs a built-in scene's plant (double, the scene's integrator and frame)\n"
      "on a SocketCAN interface, with the messages of hil/cvtplant.dbc.\n";
  prog.extra_usage = "";
  prog.make_bridge = [](cvt::port::CanTransport& bus, cvt::port::Clock& clock, cvt::sil::FrameSink* sink) {
    return std::make_unique<cvt::sil::Bridge>(bus, clock, sink);
  };
  return cvt::hil::bridge_program_main(argc, argv, prog);
}
