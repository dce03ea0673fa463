// The plants and subcommands of cvtplant-sil (docs/sil.md#plants).
#include "cvtplant/sil/harness/extensions.hpp"

namespace cvt::sil::harness {

namespace {

// Function-local tables: registrations from other translation units run at
// their static initialisation, in any order.
std::vector<PlantKind>& kinds() {
  static std::vector<PlantKind> k{PlantKind{
      "rom", "the scene's real-time plant (docs/rom.md), the default",
      [](InProcessBus& bus, const PlantKindOptions& o) -> std::unique_ptr<PlantUnderTest> {
        return std::make_unique<LoopbackBridgePlant>(bus, o.frame_cost_ns);
      },
      "cvtplant-bridge", 1000, {}, {}, ""}};
  return k;
}

std::vector<Subcommand>& commands() {
  static std::vector<Subcommand> c;
  return c;
}

}  // namespace

void register_plant_kind(PlantKind k) { kinds().push_back(std::move(k)); }
const std::vector<PlantKind>& plant_kinds() { return kinds(); }

const PlantKind* find_plant_kind(const std::string& name) {
  for (const PlantKind& k : kinds())
    if (k.name == name) return &k;
  return nullptr;
}

std::string plant_kind_names() {
  std::string n;
  for (const PlantKind& k : kinds()) n += (n.empty() ? "" : ", ") + k.name;
  return n;
}

void register_subcommand(Subcommand s) { commands().push_back(std::move(s)); }
const std::vector<Subcommand>& subcommands() { return commands(); }

}  // namespace cvt::sil::harness
