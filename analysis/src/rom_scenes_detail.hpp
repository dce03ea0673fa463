#pragma once
// What rom_scenes.cpp and the spectrum shards (rom_spectrum_<k>.cpp) share:
// the plant behind the scene dispatch, the helpers of rom_scenes.cpp, the
// state counts of the plants, and the declarations of the spectrum and
// trajectory templates, defined in rom_scenes_flow.hpp and instantiated once
// per state count, each count in its own translation unit so that a build
// compiles them in parallel (docs/analysis.md#rom-lyapunov).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cvtplant/analysis/lyapunov.hpp"
#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/scene/all_plants.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt::analysis::rom_detail {

using Outputs = cvt::RomOutputs<double>;
using Sim = cvt::IRomSimulator<double>;
using Holder = cvt::SceneSimulator<cvt::AllRomPlants<double>>;

// Builds the scene's plant (double) or throws InputError naming the problem.
void load(Holder& h, const cvt::Scene& s, const std::string& name);
// The scene with the model parameters of `p` (rom_params_of) applied.
cvt::Scene apply(const cvt::Scene& base, const std::string& name, const Params& p);
std::string fmt(const char* f, double a, double b = 0, double c = 0);

// The state counts of the double plants (AllRomPlants<double>), distinct
// and increasing: every feature mask the set holds, through the layout's
// own count (plant/rom_layout.hpp).
namespace counts {
constexpr int kMax = cvt::rom_state_index(cvt::rom_feature::known).count + 8;
constexpr std::array<bool, kMax + 1> present() {
  std::array<bool, kMax + 1> seen{};
  for (std::uint32_t m = 0; m <= cvt::rom_feature::known; ++m)
    if (cvt::AllRomPlants<double>::contains(m)) seen[static_cast<std::size_t>(cvt::rom_state_index(m).count)] = true;
  return seen;
}
constexpr std::size_t number() {
  std::size_t n = 0;
  for (const bool b : present()) n += b ? 1 : 0;
  return n;
}
}  // namespace counts
constexpr std::array<int, counts::number()> kRomStateCounts = [] {
  std::array<int, counts::number()> out{};
  std::size_t k = 0;
  const auto seen = counts::present();
  for (int n = 0; n <= counts::kMax; ++n)
    if (seen[static_cast<std::size_t>(n)]) out[k++] = n;
  return out;
}();

// The spectrum and the trajectory of a plant of N states (rom_scenes_flow.hpp).
template <int N>
SpectrumResult rom_spectrum(const cvt::Scene& base, const std::string& name, const Params& p,
                            const std::vector<double>& x0, const BenettinOptions& o);
template <int N>
std::vector<double> rom_trajectory(const cvt::Scene& base, const std::string& name, const Params& p,
                                   const std::vector<double>& x0, double dt, double t_tr, double t_end,
                                   double sample_dt, const ProgressFn& progress);

}  // namespace cvt::analysis::rom_detail
