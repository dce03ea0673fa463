// The reduced-order CVT plant in the analysis toolkit (docs/analysis.md#rom-scenes).
// The spectrum and trajectory templates are declared in rom_scenes_detail.hpp
// and instantiated per state count in rom_spectrum_<k>.cpp.
#include "cvtplant/analysis/rom_scenes.hpp"

#include <cstdio>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/plant/rom_signals.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#include "fmt.hpp"
#include "rom_scenes_detail.hpp"

namespace cvt::analysis {
namespace rom_detail {

void load(Holder& h, const cvt::Scene& s, const std::string& name) {
  const cvt::SceneIssue issue = h.load(s);
  if (!issue.ok) throw InputError("scene '" + name + "': " + issue.field + ": " + issue.message);
}

std::string fmt(const char* f, double a, double b, double c) { return detail::fmt(f, a, b, c); }

cvt::Scene apply(const cvt::Scene& base, const std::string& name, const Params& p) {
  cvt::Scene s = base;
  s.tau_in = cvt::constant_profile(p.at("tau_in_Nm"));
  s.tau_load = cvt::constant_profile(p.at("tau_load_Nm"));
  s.clamp = cvt::constant_profile(p.at("clamp_N"));
  s.params.friction.mu0 = p.at("mu0");
  const cvt::SceneIssue issue = cvt::validate_scene(s);
  if (!issue.ok) throw InputError("scene '" + name + "': " + issue.field + ": " + issue.message);
  return s;
}

}  // namespace rom_detail

namespace {

using namespace rom_detail;

// fn(std::integral_constant<int, N>) for a plant of n states, N one of
// kRomStateCounts: the spectrum code works on fixed-size Eigen types (the
// same kernels, and so the same bits, as for the reference systems).
template <class Fn, std::size_t... K>
auto with_state_count(int n, Fn&& fn, std::index_sequence<K...>) {
  using R = decltype(fn(std::integral_constant<int, kRomStateCounts[0]>{}));
  if constexpr (std::is_void_v<R>) {
    if (((n == kRomStateCounts[K] ? (fn(std::integral_constant<int, kRomStateCounts[K]>{}), true) : false) || ...))
      return;
  } else {
    R out{};
    if (((n == kRomStateCounts[K] ? (out = fn(std::integral_constant<int, kRomStateCounts[K]>{}), true) : false) ||
         ...))
      return out;
  }
  throw std::logic_error("no plant has " + std::to_string(n) + " states");
}
template <class Fn>
auto with_state_count(int n, Fn&& fn) {
  return with_state_count(n, std::forward<Fn>(fn), std::make_index_sequence<kRomStateCounts.size()>{});
}

// Model parameters that `--param` may change: the three constant inputs and mu0.
Params rom_params_of(const cvt::Scene& s) {
  return {{"tau_in_Nm", s.tau_in.value},
          {"tau_load_Nm", s.tau_load.value},
          {"clamp_N", s.clamp.value},
          {"mu0", s.params.friction.mu0}};
}
}  // namespace

// The core states every plant has (rom_layout.hpp), sampled in SI units:
// the lumps' positions and speeds, which are states, not output signals.
constexpr int kStateSignalIndex[] = {2, 3, 4, 5};
constexpr const char* kStateSignalUnits[] = {"m", "m/s", "m", "m/s"};
const char* state_signal_name(int k) { return cvt::rom_state_name(0, kStateSignalIndex[k]); }

// The plant's signal of a name (plant/rom_signals.hpp), or RomSignal::count.
cvt::RomSignal output_signal(const std::string& name) { return cvt::rom_signal_by_name(name.c_str()); }

std::string rom_signal_unit(const std::string& name) {
  if (const cvt::RomSignal s = output_signal(name); s != cvt::RomSignal::count) return cvt::rom_signal_info(s).unit;
  for (int k = 0; k < 4; ++k)
    if (name == state_signal_name(k)) return kStateSignalUnits[k];
  throw InputError("unknown signal '" + name + "'");
}

const std::vector<std::string>& rom_signal_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& d : cvt::kRomSignals) v.push_back(d.name);
    for (int k = 0; k < 4; ++k) v.push_back(state_signal_name(k));
    return v;
  }();
  return names;
}

RomSeries rom_scene_series(const cvt::Scene& scene, const std::string& name, const std::vector<std::string>& signals,
                           double t_end, const ProgressFn& progress) {
  cvt::Scene s = scene;
  if (t_end > 0) s.t_end_s = t_end;
  std::vector<std::pair<std::string, cvt::RomSignal>> outputs;  // name, signal
  std::vector<std::pair<std::string, int>> states;             // name, state index
  for (const auto& sig : signals) {
    const cvt::RomSignal out = output_signal(sig);
    int state = -1;
    for (int k = 0; k < 4; ++k)
      if (sig == state_signal_name(k)) state = kStateSignalIndex[k];
    if (out == cvt::RomSignal::count && state < 0) {
      std::string known;
      for (const auto& k : rom_signal_names()) known += (known.empty() ? "" : ", ") + k;
      throw InputError("unknown signal '" + sig + "' (known: " + known + ")");
    }
    if (out != cvt::RomSignal::count) outputs.emplace_back(sig, out);
    else states.emplace_back(sig, state);
  }
  RomSeries r;
  r.scene = name;
  r.frame_s = s.frame_s;
  Holder holder;
  load(holder, s, name);
  const cvt::RomFault fault = cvt::run_frames(holder.sim(), s, s.frame_s, [&](long i, double t, const Sim& sim) {
    if ((i & 1023) == 0 && progress) progress(t, s.t_end_s);
    const Outputs o = sim.outputs();
    r.t.push_back(t);
    for (const auto& [n, id] : outputs) r.signal[n].push_back(cvt::rom_signal(o, sim.energy(), id));
    if (!states.empty()) {
      double xs[cvt::kRomMaxStates];
      sim.state_si(xs);
      for (const auto& [n, k] : states) r.signal[n].push_back(xs[k]);
    }
    return true;
  });
  r.fault = cvt::rom_fault_name(fault);
  return r;
}

Model rom_model(const cvt::Scene& scene, const std::string& name) {
  const std::pair<const char*, const cvt::Profile*> inputs[] = {
      {"tau_in", &scene.tau_in}, {"tau_load", &scene.tau_load}, {"clamp", &scene.clamp}};
  for (const auto& [field, profile] : inputs)
    if (profile->kind != cvt::ProfileKind::constant)
      throw InputError("scene '" + name + "': " + field +
                       " varies in time; the spectrum tools need constant inputs (an autonomous system)");
  Holder holder;
  load(holder, scene, name);
  const Sim& plant = holder.sim();
  const int n = plant.state_count();
  Model m;
  m.name = name;
  m.description = std::string("ROM plant (docs/rom.md): ") + scene.summary;
  m.dim = n;
  for (int i = 0; i < n; ++i) m.state_names.push_back(cvt::rom_state_name(scene.features, i));
  m.default_x0.resize(static_cast<std::size_t>(n));
  plant.initial_state(scene.initial, m.default_x0.data());
  m.default_params = rom_params_of(scene);
  with_state_count(n, [&](auto count) {
    constexpr int N = decltype(count)::value;
    cvt::Scene base = scene;
    base.name = "";  // the scene's strings may not outlive this call; `name` is kept instead
    base.summary = "";
    m.spectrum = [base, name](const Params& p, const std::vector<double>& x, const BenettinOptions& o) {
      return rom_spectrum<N>(base, name, p, x, o);
    };
    m.trajectory_fn = [base, name](const Params& p, const std::vector<double>& x, double dt, double a, double t,
                                   double c, const ProgressFn& pr) {
      return rom_trajectory<N>(base, name, p, x, dt, a, t, c, pr);
    };
  });
  // docs/analysis.md#rom-lyapunov: upper bounds; rom_spectrum shortens both
  // from the stiffest eigenvalue after the transient (the lump contact modes,
  // -1.3e4 1/s in case 1: at 1e-4 s RK4's own damping ln|R(h lambda)|/h would
  // replace them and the trace check would miss by 5 %). The start from rest
  // (stick, ~ -1e7 1/s) is left to the ros2 transient.
  m.defaults.dt = 1e-4;
  m.defaults.t_renorm = 1e-3;
  m.defaults.t_transient = 30;
  m.defaults.t_warmup = 5;  // > 4 / (torsional decay ~0.95 1/s): separates it from the symmetry direction
  m.defaults.t_end = 20;
  return m;
}

void add_rom_models(std::vector<Model>& table) {
  // Not gross-slip: there the friction saturates (|v_rel| ~ 86 m/s), so each
  // pulley speed is separately neutral and the one-symmetry count of
  // rom_spectrum would call the motion periodic (docs/analysis.md#rom-lyapunov).
  for (const char* name : {"seed-case1", "seed-case2"}) table.push_back(rom_model(*cvt::find_builtin_scene(name), name));
}

}  // namespace cvt::analysis
