#include "cvtplant/analysis/systems.hpp"

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/rom_scenes.hpp"
#include "cvtplant/integrate/explicit_rk.hpp"
#include "cvtplant/plant/oscillator.hpp"

namespace cvt::analysis {
namespace {

template <class Flow>
std::vector<double> flow_trajectory(const Flow& sys, const std::vector<double>& x0, double dt, double t_tr,
                                    double t_end, double sample_dt, const ProgressFn& progress) {
  constexpr int N = Flow::kStates;
  using V = Eigen::Matrix<double, N, 1>;
  if (static_cast<int>(x0.size()) != N) throw InputError("x0 needs " + std::to_string(N) + " values");
  if (!(dt > 0) || !(sample_dt > 0) || !(t_end > 0)) throw InputError("trajectory: need dt, sample_dt, t_end > 0");
  V x = Eigen::Map<const V>(x0.data());
  const long every = std::max(1L, std::lround(sample_dt / dt));
  const long n_tr = std::lround(t_tr / dt), n = std::lround(t_end / dt);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n / every + 1) * N);
  for (long s = 0; s < n_tr + n; ++s) {
    if ((s & 16383) == 0 && progress) progress(static_cast<double>(s), static_cast<double>(n_tr + n));
    step_rk4(sys, x, dt);
    if (s >= n_tr && (s - n_tr + 1) % every == 0) {
      if (!x.allFinite()) throw std::runtime_error("trajectory became non-finite");
      for (int i = 0; i < N; ++i) out.push_back(x(i));
    }
  }
  return out;
}

template <class Map>
std::vector<double> map_trajectory(const Map& sys, const std::vector<double>& x0, double t_tr, double t_end,
                                   const ProgressFn& progress) {
  constexpr int N = Map::kStates;
  using V = Eigen::Matrix<double, N, 1>;
  if (static_cast<int>(x0.size()) != N) throw InputError("x0 needs " + std::to_string(N) + " values");
  V x = Eigen::Map<const V>(x0.data()), xn;
  std::vector<double> out;
  const long n_tr = std::lround(t_tr), n = std::lround(t_end);
  for (long s = 0; s < n_tr + n; ++s) {
    if ((s & 65535) == 0 && progress) progress(static_cast<double>(s), static_cast<double>(n_tr + n));
    sys.step(x, xn);
    x = xn;
    if (s >= n_tr)
      for (int i = 0; i < N; ++i) out.push_back(x(i));
  }
  if (!x.allFinite()) throw std::runtime_error("map orbit diverged");
  return out;
}

template <int N>
Eigen::Matrix<double, N, 1> to_vec(const std::vector<double>& x0) {
  if (static_cast<int>(x0.size()) != N) throw InputError("x0 needs " + std::to_string(N) + " values");
  return Eigen::Map<const Eigen::Matrix<double, N, 1>>(x0.data());
}

double get(const Params& p, const char* k) { return p.at(k); }

Lorenz make_lorenz(const Params& p) {
  Lorenz s;
  std::tie(s.sigma, s.rho, s.beta) = std::make_tuple(get(p, "sigma"), get(p, "rho"), get(p, "beta"));
  return s;
}
Rossler make_rossler(const Params& p) {
  Rossler s;
  std::tie(s.a, s.b, s.c) = std::make_tuple(get(p, "a"), get(p, "b"), get(p, "c"));
  return s;
}
Henon make_henon(const Params& p) {
  Henon s;
  std::tie(s.a, s.b) = std::make_tuple(get(p, "a"), get(p, "b"));
  return s;
}
Logistic make_logistic(const Params& p) {
  Logistic s;
  s.r = get(p, "r");
  return s;
}

// The seed's section-3 values (physics/seed.hpp), as named parameters.
Params oscillator_params(bool stribeck) {
  const OscillatorParams<double> o;
  const FrictionParams<double> f = stribeck ? friction_presets::oscillator_stribeck<double>()
                                            : friction_presets::oscillator_coulomb<double>();
  Params p{{"m1_kg", o.m1_kg},     {"m2_kg", o.m2_kg},     {"k1_N_m", o.k1_N_m},
           {"k2_N_m", o.k2_N_m},   {"c1_Ns_m", o.c1_Ns_m}, {"c2_Ns_m", o.c2_Ns_m},
           {"belt_speed_m_s", o.belt_speed_m_s},           {"g_m_s2", o.g_m_s2},
           {"mu0", f.mu0},         {"lambda_s_m", f.lambda_s_m}};
  if (stribeck) {
    p["sigma"] = f.sigma;
    p["kappa_s_m"] = f.kappa_s_m;
    p["chi_s_m"] = f.chi_s_m;
  }
  return p;
}

// The core's heap-free seed oscillator (lib/include/cvtplant/plant/oscillator.hpp),
// seed Eq. 9, parameterised from the model's named parameters.
StickSlipOscillator<double> make_oscillator(const Params& p, bool stribeck) {
  FrictionParams<double> f = stribeck ? friction_presets::oscillator_stribeck<double>()
                                      : friction_presets::oscillator_coulomb<double>();
  f.mu0 = get(p, "mu0");
  f.lambda_s_m = get(p, "lambda_s_m");
  if (stribeck) {
    f.sigma = get(p, "sigma");
    f.kappa_s_m = get(p, "kappa_s_m");
    f.chi_s_m = get(p, "chi_s_m");
  }
  OscillatorParams<double> o = OscillatorParams<double>::seed_section3(f);
  o.m1_kg = get(p, "m1_kg");
  o.m2_kg = get(p, "m2_kg");
  o.k1_N_m = get(p, "k1_N_m");
  o.k2_N_m = get(p, "k2_N_m");
  o.c1_Ns_m = get(p, "c1_Ns_m");
  o.c2_Ns_m = get(p, "c2_Ns_m");
  o.belt_speed_m_s = get(p, "belt_speed_m_s");
  o.g_m_s2 = get(p, "g_m_s2");
  return StickSlipOscillator<double>(o);
}

// A model's description and the run that resolves it (dt, transient,
// warm-up, accumulation; maps count iterations and ignore dt).
Model described(const char* name, const char* description, std::vector<std::string> states,
                std::vector<double> x0, Params params, double dt, double t_transient, double t_warmup,
                double t_end) {
  Model s;
  s.name = name;
  s.description = description;
  s.dim = static_cast<int>(states.size());
  s.state_names = std::move(states);
  s.default_x0 = std::move(x0);
  s.default_params = std::move(params);
  s.defaults.dt = dt;
  s.defaults.t_transient = t_transient;
  s.defaults.t_warmup = t_warmup;
  s.defaults.t_end = t_end;
  return s;
}

// A flow of N states whose system make(p) builds from the named parameters.
template <int N, class Make>
Model flow_model(Model s, Make make) {
  s.spectrum = [make](const Params& p, const std::vector<double>& x0, const BenettinOptions& o) {
    return lyapunov_flow(make(p), to_vec<N>(x0), o);
  };
  s.trajectory_fn = [make](const Params& p, const std::vector<double>& x0, double dt, double a, double b, double c,
                           const ProgressFn& pr) { return flow_trajectory(make(p), x0, dt, a, b, c, pr); };
  return s;
}

// The same for a map of N states (times are iterations).
template <int N, class Make>
Model map_model(Model s, Make make) {
  s.is_map = true;
  s.spectrum = [make](const Params& p, const std::vector<double>& x0, const BenettinOptions& o) {
    return lyapunov_map(make(p), to_vec<N>(x0), o);
  };
  s.trajectory_fn = [make](const Params& p, const std::vector<double>& x0, double, double a, double b, double,
                           const ProgressFn& pr) { return map_trajectory(make(p), x0, a, b, pr); };
  return s;
}

std::vector<Model>& table() {
  static std::vector<Model> t = [] {
    std::vector<Model> v;
    v.push_back(flow_model<3>(described("lorenz", "Lorenz (sigma=10, rho=28, beta=8/3)", {"x", "y", "z"}, {1, 1, 1},
                                        {{"sigma", 10}, {"rho", 28}, {"beta", 8.0 / 3.0}}, 0.005, 50, 10, 2000),
                              make_lorenz));
    v.push_back(flow_model<3>(described("rossler", "Roessler (a=b=0.2, c=5.7)", {"x", "y", "z"}, {1, 1, 0},
                                        {{"a", 0.2}, {"b", 0.2}, {"c", 5.7}}, 0.01, 200, 50, 20000),
                              make_rossler));
    for (const bool stribeck : {false, true}) {
      // Coulomb: the atan slope 2 mu0 g lambda / pi ~ 1.6e4 1/s near stick
      // limits RK4 to dt < 2.8/1.6e4 ~ 1.8e-4 there; Stribeck: mu(0) = 0 removes that stiffness
      // and dt = 1e-3 changes the exponents by < 1e-8 against dt/2
      // (docs/analysis.md#seed-oscillator).
      const Model s = described(
          stribeck ? "oscillator-stribeck" : "oscillator-coulomb",
          stribeck ? "seed Eq. 9 2-DOF stick-slip oscillator, Stribeck friction (seed sec. 3)"
                   : "seed Eq. 9 2-DOF stick-slip oscillator, constant (Coulomb) friction (seed sec. 3)",
          {"x1_m", "v1_m_s", "x2_m", "v2_m_s"}, {0, 3, 0, 6}, oscillator_params(stribeck), stribeck ? 1e-3 : 1e-4,
          stribeck ? 200 : 0, 20, stribeck ? 2000 : 200);
      v.push_back(flow_model<4>(s, [stribeck](const Params& p) { return make_oscillator(p, stribeck); }));
    }
    v.push_back(map_model<2>(described("henon", "Henon map (a=1.4, b=0.3); times are iterations", {"x", "y"},
                                       {0.1, 0.1}, {{"a", 1.4}, {"b", 0.3}}, BenettinOptions{}.dt, 1000, 100, 1000000),
                             make_henon));
    v.push_back(map_model<1>(described("logistic", "logistic map x -> r x (1-x), r=4; times are iterations", {"x"},
                                       {0.3}, {{"r", 4}}, BenettinOptions{}.dt, 1000, 100, 1000000),
                             make_logistic));
    add_rom_models(v);
    return v;
  }();
  return t;
}

}  // namespace

const std::vector<Model>& models() { return table(); }

void register_model(Model s) {
  for (auto& t : table())
    if (t.name == s.name) {
      t = std::move(s);
      return;
    }
  table().push_back(std::move(s));
}

bool has_model(const std::string& name) {
  for (const Model& m : table())
    if (m.name == name) return true;
  return false;
}

const Model& find_model(const std::string& name) {
  std::string known;
  for (const auto& s : table()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw InputError("unknown scene '" + name + "' (known: " + known + ")");
}

Params merge_params(const Model& s, const Params& overrides) {
  Params p = s.default_params;
  for (const auto& [k, v] : overrides) {
    if (!p.count(k)) {
      std::string known;
      for (const auto& [kk, vv] : s.default_params) known += (known.empty() ? "" : ", ") + kk;
      throw InputError("scene '" + s.name + "' has no parameter '" + k + "' (parameters: " + known + ")");
    }
    if (!std::isfinite(v)) throw InputError("parameter '" + k + "' must be finite");
    p[k] = v;
  }
  return p;
}

}  // namespace cvt::analysis
