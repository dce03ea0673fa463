// What cvtplant-sil can be extended with (docs/sil.md#plants): plants to
// run the scenarios against (`--plant NAME`) and subcommands. The harness
// knows the scene's real-time plant (`rom`) only; a host module that may use
// more than hil/ (cosim/: the multibody reference, the closed-loop
// comparison) registers its own when it is linked into the program, so hil/
// depends on nothing but lib/ and port/. Host only.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/sil/harness/plant.hpp"
#include "cvtplant/sil/harness/scenario.hpp"

namespace cvt::sil::harness {

struct PlantKindOptions {
  std::string out_dir = ".";        // the run's outputs (a plant may keep a cache there)
  std::int64_t frame_cost_ns = 0;   // --loopback-frame-cost-us
  // --plant-option NAME=VALUE, in order: the plant's own settings (its
  // PlantKind::check_option has accepted each).
  std::vector<std::string> options;
};

struct PlantKind {
  std::string name;  // `--plant NAME`
  std::string what;  // one line for --help
  // The plant in this process on the loopback bus.
  std::function<std::unique_ptr<PlantUnderTest>(InProcessBus&, const PlantKindOptions&)> in_process;
  // How to serve it on a CAN interface, for messages ("cvtplant-bridge").
  std::string bus_program;
  // The reply timeout on a CAN interface when --reply-timeout-ms is not
  // given: how long one 10-frame Step may take on a slow host.
  double bus_reply_timeout_ms = 1000;
  // Real time: empty when the plant keeps time for the scenario, else why
  // not (the run is refused).
  std::function<std::string(const Scenario&, const PlantKindOptions&)> realtime_refusal;
  // One --plant-option NAME=VALUE: "" when the plant takes it, else the
  // usage error; empty: the plant has no options.
  std::function<std::string(const std::string& option)> check_option;
  std::string options_usage;  // its options for --help ("" for none)
};

// Registers a kind (at static initialisation: `static const bool r = (register_plant_kind({...}), true);`).
void register_plant_kind(PlantKind k);
// Every kind, `rom` first.
const std::vector<PlantKind>& plant_kinds();
const PlantKind* find_plant_kind(const std::string& name);
std::string plant_kind_names();  // "rom, reference"

struct Subcommand {
  std::string name;   // cvtplant-sil NAME ...
  std::string usage;  // its lines for --help
  // argv[0] is the program, argv[1] the subcommand. Exit status as run's.
  std::function<int(int argc, char** argv)> main;
};
void register_subcommand(Subcommand s);
const std::vector<Subcommand>& subcommands();

}  // namespace cvt::sil::harness
