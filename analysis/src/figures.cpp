#include "cvtplant/analysis/figures.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/embedding.hpp"
#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/rqa.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

void ensure_dir(const std::string& d) {
  struct stat st {};
  if (stat(d.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) throw InputError("'" + d + "' exists and is not a directory");
    return;
  }
  if (mkdir(d.c_str(), 0755) != 0) throw InputError("cannot create directory '" + d + "'");
}

std::ofstream open_text_file(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError("cannot write '" + path + "'");
  f.precision(10);
  return f;
}

std::string png_terminal(int width_px, int height_px) {
  // noenhanced: names like belt_speed_m_s are printed literally, not as subscripts.
  return "set terminal pngcairo size " + std::to_string(width_px) + "," + std::to_string(height_px) +
         " font 'DejaVu Sans,11' noenhanced\n";
}

namespace {

const std::string kTerm = png_terminal(900, 600) + "set grid\n";

std::string fmt_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

void run_gnuplot(const std::string& script_path) {
  const std::string cmd = "gnuplot '" + script_path + "' 2>&1";
  std::FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot start gnuplot");
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int rc = pclose(p);
  if (rc != 0) throw std::runtime_error("gnuplot failed on " + script_path + ": " + out);
}

std::vector<std::string> series_figures(const std::vector<double>& x_raw, double dt, const std::string& label,
                                        const std::string& out_dir, int tau, int m) {
  ensure_dir(out_dir);
  validate_series(x_raw, 200, "figures");
  const std::vector<double> x = zscore(x_raw);
  const int w = default_theiler(x);
  const AmiResult ami = average_mutual_information(x, std::min<int>(static_cast<int>(x.size() / 10), 300));
  if (tau <= 0) tau = ami.tau;
  FnnOptions fo;
  fo.tau = tau;
  fo.theiler = w;
  const FnnResult fnn = false_nearest_neighbours(x, fo);
  CaoOptions co;
  co.tau = tau;
  co.theiler = w;
  const CaoResult cr = cao(x, co);
  if (m <= 0) m = std::max(2, fnn.dimension);
  LleOptions lo;
  lo.m = m;
  lo.tau = tau;
  lo.theiler = w;
  lo.dt = dt;
  const LleResult lle = lle_rosenstein(x, lo);
  const std::string D = out_dir + "/";
  {
    auto f = open_text_file(D + "series.dat");
    for (std::size_t i = 0; i < x_raw.size(); ++i) f << i * dt << ' ' << x_raw[i] << ' ' << x[i] << '\n';
    auto g = open_text_file(D + "delay.dat");
    for (std::size_t i = 0; i + 2 * tau < x.size(); ++i) g << x[i] << ' ' << x[i + tau] << ' ' << x[i + 2 * tau] << '\n';
    auto a = open_text_file(D + "ami.dat");
    for (std::size_t k = 0; k < ami.ami.size(); ++k) a << k << ' ' << ami.ami[k] << ' ' << ami.acf[k] << '\n';
    auto n = open_text_file(D + "fnn.dat");
    for (std::size_t k = 0; k < fnn.m.size(); ++k)
      n << fnn.m[k] << ' ' << fnn.fraction[k] << ' ' << fnn.fraction_rtol[k] << ' ' << fnn.fraction_atol[k] << ' '
        << cr.e1[k] << ' ' << cr.e2[k] << '\n';
    auto d = open_text_file(D + "divergence.dat");
    for (std::size_t k = 0; k < lle.divergence.size(); ++k) d << k * dt << ' ' << lle.divergence[k] << '\n';
  }
  const double t0 = lle.fit.k_begin * dt, t1 = lle.fit.k_end * dt;
  const double y0 = lle.divergence[lle.fit.k_begin];
  {
    auto s = open_text_file(D + "series.gp");
    s << kTerm;
    s << "set output '" << D << "time_history.png'\nset title '" << label << ": time history'\nset xlabel 'time t [s]'\n"
      << "plot '" << D << "series.dat' u 1:2 w l notitle\n";
    s << "set output '" << D << "delay_reconstruction.png'\nset size square\nset title '" << label
      << ": delay reconstruction, tau = " << tau << " samples (normalised)'\nset xlabel 's(t)'\nset ylabel 's(t+tau)'\n"
      << "plot '" << D << "delay.dat' u 1:2 w d notitle\nset size nosquare\nset ylabel ''\n";
    s << "set output '" << D << "ami.png'\nset title '" << label << ": AMI (first minimum " << ami.tau_ami
      << ") and autocorrelation'\nset xlabel 'lag (samples)'\n"
      << "plot '" << D << "ami.dat' u 1:2 w lp t 'AMI [nats]', '' u 1:3 w l t 'autocorrelation'\n";
    s << "set output '" << D << "fnn.png'\nset title '" << label << ": false nearest neighbours (Rtol 10, Atol 2), Cao E1/E2'\n"
      << "set xlabel 'embedding dimension m'\nset yrange [0:1.5]\n"
      << "plot '" << D << "fnn.dat' u 1:2 w lp t 'FNN fraction', '' u 1:5 w lp t 'Cao E1', '' u 1:6 w lp t 'Cao E2'\n"
      << "set autoscale y\n";
    s << "set output '" << D << "divergence.png'\nset title sprintf('" << label
      << ": Rosenstein divergence, m=%d tau=%d, slope %.4g +- %.2g', " << m << ", " << tau << ", " << lle.fit.slope
      << ", " << lle.fit.ci95 << ")\nset xlabel 'time t [s]'\nset ylabel '<ln d(t)>'\n"
      << "f(t) = " << y0 << " + " << lle.fit.slope << "*(t - " << t0 << ")\n"
      << "plot '" << D << "divergence.dat' u 1:2 w l t 'divergence', [" << t0 << ":" << t1
      << "] f(x) lw 2 t '" << (lle.fit.scaling_region ? "fit (scaling region)" : "fit (no scaling region: a bound only)")
      << "'\n";
  }
  run_gnuplot(D + "series.gp");
  // Recurrence plot of at most 4000 points (the PNG is at most 1000 px).
  std::vector<double> head(x.begin(), x.begin() + static_cast<long>(std::min<std::size_t>(x.size(), 4000 + (m - 1) * tau)));
  const Embedding e = delay_embed(head, m, tau);
  const double eps = radius_for_rr(e, 0.05, w);
  // The matrix as pixels (libpng), then drawn by gnuplot with its axes in
  // time and the embedding and radius that made it in the title.
  write_recurrence_png(e, eps, -1, D + "recurrence_matrix.png", 1000);
  {
    const std::size_t side = std::min<std::size_t>(e.n, 1000);
    const double px = static_cast<double>(e.n) * dt / static_cast<double>(side);  // one pixel [s]
    const double span = static_cast<double>(e.n) * dt;
    auto r = open_text_file(D + "recurrence.gp");
    r << png_terminal(900, 900) << "set output '" << D << "recurrence.png'\n"
      << "set title \"" << label << ": recurrence plot of the first " << e.n << " points\\nm = " << m
      << ", tau = " << tau << " samples (" << fmt_g(tau * dt) << " s), eps = " << fmt_g(eps)
      << " (z-scored units, recurrence rate 5 %), Euclidean norm\"\n"
      << "set xlabel 'time t_i [s]'\nset ylabel 'time t_j [s]'\nset size ratio -1\n"
      << "set xrange [0:" << span << "]\nset yrange [0:" << span << "]\nset tics out\n"
      << "plot '" << D << "recurrence_matrix.png' binary filetype=png dx=" << px << " dy=" << px
      << " origin=(0,0) with rgbimage notitle\n";
  }
  run_gnuplot(D + "recurrence.gp");
  return {D + "time_history.png", D + "delay_reconstruction.png", D + "ami.png", D + "fnn.png", D + "divergence.png",
          D + "recurrence.png"};
}

std::string run_time_history_figure(const std::vector<double>& x, double dt, long discard, const std::string& label,
                                    const std::string& out_dir) {
  ensure_dir(out_dir);
  if (x.empty()) throw InputError("figures: empty series");
  const std::string D = out_dir + "/";
  double lo = x[0], hi = x[0];
  {
    auto f = open_text_file(D + "run.dat");
    f.precision(15);
    for (std::size_t i = 0; i < x.size(); ++i) {
      f << i * dt << ' ' << x[i] << '\n';
      lo = std::min(lo, x[i]);
      hi = std::max(hi, x[i]);
    }
  }
  // gnuplot cannot draw an empty y range; a constant series gets +-1 % (or +-1).
  const double pad = hi - lo > 1e-9 * std::max(std::abs(hi), std::abs(lo)) ? 0.05 * (hi - lo)
                                                                           : std::max(1.0, 0.01 * std::abs(hi));
  const double t_tr = discard * dt;
  auto s = open_text_file(D + "run.gp");
  s.precision(15);
  s << kTerm << "set output '" << D << "run_time_history.png'\nset title '" << label
    << ": whole run (shaded: transient, not analysed)'\nset xlabel 't [s]'\nset yrange [" << lo - pad << ":"
    << hi + pad << "]\n";
  if (discard > 0)
    s << "set object 1 rect from 0,graph 0 to " << t_tr << ",graph 1 fc rgb '#dddddd' fs solid noborder behind\n";
  s << "plot '" << D << "run.dat' u 1:2 w l notitle\n";
  s.close();
  run_gnuplot(D + "run.gp");
  return D + "run_time_history.png";
}

std::vector<std::string> model_figures(const Model& sc, const Params& p, const std::vector<double>& x0, double dt,
                                       double t_end, const std::string& out_dir, const ProgressFn& progress) {
  ensure_dir(out_dir);
  const std::string D = out_dir + "/";
  const double sample = sc.is_map ? 1.0 : std::max(dt, t_end / 20000);
  const std::vector<double> rows = sc.trajectory(p, x0, dt, 0.0, t_end, sample, progress);
  {
    auto f = open_text_file(D + "scene.dat");
    const std::size_t n = rows.size() / sc.dim;
    for (std::size_t i = 0; i < n; ++i) {
      f << (i + 1) * sample;
      for (int k = 0; k < sc.dim; ++k) f << ' ' << rows[i * sc.dim + k];
      f << '\n';
    }
  }
  std::vector<std::string> out;
  // What made the figure: the model, its integrator and step, its parameters.
  std::string made = sc.name + (sc.is_map ? ": iterated map" : ": RK4, dt = " + fmt_g(dt) + " s");
  for (const auto& [k, v] : p) made += ", " + k + " = " + fmt_g(v);
  const std::string t_axis = sc.is_map ? "iteration n" : "time t (model time units)";
  auto s = open_text_file(D + "scene.gp");
  // One panel per state on a shared time axis (the states of a model may
  // differ in scale and unit); tick labels and the axis title on the bottom
  // panel only.
  const int n = sc.dim;
  const int height = 150 * n + 90;
  s << png_terminal(1000, height) << "set grid\nset output '" << D << "scene_time_history.png'\n"
    << "set lmargin at screen 0.1\nset rmargin at screen 0.97\nset multiplot title '" << made << "'\n";
  const double top = 1.0 - 60.0 / height, bottom = 50.0 / height, h = (top - bottom) / n;
  for (int k = 0; k < n; ++k) {
    s << "set tmargin at screen " << top - k * h << "\nset bmargin at screen " << top - (k + 1) * h + 0.01 << '\n';
    s << (k + 1 == n ? "set format x '%g'\nset xlabel '" + t_axis + "'\n" : std::string("set format x ''\nunset xlabel\n"));
    s << "set ylabel '" << sc.state_names[k] << "'\nplot '" << D << "scene.dat' u 1:" << k + 2
      << (sc.is_map ? " w d" : " w l") << " notitle\n";
  }
  s << "unset multiplot\nreset\n" << kTerm;
  out.push_back(D + "scene_time_history.png");
  // Phase portraits: (x1, v1) and (x2, v2) for the oscillator, (x, y) otherwise.
  for (int k = 0; k + 1 < sc.dim; k += 2) {
    const std::string png = D + "scene_phase_" + sc.state_names[k] + ".png";
    s << "set output '" << png << "'\nset title \"" << made << "\\nphase portrait\"\nset xlabel '" << sc.state_names[k]
      << "'\nset ylabel '" << sc.state_names[k + 1] << "'\nplot '" << D << "scene.dat' u " << k + 2 << ":" << k + 3
      << (sc.is_map ? " w d" : " w l") << " notitle\n";
    out.push_back(png);
  }
  s.close();
  run_gnuplot(D + "scene.gp");
  return out;
}

std::vector<std::string> sweep_figures(const std::string& sweep_csv, const std::string& out_dir) {
  ensure_dir(out_dir);
  std::ifstream in(sweep_csv);
  if (!in) throw InputError("cannot read '" + sweep_csv + "'");
  std::string sig, header, line;
  if (!std::getline(in, sig) || sig.rfind("# cvtplant sweep ", 0) != 0 || !std::getline(in, header))
    throw InputError("'" + sweep_csv + "' is not a merged sweep file");
  std::vector<std::string> cols;
  {
    std::stringstream hs(header);
    std::string c;
    while (std::getline(hs, c, ',')) cols.push_back(c);
  }
  const bool two_d = sig.find(" a2=") != std::string::npos;
  // What made the sweep, from its signature: the scene, the fixed
  // parameters, the run lengths and the state whose maxima are drawn.
  std::map<std::string, std::string> made;
  std::string fixed;
  {
    std::stringstream ss(sig.substr(std::string("# cvtplant sweep ").size()));
    std::string tok;
    while (ss >> tok) {
      const std::size_t eq = tok.find('=');
      if (eq == std::string::npos) continue;
      const std::string k = tok.substr(0, eq), v = tok.substr(eq + 1);
      // Numbers are written with 17 digits; the title shows them short.
      char* end = nullptr;
      const double num = std::strtod(v.c_str(), &end);
      made[k] = k != "scene" && k != "a1" && k != "a2" && k != "x0" && end != v.c_str() && *end == '\0' ? fmt_g(num) : v;
      if (k != "scene" && k != "a1" && k != "a2" && k != "x0" && k != "dt" && k != "t_transient" && k != "t_end" &&
          k != "state" && k != "total")
        fixed += ", " + k + " = " + made[k];
    }
  }
  const bool is_map = has_model(made["scene"]) && find_model(made["scene"]).is_map;
  const std::string runs = is_map ? "transient " + made["t_transient"] + ", accumulation " + made["t_end"] + " iterations"
                                  : "RK4 dt = " + made["dt"] + " s, transient " + made["t_transient"] +
                                        " s, accumulation " + made["t_end"] + " s";
  const std::string subtitle = made["scene"] + fixed + "; " + runs;
  const std::string lambda_unit = is_map ? "[1/iteration]" : "[1/s]";
  const std::string D = out_dir + "/";
  auto bif = open_text_file(D + "bifurcation.dat");
  auto lam = open_text_file(D + "exponents.dat");
  long line_no = 2;
  std::size_t peaks_col = 0;
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == "peaks") peaks_col = i;
  if (peaks_col == 0) throw InputError("'" + sweep_csv + "': no peaks column");
  double last_p2 = std::nan("");
  double lam_abs = 1e-3;
  while (std::getline(in, line)) {
    ++line_no;
    std::vector<std::string> cells;
    std::stringstream ls(line);
    std::string c;
    while (std::getline(ls, c, ',')) cells.push_back(c);
    if (cells.size() < peaks_col + 1) throw InputError(sweep_csv + ":" + std::to_string(line_no) + ": short row");
    const double p1 = std::atof(cells[1].c_str()), p2 = std::atof(cells[2].c_str());
    if (two_d && !std::isnan(last_p2) && p2 != last_p2) lam << '\n';  // gnuplot pm3d scan break
    last_p2 = p2;
    lam << p1 << ' ' << p2 << ' ' << cells[3] << '\n';
    if (std::isfinite(std::atof(cells[3].c_str()))) lam_abs = std::max(lam_abs, std::abs(std::atof(cells[3].c_str())));
    std::stringstream ps(cells[peaks_col]);
    std::string v;
    while (std::getline(ps, v, ';'))
      if (!v.empty()) bif << p1 << ' ' << p2 << ' ' << v << '\n';
  }
  bif.close();
  lam.close();
  auto s = open_text_file(D + "sweep.gp");
  s << kTerm;
  s << "set output '" << D << "bifurcation.png'\nset title \"bifurcation diagram: local maxima of state "
    << made["state"] << " against " << cols[1] << "\\n" << subtitle << "\"\nset xlabel '" << cols[1]
    << "'\nset ylabel 'local maxima of state " << made["state"] << "'\n";
  if (two_d)
    s << "set cblabel '" << cols[2] << "'\nplot '" << D << "bifurcation.dat' u 1:3:2 w p pt 7 ps 0.3 palette notitle\n";
  else
    s << "plot '" << D << "bifurcation.dat' u 1:3 w p pt 7 ps 0.3 notitle\n";
  s << "set output '" << D << "exponent_map.png'\n";
  if (two_d)
    s << "set title \"largest Lyapunov exponent lambda_1 " << lambda_unit << " over " << cols[1] << " and " << cols[2]
      << "\\n" << subtitle << "\"\nset xlabel '" << cols[1] << "'\nset ylabel '" << cols[2]
      << "'\nset palette defined (-1 'blue', 0 'white', 1 'red')\nset cbrange [" << -lam_abs << ":"
      << lam_abs << "]\nset cblabel 'lambda_1 " << lambda_unit << " (white = 0)'\nplot '" << D
      << "exponents.dat' u 1:2:3 w image notitle\n";  // one cell per grid point, its own colour
  else
    s << "set title \"largest Lyapunov exponent against " << cols[1] << "\\n" << subtitle << "\"\nset xlabel '"
      << cols[1] << "'\nset ylabel 'lambda_1 " << lambda_unit << "'\nplot '" << D
      << "exponents.dat' u 1:3 w lp notitle, 0 lc 'black' notitle\n";
  s.close();
  run_gnuplot(D + "sweep.gp");
  return {D + "bifurcation.png", D + "exponent_map.png"};
}

}  // namespace cvt::analysis
