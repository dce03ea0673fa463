// What `cvtplant validate` writes per scene (docs/cli.md#validate).
#include "cvtplant/validation/report.hpp"

#include <algorithm>
#include <cmath>

#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/validation/compare.hpp"

namespace cvt::validation {

void write_overlay_csv(std::FILE* f, const Series& p, const Series& r) {
  std::fprintf(f,
               "t_s,omega1_plant,omega1_ref,omega2_plant,omega2_ref,ratio_plant,ratio_ref,F_ax1_plant_N,F_ax1_ref_N,"
               "torque_plant_Nm,torque_ref_Nm,slip1_plant_m_s,slip1_ref_m_s,wrap_slip1_plant_m_s,wrap_slip1_ref_m_s,"
               "ratio_geom_plant,ratio_geom_ref,F_ax2_plant_N,F_ax2_ref_N\n");
  auto ratio = [](double w1, double w2) { return std::fabs(w2) >= 1.0 ? w1 / w2 : NAN; };
  for (std::size_t i = 0; i < std::min(p.size(), r.size()); ++i)
    std::fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                 p.t_s[i], p.omega1_rad_s[i], r.omega1_rad_s[i], p.omega2_rad_s[i], r.omega2_rad_s[i],
                 ratio(p.omega1_rad_s[i], p.omega2_rad_s[i]), ratio(r.omega1_rad_s[i], r.omega2_rad_s[i]),
                 p.F_ax1_N[i], r.F_ax1_N[i], p.torque_driver_Nm[i], r.torque_driver_Nm[i], p.slip1_m_s[i],
                 r.slip1_m_s[i], p.wrap_slip_m_s[i], r.wrap_slip_m_s[i], p.ratio_geom[i], r.ratio_geom[i],
                 p.F_ax2_N[i], r.F_ax2_N[i]);
}

void write_overlay_png(const std::string& dir, const std::string& name, const std::string& csv,
                       const std::string& png, double compared_s, double t_end_s) {
  auto s = cvt::analysis::open_text_file(dir + "/" + name + ".gp");
  s << cvt::analysis::png_terminal(1000, 1300) << "set output '" << png << "'\n"
    << "set datafile separator ','\nset datafile missing 'nan'\nset grid\nset key outside right\n"
    << "set multiplot layout 5,1 title 'Scene " << name
    << ": real-time plant (lines) against the multibody reference (thin, grey and red)'\n"
    << "set lmargin 12\nset rmargin 26\nunset xlabel\n"
    // A fixed time axis: a short run whose ratio is undefined throughout (the
    // driven pulley below 1 rad/s) still draws an empty panel, not an error.
    << "set xrange [0:" << t_end_s << "]\n";
  // A dotted line where the comparison ends (a sheave at its end stop, or
  // the reference stopped).
  if (compared_s < t_end_s - 1e-9)
    s << "set arrow from " << compared_s << ", graph 0 to " << compared_s << ", graph 1 nohead dt 3 lc rgb '#000000'\n";
  const std::string src = "'" + csv + "' skip 1";
  s << "set ylabel 'pulley speed [rad/s]'\n"
    << "plot " << src << " using 1:3 with lines lw 1 lc rgb '#888888' title 'omega1 reference', " << src
    << " using 1:5 with lines lw 1 lc rgb '#e07b7b' title 'omega2 reference', " << src
    << " using 1:2 with lines lw 2 lc rgb '#1f4e9c' title 'omega1 plant', " << src
    << " using 1:4 with lines lw 2 dt 2 lc rgb '#c0392b' title 'omega2 plant'\n";
  // The ratio passes through infinity while a driven pulley starts: a fixed
  // range keeps the running values readable.
  s << "set ylabel 'ratio [-]'\nset yrange [0:6]\n"
    << "plot " << src << " using 1:7 with lines lw 1 lc rgb '#888888' title 'omega1/omega2 ref.', " << src
    << " using 1:17 with lines lw 1 lc rgb '#e07b7b' title 'r2/r1 ref.', " << src
    << " using 1:6 with lines lw 2 lc rgb '#1f4e9c' title 'omega1/omega2 plant', " << src
    << " using 1:16 with lines lw 2 dt 2 lc rgb '#c0392b' title 'r2/r1 plant'\n";
  s << "set autoscale y\nset ylabel 'axial force [kN]'\n"
    << "plot " << src << " using 1:($9/1000) with lines lw 1 lc rgb '#888888' title 'F_ax1 ref.', " << src
    << " using 1:($19/1000) with lines lw 1 lc rgb '#e07b7b' title 'F_ax2 ref.', " << src
    << " using 1:($8/1000) with lines lw 2 lc rgb '#1f4e9c' title 'F_ax1 plant', " << src
    << " using 1:($18/1000) with lines lw 2 dt 2 lc rgb '#c0392b' title 'F_ax2 plant'\n";
  s << "set ylabel 'torque on the driver [N m]'\n"
    << "plot " << src << " using 1:11 with lines lw 1 lc rgb '#888888' title 'reference', " << src
    << " using 1:10 with lines lw 2 lc rgb '#1f4e9c' title 'plant'\n";
  // The mean over the wrap, and (dashed) the slip the whole wrap shares,
  // whose crossing of the threshold is the time to gross slip.
  s << "set xlabel 't [s]'\nset ylabel 'driver slip speed [m/s]'\n"
    << "plot " << src << " using 1:13 with lines lw 1 lc rgb '#888888' title 'ref. mean', " << src
    << " using 1:15 with lines lw 1 dt 2 lc rgb '#e07b7b' title 'ref. whole wrap', " << src
    << " using 1:12 with lines lw 2 lc rgb '#1f4e9c' title 'plant mean', " << src
    << " using 1:14 with lines lw 2 dt 2 lc rgb '#c0392b' title 'plant whole wrap', " << kGrossSlip_m_s
    << " with lines lw 1 dt 3 lc rgb '#000000' title 'gross slip'\n"
    << "unset multiplot\n";
  s.close();
  cvt::analysis::run_gnuplot(dir + "/" + name + ".gp");
}

}  // namespace cvt::validation
