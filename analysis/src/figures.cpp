#include "cvtplant/analysis/figures.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
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
    s << "set output '" << D << "time_history.png'\nset title '" << label << ": time history'\nset xlabel 't'\n"
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
      << ", " << lle.fit.ci95 << ")\nset xlabel 't'\nset ylabel '<ln d(t)>'\n"
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
  write_recurrence_png(e, eps, -1, D + "recurrence.png", 1000);
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
                                       double t_end, const std::string& out_dir) {
  ensure_dir(out_dir);
  const std::string D = out_dir + "/";
  const double sample = sc.is_map ? 1.0 : std::max(dt, t_end / 20000);
  const std::vector<double> rows = sc.trajectory(p, x0, dt, 0.0, t_end, sample);
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
  auto s = open_text_file(D + "scene.gp");
  s << kTerm;
  s << "set output '" << D << "scene_time_history.png'\nset title '" << sc.name << ": time history'\nset xlabel 't'\nplot ";
  for (int k = 0; k < sc.dim; k += (sc.dim == 4 ? 2 : 1))
    s << (k ? ", " : "") << "'" << D << "scene.dat' u 1:" << k + 2 << " w l t '" << sc.state_names[k] << "'";
  s << "\n";
  out.push_back(D + "scene_time_history.png");
  // Phase portraits: (x1, v1) and (x2, v2) for the oscillator, (x, y) otherwise.
  for (int k = 0; k + 1 < sc.dim; k += 2) {
    const std::string png = D + "scene_phase_" + sc.state_names[k] + ".png";
    s << "set output '" << png << "'\nset title '" << sc.name << ": phase portrait'\nset xlabel '" << sc.state_names[k]
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
  s << "set output '" << D << "bifurcation.png'\nset title 'bifurcation diagram (local maxima)'\nset xlabel '" << cols[1]
    << "'\nset ylabel 'peak value'\n";
  if (two_d)
    s << "plot '" << D << "bifurcation.dat' u 1:3:2 w p pt 7 ps 0.3 palette t 'colour: " << cols[2] << "'\n";
  else
    s << "plot '" << D << "bifurcation.dat' u 1:3 w p pt 7 ps 0.3 notitle\n";
  s << "set output '" << D << "exponent_map.png'\n";
  if (two_d)
    s << "set title 'largest Lyapunov exponent'\nset xlabel '" << cols[1] << "'\nset ylabel '" << cols[2]
      << "'\nset view map\nset palette defined (-1 'blue', 0 'white', 1 'red')\nset cbrange [" << -lam_abs << ":"
      << lam_abs << "]\nset cblabel 'lambda_1 (white = 0)'\nsplot '" << D
      << "exponents.dat' u 1:2:3 w pm3d notitle\n";
  else
    s << "set title 'largest Lyapunov exponent'\nset xlabel '" << cols[1] << "'\nset ylabel 'lambda_1'\nplot '" << D
      << "exponents.dat' u 1:3 w lp notitle, 0 lc 'black' notitle\n";
  s.close();
  run_gnuplot(D + "sweep.gp");
  return {D + "bifurcation.png", D + "exponent_map.png"};
}

}  // namespace cvt::analysis
