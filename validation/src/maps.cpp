// The maps of a shifting CVT on the reference and the plant (docs/validation.md#maps).
#include "cvtplant/validation/maps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/validation/compare.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/suite.hpp"

namespace cvt::validation {

namespace {

using cvt::mbd::TimeProfile;

constexpr double kMapOmega1_rad_s = 150.0;
constexpr double kMapRatios[] = {0.95, 1.2, 1.5, 2.0, 2.5};
constexpr double kMapTorques_Nm[] = {0.0, 40.0, 90.0, 150.0};
constexpr double kShiftOmega1_rad_s[] = {100.0, 200.0};
constexpr double kShiftRatios[] = {1.0, 1.5, 2.2};
constexpr double kShiftTorque_Nm = 60.0;
constexpr double kShiftDeltas[] = {-0.1, -0.05, 0.0, 0.05, 0.1};
constexpr double kShiftFrom_s = 0.01, kShiftTo_s = 0.05;
constexpr double kTractionRatio = 1.5;
constexpr double kTractionClamps_N[] = {12500.0, 20000.0, 30000.0};
constexpr double kTractionLevels[] = {0.1, 0.3, 0.5, 0.7, 0.85, 1.0, 1.15};  // of the capacity
constexpr double kTractionStep_s = 0.04;
constexpr double kOnsetTorques_Nm[] = {40.0, 80.0, 120.0, 150.0};

const cvt::mbd::MbdParams& set() {
  static const cvt::mbd::MbdParams p = cvt::mbd::production_set();
  return p;
}

double r1_of(double ratio) { return driver_radius_for_ratio(set().r1_m, set().r2_m, set().center_distance_m, ratio); }

// T cos(beta0) / (2 mu0 F r1): the torque over the clamping's capacity.
double torque_ratio(double torque, double clamp, double r1) {
  return torque * std::cos(set().beta0_rad) / (2.0 * set().friction.mu0 * clamp * r1);
}

std::string tag(const char* what, double a, double b, double c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s-%g-%g-%g", what, a, b, c);
  return buf;
}

Manoeuvre shift_manoeuvre(double omega1, double ratio, double delta) {
  Manoeuvre m = clamp_step_manoeuvre(controller_point(omega1, ratio, kShiftTorque_Nm), delta, 0.0, kShiftTo_s);
  m.name = tag("rate", omega1, ratio, delta);
  m.kind = "shift-rate";
  if (delta == 0.0) m.clamp1_factor = TimeProfile::constant(1.0);
  return m;
}

double capacity_torque(double clamp, double r1) { return 2.0 * set().friction.mu0 * clamp * r1 / std::cos(set().beta0_rad); }

Manoeuvre traction_manoeuvre(double clamp2) {
  const double r1 = r1_of(kTractionRatio);
  const double t_max = capacity_torque(clamp2, r1);
  Manoeuvre m;
  m.name = tag("traction", kMapOmega1_rad_s, kTractionRatio, clamp2);
  m.kind = "traction";
  m.start.omega1_rad_s = kMapOmega1_rad_s;
  m.start.ratio = kTractionRatio;
  m.start.tau_in_Nm = kTractionLevels[0] * t_max;
  m.start.clamp2_N = clamp2;
  // A staircase of input torque, each step 40 ms (5 ms ramps), the load
  // raised with it so the speeds hold.
  double t = 0;
  for (const double level : kTractionLevels) {
    const double torque = level * t_max;
    if (t == 0) {
      m.tau_in_Nm.points.push_back({0.0, torque});
      m.tau_load_Nm.points.push_back({0.0, 0.0});
    } else {
      m.tau_in_Nm.points.push_back({t + 0.005, torque});
      m.tau_load_Nm.points.push_back({t + 0.005, (torque - m.start.tau_in_Nm) * kTractionRatio});
    }
    t += kTractionStep_s;
    m.tau_in_Nm.points.push_back({t, torque});
    m.tau_load_Nm.points.push_back({t, (torque - m.start.tau_in_Nm) * kTractionRatio});
  }
  m.t_end_s = t;
  m.stop_at_gross_slip = true;
  return m;
}

}  // namespace

Manoeuvre onset_manoeuvre(double torque) {
  Manoeuvre m = hold_manoeuvre(kMapOmega1_rad_s, kTractionRatio, torque, 0.5);
  m.name = tag("onset", kMapOmega1_rad_s, kTractionRatio, torque);
  m.kind = "onset";
  m.clamp1_factor = TimeProfile{{{0.05, 1.0}, {0.45, 0.25}}};
  m.clamp2_factor = m.clamp1_factor;
  m.stop_at_gross_slip = true;
  return m;
}

namespace {

double mean_over(const Series& s, const std::vector<double>& y, double from_s, double to_s) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.t_s[i] >= from_s - 1e-9 && s.t_s[i] <= to_s + 1e-9 && std::isfinite(y[i])) {
      sum += y[i];
      ++n;
    }
  return n > 0 ? sum / n : std::nan("");
}

// Line through (x, y) by least squares: slope, the x where it is 0, R^2.
void fit_line(const std::vector<double>& x, const std::vector<double>& y, double& slope, double& x0, double& r2) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
    syy += y[i] * y[i];
  }
  const double vxx = sxx - sx * sx / n, vxy = sxy - sx * sy / n, vyy = syy - sy * sy / n;
  slope = vxy / vxx;
  const double b = (sy - slope * sx) / n;
  x0 = -b / slope;
  r2 = vyy > 0 ? vxy * vxy / (vxx * vyy) : 1.0;
}

double first_gross_slip_s(const Series& s) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (std::fabs(s.wrap_slip_m_s[i]) > kGrossSlip_m_s) return s.t_s[i];
  return -1;
}

double value_at(const Series& s, const std::vector<double>& y, double t) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.t_s[i] >= t - 1e-9) return y[i];
  return std::nan("");
}

}  // namespace

std::vector<Manoeuvre> shift_cell_manoeuvres(double omega1_rad_s, double ratio) {
  std::vector<Manoeuvre> out;
  for (const double delta : kShiftDeltas) out.push_back(shift_manoeuvre(omega1_rad_s, ratio, delta));
  return out;
}

double shift_slope(const std::vector<Manoeuvre>& cell, const std::vector<ReferenceRun>& runs) {
  std::vector<double> d, rate;
  for (std::size_t i = 0; i < cell.size() && i < runs.size(); ++i) {
    const Series& r = runs[i].series;
    d.push_back(std::log(cell[i].clamp1_factor.at(kShiftTo_s)));
    rate.push_back(slope_over(r.t_s, r.ratio_geom, kShiftFrom_s, kShiftTo_s));
  }
  double slope = 0, x0 = 0, r2 = 0;
  fit_line(d, rate, slope, x0, r2);
  return slope;
}

double onset_clamp2_N(const Series& s) {
  const double t = first_gross_slip_s(s);
  return t >= 0 ? value_at(s, s.clamp2_N, t) : std::nan("");
}

double slope_over(const std::vector<double>& t, const std::vector<double>& y, double from_s, double to_s) {
  std::vector<double> x, v;
  for (std::size_t i = 0; i < t.size() && i < y.size(); ++i)
    if (t[i] >= from_s - 1e-9 && t[i] <= to_s + 1e-9 && std::isfinite(y[i])) {
      x.push_back(t[i]);
      v.push_back(y[i]);
    }
  if (x.size() < 2) return std::nan("");
  double slope = 0, x0 = 0, r2 = 0;
  fit_line(x, v, slope, x0, r2);
  return slope;
}

std::vector<Manoeuvre> map_manoeuvres() {
  std::vector<Manoeuvre> out;
  for (const double ratio : kMapRatios)
    for (const double torque : kMapTorques_Nm) out.push_back(hold_manoeuvre(kMapOmega1_rad_s, ratio, torque, 0.3));
  for (const double omega1 : kShiftOmega1_rad_s)
    for (const double ratio : kShiftRatios)
      for (const double delta : kShiftDeltas) out.push_back(shift_manoeuvre(omega1, ratio, delta));
  for (const double clamp : kTractionClamps_N) out.push_back(traction_manoeuvre(clamp));
  for (const double torque : kOnsetTorques_Nm) out.push_back(onset_manoeuvre(torque));
  return out;
}

Maps make_maps(const cvt::Scene& plant, const ReferenceConfig& c, const std::string& cache_dir,
               const cvt::mbd::ProgressSink& on_progress) {
  const std::vector<Manoeuvre> ms = map_manoeuvres();
  const std::vector<ReferenceRun> refs = reference_manoeuvres(ms, c, cache_dir, on_progress);
  Maps out;
  std::map<std::string, std::size_t> at;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    at[ms[i].name] = i;
    if (!refs[i].from_cache) out.reference_cpu_s += refs[i].cpu_s;  // a hit's is NaN: none spent
    ++out.reference_runs;
    out.from_cache += refs[i].from_cache ? 1 : 0;
    if (!refs[i].cache_problem.empty()) out.cache_problems.push_back(refs[i].cache_problem);
  }
  // The plant's run of a manoeuvre, with the reference's inputs.
  const auto plant_of = [&](std::size_t i, PlantHold* hold) {
    return plant_manoeuvre(ms[i], plant, &refs[i].series, hold);
  };
  for (const double ratio : kMapRatios)
    for (const double torque : kMapTorques_Nm) {
      const std::size_t i = at.at(hold_manoeuvre(kMapOmega1_rad_s, ratio, torque, 0.3).name);
      const Series& r = refs[i].series;
      PlantHold h;
      const Series p = plant_of(i, &h);
      ThrustCell cell;
      cell.ratio = ratio;
      cell.torque_Nm = torque;
      cell.clamp2_N = ms[i].start.clamp2_N;
      cell.torque_ratio = torque_ratio(torque, cell.clamp2_N, r1_of(ratio));
      cell.kappa_ref = reference_hold_clamp1_N(ms[i], r) / cell.clamp2_N;
      cell.kappa_plant = h.clamp1_N / cell.clamp2_N;
      cell.ratio_ref = r.ratio_geom[0];
      cell.ratio_plant = p.ratio_geom[0];
      cell.drift_ref_per_s = slope_over(r.t_s, r.ratio_geom, 0.0, r.t_s.back());
      out.thrust.push_back(cell);
    }
  for (const double omega1 : kShiftOmega1_rad_s)
    for (const double ratio : kShiftRatios) {
      ShiftCell cell;
      cell.omega1_rad_s = omega1;
      cell.ratio = ratio;
      cell.torque_Nm = kShiftTorque_Nm;
      for (const double delta : kShiftDeltas) {
        const std::size_t i = at.at(shift_manoeuvre(omega1, ratio, delta).name);
        cell.clamp2_N = ms[i].start.clamp2_N;
        const Series& r = refs[i].series;
        const Series p = plant_of(i, nullptr);
        cell.delta.push_back(delta);
        cell.rate_ref.push_back(slope_over(r.t_s, r.ratio_geom, kShiftFrom_s, kShiftTo_s));
        cell.rate_plant.push_back(slope_over(p.t_s, p.ratio_geom, kShiftFrom_s, kShiftTo_s));
      }
      fit_line(cell.delta, cell.rate_ref, cell.slope_ref, cell.delta0_ref, cell.r2_ref);
      fit_line(cell.delta, cell.rate_plant, cell.slope_plant, cell.delta0_plant, cell.r2_plant);
      out.shift.push_back(cell);
    }
  for (const double clamp : kTractionClamps_N) {
    const std::size_t i = at.at(traction_manoeuvre(clamp).name);
    const Series& r = refs[i].series;
    const Series p = plant_of(i, nullptr);
    const double r1 = r1_of(kTractionRatio);
    const double t_max = capacity_torque(clamp, r1);
    const double slip_r = first_gross_slip_s(r), slip_p = first_gross_slip_s(p);
    double t = 0;
    for (const double level : kTractionLevels) {
      t += kTractionStep_s;
      TractionPoint tp;
      tp.clamp2_N = clamp;
      tp.torque_cmd_Nm = level * t_max;
      tp.torque_ratio = level;
      const auto point = [&](const Series& s, double slip_s, double& torque, double& slip) {
        const bool sliding = slip_s >= 0 && slip_s <= t + 1e-9;
        if (sliding || s.t_s.back() < t - 1e-9) {
          torque = slip = std::nan("");
          return;
        }
        // Relative slip (v1 - v_chain) / v1 with v1 = omega1 r1 on the running radius.
        std::vector<double> rel(s.size());
        for (std::size_t k = 0; k < s.size(); ++k)
          rel[k] = s.slip1_m_s[k] / (s.omega1_rad_s[k] * r1_of(s.ratio_geom[k]));
        torque = mean_over(s, s.torque_driver_Nm, t - 0.02, t);
        slip = mean_over(s, rel, t - 0.02, t);
      };
      point(r, slip_r, tp.torque_ref_Nm, tp.slip_ref);
      point(p, slip_p, tp.torque_plant_Nm, tp.slip_plant);
      out.traction.push_back(tp);
    }
  }
  for (const double torque : kOnsetTorques_Nm) {
    const std::size_t i = at.at(onset_manoeuvre(torque).name);
    const Series& r = refs[i].series;
    const Series p = plant_of(i, nullptr);
    OnsetPoint op;
    op.torque_Nm = torque;
    op.clamp_ref_N = onset_clamp2_N(r);
    op.clamp_plant_N = onset_clamp2_N(p);
    op.clamp_closed_N = capacity_clamp_N(torque, r1_of(r.ratio_geom[0]), set().friction.mu0, set().beta0_rad, 1.0);
    out.onset.push_back(op);
  }
  return out;
}

namespace {

// One map's table dir/name: the header line, then write_row(file, row) for each row.
template <class Rows, class WriteRow>
void write_csv(const std::string& dir, const char* name, const char* header, const Rows& rows, WriteRow write_row,
               std::vector<std::string>& paths) {
  const std::string path = dir + "/" + name;
  auto f = cvt::analysis::open_text_file(path);
  f << header;
  for (const auto& row : rows) write_row(f, row);
  paths.push_back(path);
}

void write_csvs(const Maps& m, const std::string& dir, std::vector<std::string>& paths) {
  write_csv(dir, "thrust-ratio.csv",
            "ratio,torque_Nm,clamp2_N,torque_ratio,kappa_ref,kappa_plant,error,ratio_ref,ratio_plant,drift_ref_per_s\n",
            m.thrust, [](auto& f, const auto& c) {
              f << c.ratio << ',' << c.torque_Nm << ',' << c.clamp2_N << ',' << c.torque_ratio << ',' << c.kappa_ref
                << ',' << c.kappa_plant << ',' << c.error() << ',' << c.ratio_ref << ',' << c.ratio_plant << ','
                << c.drift_ref_per_s << '\n';
            }, paths);
  write_csv(dir, "shift-rate.csv",
            "omega1_rad_s,ratio,torque_Nm,clamp2_N,delta_ln_F1_F2,rate_ref_per_s,rate_plant_per_s,slope_ref,slope_plant,"
            "cmm_coefficient_ref,cmm_coefficient_plant,r2_ref,r2_plant\n",
            m.shift, [](auto& f, const auto& c) {
              for (std::size_t i = 0; i < c.delta.size(); ++i)
                f << c.omega1_rad_s << ',' << c.ratio << ',' << c.torque_Nm << ',' << c.clamp2_N << ',' << c.delta[i]
                  << ',' << c.rate_ref[i] << ',' << c.rate_plant[i] << ',' << c.slope_ref << ',' << c.slope_plant << ','
                  << c.slope_ref / c.omega1_rad_s << ',' << c.slope_plant / c.omega1_rad_s << ',' << c.r2_ref << ','
                  << c.r2_plant << '\n';
            }, paths);
  write_csv(dir, "traction.csv", "clamp2_N,torque_cmd_Nm,torque_ratio,torque_ref_Nm,slip_ref,torque_plant_Nm,slip_plant\n",
            m.traction, [](auto& f, const auto& p) {
              f << p.clamp2_N << ',' << p.torque_cmd_Nm << ',' << p.torque_ratio << ',' << p.torque_ref_Nm << ','
                << p.slip_ref << ',' << p.torque_plant_Nm << ',' << p.slip_plant << '\n';
            }, paths);
  write_csv(dir, "gross-slip-onset.csv", "torque_Nm,clamp_ref_N,clamp_plant_N,clamp_closed_form_N,error\n", m.onset,
            [](auto& f, const auto& o) {
              f << o.torque_Nm << ',' << o.clamp_ref_N << ',' << o.clamp_plant_N << ',' << o.clamp_closed_N << ','
                << o.error() << '\n';
            }, paths);
}

// One gnuplot script per map next to its CSV.
void draw(const std::string& dir, const std::string& name, const std::string& body, std::vector<std::string>& paths) {
  const std::string png = dir + "/" + name + ".png";
  auto s = cvt::analysis::open_text_file(dir + "/" + name + ".gp");
  s << cvt::analysis::png_terminal(1000, 700) << "set output '" << png << "'\n"
    << "set datafile separator ','\nset datafile missing 'nan'\nset grid\nset key outside right\n"
    << body;
  s.close();
  cvt::analysis::run_gnuplot(dir + "/" + name + ".gp");
  paths.push_back(png);
}

// A gnuplot plot command grown one group of curves at a time: `add` formats
// a group with printf, its first %s the separator from the group before.
struct PlotCommand {
  std::string text;  // the title, labels and "plot "; then the groups
  int groups = 0;
  int colour() const { return groups + 1; }  // the next group's line colour
  template <class... A>
  void add(const char* f, A... a) {
    const char* sep = groups++ > 0 ? ", " : "";
    std::string b(static_cast<std::size_t>(std::snprintf(nullptr, 0, f, sep, a...)), '\0');
    std::snprintf(b.data(), b.size() + 1, f, sep, a...);
    text += b;
  }
};

void write_figures(const Maps&, const std::string& dir, std::vector<std::string>& paths) {
  PlotCommand thrust{"set title 'Thrust-ratio map: F1/F2 that holds the ratio, reference (points) and plant "
                     "(lines)'\nset xlabel 'geometric ratio r2/r1 [-]'\nset ylabel 'kappa = F1/F2 [-]'\nplot "};
  for (const double torque : kMapTorques_Nm)
    thrust.add("%s'%s/thrust-ratio.csv' skip 1 using ($2==%g?$1:1/0):5 with points pt 7 lc %d title 'reference %g N m', "
               "'%s/thrust-ratio.csv' skip 1 using ($2==%g?$1:1/0):6 with lines lw 2 lc %d title 'plant %g N m'",
               dir.c_str(), torque, thrust.colour(), torque, dir.c_str(), torque, thrust.colour(), torque);
  draw(dir, "thrust-ratio", thrust.text + "\n", paths);
  PlotCommand shift{"set title 'Shift rate after a step of ln(F1/F2) from the hold: reference (points), plant (lines)'\n"
                    "set xlabel 'delta ln(F1/F2) [-]'\nset ylabel 'd(r2/r1)/dt per primary speed [1/rad]'\nplot "};
  for (const double omega1 : kShiftOmega1_rad_s)
    for (const double ratio : kShiftRatios)
      shift.add("%s'%s/shift-rate.csv' skip 1 using (($1==%g&&$2==%g)?$5:1/0):($6/$1) with linespoints dt 3 pt 7 lc %d "
                "title 'ref. %g rad/s, %g', '%s/shift-rate.csv' skip 1 using (($1==%g&&$2==%g)?$5:1/0):($7/$1) with "
                "lines lw 2 lc %d title 'plant %g rad/s, %g'",
                dir.c_str(), omega1, ratio, shift.colour(), omega1, ratio, dir.c_str(), omega1, ratio, shift.colour(),
                omega1, ratio);
  draw(dir, "shift-rate", shift.text + "\n", paths);
  PlotCommand traction{"set title 'Traction: transmitted torque against the driver slip, reference (points), plant (lines)'\n"
                       "set xlabel 'driver slip (v1 - v_chain)/v1 [%]'\nset ylabel 'torque on the driver [N m]'\nplot "};
  for (const double clamp : kTractionClamps_N)
    traction.add("%s'%s/traction.csv' skip 1 using ($1==%g?100*$5:1/0):4 with linespoints dt 3 pt 7 lc %d title 'ref. %g kN', "
                 "'%s/traction.csv' skip 1 using ($1==%g?100*$7:1/0):6 with linespoints lw 2 pt 4 lc %d title 'plant %g kN'",
                 dir.c_str(), clamp, traction.colour(), clamp / 1000, dir.c_str(), clamp, traction.colour(), clamp / 1000);
  draw(dir, "traction", traction.text + "\n", paths);
  const std::string onset = "set title 'Clamping at the onset of gross slip'\nset xlabel 'input torque [N m]'\n"
         "set ylabel 'driven clamping at onset [kN]'\nplot '" + dir +
         "/gross-slip-onset.csv' skip 1 using 1:($2/1000) with linespoints pt 7 lw 1 title 'reference', '" + dir +
         "/gross-slip-onset.csv' skip 1 using 1:($3/1000) with linespoints pt 4 lw 2 title 'plant', '" + dir +
         "/gross-slip-onset.csv' skip 1 using 1:($4/1000) with lines dt 2 title 'closed form, mu0'\n";
  draw(dir, "gross-slip-onset", onset, paths);
}

}  // namespace

std::vector<std::string> write_maps(const Maps& m, const std::string& dir, bool figures) {
  std::vector<std::string> paths;
  write_csvs(m, dir, paths);
  if (figures) write_figures(m, dir, paths);
  return paths;
}

}  // namespace cvt::validation
