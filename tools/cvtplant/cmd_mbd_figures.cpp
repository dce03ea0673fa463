// `cvtplant mbd figures`: the seed's Figs. 13 and 14 (pulley speeds and driver
// axial force, cases 1 and 2) and a picture of the chain on the pulleys, as
// PNG through gnuplot (docs/cli.md#mbd-figures, docs/mbd.md#what-the-model-shows).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cmd_mbd.hpp"
#include "commands.hpp"
#include "io_util.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/mbd/geometry.hpp"

namespace cvtcli::mbdcli {

namespace {

using cvt::analysis::open_text_file;
using cvt::analysis::png_terminal;
using cvt::analysis::run_gnuplot;

// Columns of the per-sample CSV used by the figures (write_csv_header order).
constexpr int kColT = 1, kColOmega1 = 2, kColOmega2 = 3, kColFax1 = 5;

// Seed Fig. 13: pulley speeds, one panel per case (both panels in rad/s).
std::string fig13(const std::string& d, const ModelOptions& m) {
  const std::string png = d + "/fig13_pulley_speeds.png";
  auto s = open_text_file(d + "/fig13.gp");
  s << png_terminal(1000, 700) << "set output '" << png << "'\nset datafile separator ','\nset grid\n"
    << "set multiplot layout 2,1 title 'Pulley speeds, tau_in = " << m.tau_in << " N m, tau_load = "
    << m.tau_load << " N m (seed Fig. 13), multibody model, " << method_label(m) << "'\n"
    << "set xlabel 't [s]'\nset ylabel 'pulley speed [rad/s]'\nset key top left\n";
  for (int c = 1; c <= 2; ++c) {
    s << "set title '(" << (c == 1 ? 'a' : 'b') << ") seed " << case_label(c) << "'\n"
      << "plot '" << d << "/case" << c << ".csv' skip 1 using " << kColT << ":" << kColOmega1
      << " with lines lw 2 lc rgb '#1f4e9c' title 'driver omega1', '' skip 1 using " << kColT << ":" << kColOmega2
      << " with lines lw 2 dt 2 lc rgb '#c0392b' title 'driven omega2'\n";
  }
  s << "unset multiplot\n";
  s.close();
  run_gnuplot(d + "/fig13.gp");
  return png;
}

// Seed Fig. 14: driver axial force, one panel per case (both in kN).
std::string fig14(const std::string& d, const ModelOptions& m) {
  const std::string png = d + "/fig14_driver_axial_force.png";
  auto s = open_text_file(d + "/fig14.gp");
  s << png_terminal(1000, 700) << "set output '" << png << "'\nset datafile separator ','\nset grid\n"
    << "set multiplot layout 2,1 title 'Driver pulley axial force (seed Fig. 14), " << m.sheaves
    << " sheaves, multibody model, " << method_label(m) << "'\n"
    << "set xlabel 't [s]'\nset ylabel 'axial force F_ax1 [kN]'\nset key top right\n";
  for (int c = 1; c <= 2; ++c) {
    s << "set title '(" << (c == 1 ? 'a' : 'b') << ") seed " << case_label(c) << "'\n"
      << "plot '" << d << "/case" << c << ".csv' skip 1 using " << kColT << ":($" << kColFax1
      << "/1000) with lines lw 1 lc rgb '#1f4e9c' title 'F_ax1 (sum of bolt forces, Eq. 5)'\n";
  }
  s << "unset multiplot\n";
  s.close();
  run_gnuplot(d + "/fig14.gp");
  return png;
}

// The chain on the pulleys at one instant: links as bars from rear to front
// pin, coloured by contact state; the pitch circles for reference.
std::string chain_picture(const std::string& d, const ModelOptions& m, int c, const RunOutcome& r) {
  const std::string tag = "chain_case" + std::to_string(c);
  const std::string png = d + "/" + tag + ".png";
  {
    auto f = open_text_file(d + "/" + tag + ".dat");
    // Three data sets (index 0 free, 1 driver wrap, 2 driven wrap), each link a
    // two-point segment.
    for (int state = -1; state <= 1; ++state) {
      f << "# " << (state < 0 ? "free" : state == 0 ? "driver wrap" : "driven wrap") << "\n";
      bool any = false;
      for (const auto& l : r.picture) {
        if (l.pulley != state) continue;
        any = true;
        f << l.rear_x_m << ' ' << l.rear_y_m << ' ' << l.bolt_force_N << '\n'
          << l.front_x_m << ' ' << l.front_y_m << ' ' << l.bolt_force_N << "\n\n";
      }
      if (!any) f << "nan nan nan\n\n";
      f << "\n";
    }
    // Data set 3: the joints (force elements), front pin to the next rear pin.
    f << "# joints\n";
    for (std::size_t i = 0; i < r.picture.size(); ++i) {
      const auto& a = r.picture[i];
      const auto& b = r.picture[(i + 1) % r.picture.size()];
      f << a.front_x_m << ' ' << a.front_y_m << " 0\n" << b.rear_x_m << ' ' << b.rear_y_m << " 0\n\n";
    }
  }
  const cvt::mbd::MbdParams p = params_for(m, c);
  const cvt::mbd::DriveGeometry g(p.r1_m, p.r2_m, p.center_distance_m);
  // Frame: both pulleys and every link, 2 cm around.
  double x_lo = -g.r_m[0], x_hi = g.center_distance_m + g.r_m[1], y_lo = -g.r_m[1], y_hi = g.r_m[1];
  for (const auto& l : r.picture)
    for (const double x : {l.rear_x_m, l.front_x_m}) {
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
    }
  for (const auto& l : r.picture)
    for (const double y : {l.rear_y_m, l.front_y_m}) {
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
    }
  x_lo -= 0.02;
  x_hi += 0.02;
  y_lo -= 0.02;
  y_hi += 0.02;
  auto s = open_text_file(d + "/" + tag + ".gp");
  s << png_terminal(1300, 560) << "set output '" << png << "'\n"
    << "set title \"Chain on the pulleys at t = " << num(r.picture_t_s) << " s, seed " << case_label(c) << ", "
    << m.links << " links, " << m.sheave_mode() << " sheaves, " << method_label(m)
    << "\\nlinks drawn from rear to front pin (dot: the bolt at the front pin), thin lines: the joints\"\n"
    << "set size ratio -1\nset grid\nset xlabel 'x [m]'\nset ylabel 'y [m]'\nset key outside right\n"
    << "set xrange [" << x_lo << ":" << x_hi << "]\nset yrange [" << y_lo << ":" << y_hi << "]\n"
    << "set parametric\nset trange [0:2*pi]\n"
    << "plot " << g.r_m[0] << "*cos(t), " << g.r_m[0] << "*sin(t) lc rgb '#999999' dt 3 title 'pitch circles', "
    << g.center_distance_m << "+" << g.r_m[1] << "*cos(t), " << g.r_m[1]
    << "*sin(t) lc rgb '#999999' dt 3 notitle, "
    << "'" << d << "/" << tag << ".dat' index 0 using 1:2 with lines lw 3 lc rgb '#555555' title 'free', "
    << "'' index 0 every ::1::1 using 1:2 with points pt 7 ps 0.7 lc rgb '#555555' notitle, "
    << "'' index 1 using 1:2 with lines lw 3 lc rgb '#1f4e9c' title 'in the driver wrap', "
    << "'' index 1 every ::1::1 using 1:2 with points pt 7 ps 0.7 lc rgb '#1f4e9c' notitle, "
    << "'' index 2 using 1:2 with lines lw 3 lc rgb '#c0392b' title 'in the driven wrap', "
    << "'' index 2 every ::1::1 using 1:2 with points pt 7 ps 0.7 lc rgb '#c0392b' notitle, "
    << "'' index 3 using 1:2 with lines lw 1 lc rgb '#e69f00' title 'joints (stretch)', "
    << "'+' using (0):(0) every ::0::0 with points pt 1 ps 2 lc rgb 'black' title 'pulley centres', "
    << "'+' using (" << g.center_distance_m << "):(0) every ::0::0 with points pt 1 ps 2 lc rgb 'black' notitle\n";
  s.close();
  run_gnuplot(d + "/" + tag + ".gp");
  return png;
}

}  // namespace

void add_figure_options(CLI::App* sub, FigureOptions& o) {
  sub->add_option("--out-dir", o.out_dir, "Directory for the PNGs and their data (created if missing; its parent must exist)")->required();
  sub->add_option("--picture-t", o.picture_t_s, "Time of the chain picture [s] (default: the end of the run)");
  sub->add_flag("--json", o.json, "Print the files written and both runs' summaries as JSON");
  add_model_options(sub, o.model);
}

int run_figures(const FigureOptions& o) {
  if (o.model.production()) throw UsageError{"mbd figures draws the seed's Figs. 13-14: --set seed only"};
  validate(o.model);
  if (o.picture_t_s != -1 && !(o.picture_t_s >= 0 && o.picture_t_s <= o.model.t_end_s))
    throw UsageError{"--picture-t: " + num(o.picture_t_s) + " is outside [0, --t-end]"};
  try {
    cvt::analysis::ensure_dir(o.out_dir);
  } catch (const cvt::analysis::InputError& e) {
    throw UsageError{std::string("--out-dir: ") + e.what()};
  }
  const double pic_t = o.picture_t_s >= 0 ? o.picture_t_s : o.model.t_end_s;
  std::vector<std::string> pngs;
  nlohmann::json runs = nlohmann::json::array();
  RunOutcome outcome[2];
  for (int c = 1; c <= 2; ++c) {
    std::FILE* csv = open_output(o.out_dir + "/case" + std::to_string(c) + ".csv");
    outcome[c - 1] = run_case(o.model, c, csv, nullptr, 0, pic_t, "mbd figures " + case_label(c));
    close_output(csv);
    const RunOutcome& r = outcome[c - 1];
    if (r.failed) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "case %d at t = %.6g s: ", c, r.fail_t_s);
      throw RunError{buf + r.fail_quantity};
    }
    runs.push_back({{"case", c},
                    {"wall_s", r.stats.wall_s},
                    {"steps", r.stats.steps},
                    {"energy_residual_rel", r.stats.ledger_residual_max_rel},
                    {"csv", o.out_dir + "/case" + std::to_string(c) + ".csv"}});
  }
  // The runs are done: a data file or gnuplot failing now is an output that
  // could not be made (exit 1).
  try {
    pngs.push_back(fig13(o.out_dir, o.model));
    pngs.push_back(fig14(o.out_dir, o.model));
    for (int c = 1; c <= 2; ++c) pngs.push_back(chain_picture(o.out_dir, o.model, c, outcome[c - 1]));
  } catch (const std::runtime_error& e) {
    throw RunError{e.what()};
  }
  if (o.json) {
    print_json({{"subcommand", "mbd figures"}, {"png", pngs}, {"runs", runs}, {"picture_t_s", outcome[0].picture_t_s}});
  } else {
    for (const auto& p : pngs) std::printf("%s\n", p.c_str());
  }
  return 0;
}

}  // namespace cvtcli::mbdcli
