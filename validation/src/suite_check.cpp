// A manoeuvre suite against the reference (docs/validation.md#suite).
#include "cvtplant/validation/suite_check.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "cvtplant/validation/errors.hpp"

namespace cvt::validation {

double Uncertainty::u_val() const { return std::sqrt(u_num() * u_num() + u_input * u_input); }

double input_share(double spread) { return 0.5 * spread / std::sqrt(3.0); }

std::vector<OpenChoice> open_choices(cvt::mbd::ParameterSet set) {
  if (set != cvt::mbd::ParameterSet::production) return {};
  return {{"friction.mu0", 0.08, 0.10,
           "pin-sheave friction in CVT fluid: the usual design value 0.09, not read in a source "
           "(docs/mbd-production.md#friction)"},
          {"joint_rot_damping_Nms_rad", 0.002, 0.02,
           "the articulation damper, a modelling choice over the range its docs explored "
           "(docs/mbd-production.md#articulation)"}};
}

namespace {

// A quantity of the goals on a run: a series' relative RMS or a
// steady-state mean, read off a Comparison of two series.
struct GoalQuantity {
  const char* goal;
  const char* row;  // the Comparison row
  bool steady;      // the steady-state error (else the relative RMS)
  double limit;
};
constexpr GoalQuantity kRunGoals[] = {
    {"ratio RMS", "ratio omega1/omega2", false, GoalLimits::ratio},
    {"geometric ratio RMS", "geometric ratio r2/r1", false, GoalLimits::ratio},
    {"omega1 RMS", "omega1", false, GoalLimits::speed},
    {"omega2 RMS", "omega2", false, GoalLimits::speed},
    {"mean F_ax1", "F_ax1 (mean)", true, GoalLimits::axial},
    {"mean F_ax2", "F_ax2 (mean)", true, GoalLimits::axial},
};

const ErrorRow* row_of(const Comparison& c, const char* name) {
  for (const auto& r : c.rows)
    if (r.quantity == name) return &r;
  return nullptr;
}

double goal_value(const Comparison& c, const GoalQuantity& g) {
  const ErrorRow* r = row_of(c, g.row);
  if (r == nullptr) return std::nan("");
  return g.steady ? r->ss_rel : r->rel_rms;
}

// The reference's change between two of its runs, in a goal's measure:
// the relative RMS of one against the other, or the relative change of the
// steady-state mean (compare() of the two reference series).
double change(const Series& a, const Series& b, const GoalQuantity& g) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n < 2) return std::nan("");
  return std::fabs(goal_value(compare(a, b, n), g));
}

// The configurations of the uncertainty runs: the tolerance tightened 10x
// and 100x, then each open choice at its two ends.
struct Variant {
  std::string name;
  ReferenceConfig c;
};
std::vector<Variant> variants(const ReferenceConfig& base) {
  std::vector<Variant> v;
  for (const double f : {10.0, 100.0}) {
    Variant x{f == 10.0 ? "rtol/10" : "rtol/100", base};
    x.c.rtol = base.rtol / f;
    v.push_back(x);
  }
  for (const OpenChoice& o : open_choices(base.set))
    for (const double value : {o.lo, o.hi}) {
      Variant x{o.field, base};
      x.c.overrides.emplace_back(o.field, value);
      v.push_back(x);
    }
  return v;
}

// The reference's uncertainty from its variants (in the order of
// variants()): `diff(i, j)` is a goal's relative difference between the
// runs of variants i and j (j = -1: the base run). Numerical: the change at
// 10x and 100x the tolerance; input: for each open choice the spread
// between its range's two ends, a uniform distribution over it (half the
// spread / sqrt(3), docs/validation.md#uncertainty).
template <class Diff>
Uncertainty combine(const std::vector<Variant>& vs, const Diff& diff) {
  Uncertainty u;
  u.u_num10 = diff(0, -1);
  u.u_num100 = diff(1, -1);
  double s2 = 0;
  for (std::size_t i = 2; i + 1 < vs.size(); i += 2) {
    const double share = input_share(diff(static_cast<int>(i), static_cast<int>(i + 1)));
    u.inputs.emplace_back(vs[i].name, share);
    s2 += share * share;
  }
  u.u_input = std::sqrt(s2);
  return u;
}

}  // namespace

double suite_reference_s(const Suite& suite, const ReferenceConfig& c, const SuiteOptions& o) {
  const auto length = [](const std::vector<Manoeuvre>& ms) {
    double t = 0;
    for (const auto& m : ms) t += m.t_end_s;
    return t;
  };
  double runs_s = length(suite.fit) + length(suite.held_out), measured_s = 0;
  for (const auto* part : {&suite.fit, &suite.held_out})
    for (const auto& m : *part)
      if (o.uncertainty == "all" ||
          std::count(suite.uncertainty_runs.begin(), suite.uncertainty_runs.end(), m.name) != 0)
        measured_s += m.t_end_s;
  double total = runs_s;
  if (o.maps) {
    total += length(map_manoeuvres());
    // The maps' uncertainty cells: a hold, an onset run and a shift-rate cell.
    std::vector<Manoeuvre> cells = shift_cell_manoeuvres(100.0, 1.5);
    cells.push_back(hold_manoeuvre(150.0, 1.5, 90.0, 0.3));
    cells.push_back(onset_manoeuvre(120.0));
    measured_s += length(cells);
  }
  if (o.uncertainty != "none") total += static_cast<double>(2 + 2 * open_choices(c.set).size()) * measured_s;
  return total;
}

SuiteResult check_suite(const Suite& suite, const cvt::Scene& plant, const ReferenceConfig& c,
                        const std::string& cache_dir, const SuiteOptions& o,
                        const cvt::mbd::ProgressSink& on_progress) {
  if (o.uncertainty != "none" && o.uncertainty != "subset" && o.uncertainty != "all")
    throw InputError("unknown uncertainty plan '" + o.uncertainty + "' (none, subset, all)");
  SuiteResult out;
  out.suite = suite;
  std::vector<Manoeuvre> all = suite.fit;
  all.insert(all.end(), suite.held_out.begin(), suite.held_out.end());
  // Progress: the simulated time of the reference runs made so far, over
  // every call below.
  double base_s = 0, last_s = 0;
  const cvt::mbd::ProgressSink progress = [&](double t) {
    last_s = t;
    if (on_progress) on_progress(base_s + t);
  };
  const auto next_call = [&] {
    base_s += last_s;
    last_s = 0;
  };
  const std::vector<ReferenceRun> refs = reference_manoeuvres(all, c, cache_dir, progress);
  next_call();
  for (std::size_t i = 0; i < all.size(); ++i) {
    ManoeuvreCheck k;
    k.m = all[i];
    k.held_out = i >= suite.fit.size();
    k.ref = refs[i];
    k.plant = plant_manoeuvre(k.m, plant, &k.ref.series, &k.hold);
    k.cmp = compare(k.plant, k.ref.series, std::min(k.plant.size(), k.ref.series.size()));
    out.reference_cpu_s += k.ref.cpu_s;
    ++out.reference_runs;
    out.from_cache += k.ref.from_cache ? 1 : 0;
    out.runs.push_back(std::move(k));
  }
  if (o.maps) {
    out.maps = make_maps(plant, c, cache_dir, progress);
    next_call();
    out.has_maps = true;
    out.reference_cpu_s += out.maps.reference_cpu_s;
    out.reference_runs += out.maps.reference_runs;
    out.from_cache += out.maps.from_cache;
  }
  // The reference's uncertainty on the runs the plan names.
  const std::vector<Variant> vs = o.uncertainty == "none" ? std::vector<Variant>{} : variants(c);
  std::map<std::string, Uncertainty> by_goal_kind;  // "kind|goal" -> the measured one
  std::map<std::string, std::string> from;
  if (!vs.empty()) {
    std::vector<const ManoeuvreCheck*> measured;
    for (const auto& k : out.runs)
      if (o.uncertainty == "all" || std::count(suite.uncertainty_runs.begin(), suite.uncertainty_runs.end(), k.m.name))
        measured.push_back(&k);
    std::vector<Manoeuvre> ms;
    for (const auto* k : measured) ms.push_back(k->m);
    std::vector<std::vector<ReferenceRun>> vr;
    for (const Variant& v : vs) {
      vr.push_back(reference_manoeuvres(ms, v.c, cache_dir, progress));
      next_call();
      for (const auto& r : vr.back()) out.reference_cpu_s += r.cpu_s;
    }
    for (std::size_t j = 0; j < measured.size(); ++j)
      for (const GoalQuantity& g : kRunGoals) {
        const auto& base = measured[j]->ref.series;
        const Uncertainty u = combine(vs, [&](int a, int b) {
          return change(vr[static_cast<std::size_t>(a)][j].series, b < 0 ? base : vr[static_cast<std::size_t>(b)][j].series, g);
        });
        out.uncertainty.push_back({measured[j]->m.name, g.goal, u});
        const std::string key = measured[j]->m.kind + "|" + g.goal;
        if (by_goal_kind.find(key) == by_goal_kind.end()) {
          by_goal_kind[key] = u;
          from[key] = measured[j]->m.name;
        }
      }
    if (out.has_maps) {
      // One cell of each map: its measure under every variant, relative.
      const Manoeuvre hold = hold_manoeuvre(150.0, 1.5, 90.0, 0.3);
      const std::vector<Manoeuvre> cell = shift_cell_manoeuvres(100.0, 1.5);
      const Manoeuvre onset = onset_manoeuvre(120.0);
      std::vector<Manoeuvre> maps_ms{hold, onset};
      maps_ms.insert(maps_ms.end(), cell.begin(), cell.end());
      const std::vector<ReferenceRun> base = reference_manoeuvres(maps_ms, c, cache_dir, progress);
      next_call();
      const auto measures = [&](const std::vector<ReferenceRun>& r) {
        const std::vector<ReferenceRun> shift(r.begin() + 2, r.end());
        return std::vector<double>{reference_hold_clamp1_N(hold, r[0].series), onset_clamp2_N(r[1].series),
                                   shift_slope(cell, shift)};
      };
      const std::vector<double> m0 = measures(base);
      std::vector<std::vector<double>> mv;  // each variant's measures
      for (const Variant& v : vs) {
        const std::vector<ReferenceRun> r = reference_manoeuvres(maps_ms, v.c, cache_dir, progress);
        next_call();
        for (const auto& x : r) out.reference_cpu_s += x.cpu_s;
        mv.push_back(measures(r));
      }
      const char* goals[] = {"thrust-ratio cell", "gross-slip onset clamping", "shift-rate slope"};
      const char* where[] = {"ratio 1.5, 90 N m", "120 N m", "100 rad/s, ratio 1.5"};
      for (std::size_t q = 0; q < 3; ++q) {
        const Uncertainty u = combine(vs, [&](int a, int b) {
          const double x = mv[static_cast<std::size_t>(a)][q], y = b < 0 ? m0[q] : mv[static_cast<std::size_t>(b)][q];
          return std::fabs(x - y) / std::fabs(m0[q]);
        });
        out.uncertainty.push_back({where[q], goals[q], u});
        by_goal_kind[std::string("map|") + goals[q]] = u;
        from[std::string("map|") + goals[q]] = where[q];
      }
    }
  }
  // The goal table: every run's quantities, then the maps' cells.
  for (const auto& k : out.runs)
    for (const GoalQuantity& g : kRunGoals) {
      GoalRow r;
      r.goal = g.goal;
      r.where = k.m.name;
      r.held_out = k.held_out;
      r.error = goal_value(k.cmp, g);
      r.limit = g.limit;
      const std::string key = k.m.kind + "|" + g.goal;
      // A run's own uncertainty where it was measured, else its kind's.
      for (const auto& mu : out.uncertainty)
        if (mu.where == k.m.name && mu.goal == g.goal) {
          r.has_u = true;
          r.u = mu.u;
          r.u_from = mu.where;
        }
      if (!r.has_u && by_goal_kind.count(key) != 0) {
        r.has_u = true;
        r.u = by_goal_kind[key];
        r.u_from = from[key];
      }
      out.goals.push_back(r);
    }
  if (out.has_maps) {
    const auto map_row = [&](const char* goal, const std::string& where, double error, double limit) {
      GoalRow r;
      r.goal = goal;
      r.where = where;
      r.error = error;
      r.limit = limit;
      const std::string key = std::string("map|") + goal;
      if (by_goal_kind.count(key) != 0) {
        r.has_u = true;
        r.u = by_goal_kind[key];
        r.u_from = from[key];
      }
      out.goals.push_back(r);
    };
    char where[96];
    for (const auto& cell : out.maps.thrust) {
      std::snprintf(where, sizeof where, "ratio %g, %g N m", cell.ratio, cell.torque_Nm);
      map_row("thrust-ratio cell", where, cell.error(), GoalLimits::thrust);
    }
    for (const auto& cell : out.maps.shift) {
      std::snprintf(where, sizeof where, "%g rad/s, ratio %g", cell.omega1_rad_s, cell.ratio);
      map_row("shift-rate slope", where, cell.error(), GoalLimits::shift);
    }
    for (const auto& p : out.maps.onset) {
      std::snprintf(where, sizeof where, "%g N m", p.torque_Nm);
      map_row("gross-slip onset clamping", where, p.error(), GoalLimits::onset);
    }
  }
  return out;
}

}  // namespace cvt::validation
