// docs/analysis.md#evidence-figures
#include "cvtplant/analysis/evidence_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/analysis/rqa.hpp"
#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

namespace {

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::vector<std::string> evidence_figures(const EvidenceFigures& f, const std::string& out_dir) {
  ensure_dir(out_dir);
  validate_series(f.x, 200, "figures");
  const std::vector<double> z = zscore(f.x);
  const std::string D = out_dir + "/";
  const std::string term = png_terminal(900, 600) + "set grid\n";
  std::vector<std::string> out;
  auto s = open_text_file(D + "evidence.gp");
  {
    auto d = open_text_file(D + "window.dat");
    for (std::size_t i = 0; i < f.x.size(); ++i) d << i * f.dt << ' ' << f.x[i] << ' ' << z[i] << '\n';
  }
  s << term << "set output '" << D << "time_history.png'\nset title '" << f.label
    << ": the analysed window'\nset xlabel 'time in the window [s]'\nset ylabel '" << f.unit << "'\nplot '" << D
    << "window.dat' u 1:2 w l notitle\nset ylabel ''\n";
  out.push_back(D + "time_history.png");

  if (!f.delays.empty()) {
    const int n = static_cast<int>(std::min<std::size_t>(f.delays.size(), 4));
    s << "set output '" << D << "delay_reconstructions.png'\nreset\n" << png_terminal(1000, 1000)
      << "set grid\nset multiplot layout 2,2 title '" << f.label << ": delay reconstructions s(t) against s(t + d dt), normalised'\n";
    for (int k = 0; k < n; ++k) {
      const int d = f.delays[static_cast<std::size_t>(k)];
      const std::string file = D + "delay_" + std::to_string(d) + ".dat";
      auto dd = open_text_file(file);
      for (std::size_t i = 0; i + static_cast<std::size_t>(d) < z.size(); ++i) dd << z[i] << ' ' << z[i + d] << '\n';
      s << "set size square\nset title 'd = " << d << " (" << g(d * f.dt * 1e3) << " ms)'\nset xlabel 's(t)'\nset ylabel 's(t + d)'\n"
        << "plot '" << file << "' u 1:2 w l lw 0.5 notitle\n";
    }
    s << "unset multiplot\nreset\n" << term;
    out.push_back(D + "delay_reconstructions.png");
  }

  if (!f.ami.ami.empty()) {
    auto a = open_text_file(D + "ami.dat");
    for (std::size_t k = 0; k < f.ami.ami.size(); ++k) a << k << ' ' << f.ami.ami[k] << ' ' << f.ami.acf[k] << '\n';
    s << "set output '" << D << "ami.png'\nset title '" << f.label << ": AMI (first minimum " << f.ami.tau_ami
      << ", chosen " << f.ami.tau << " by " << f.ami.method << "), autocorrelation; seed d = " << f.seed_tau
      << "'\nset xlabel 'lag [samples]'\nset ylabel ''\nset arrow 1 from " << f.seed_tau << ",graph 0 to " << f.seed_tau
      << ",graph 1 nohead dt 2\nplot '" << D << "ami.dat' u 1:2 w lp pt 7 ps 0.4 t 'AMI [nats]', '' u 1:3 w l t 'autocorrelation'\nunset arrow 1\n";
    out.push_back(D + "ami.png");
  }

  if (!f.fnn.m.empty()) {
    auto n = open_text_file(D + "fnn.dat");
    for (std::size_t k = 0; k < f.fnn.m.size(); ++k)
      n << f.fnn.m[k] << ' ' << f.fnn.fraction[k] << ' ' << (k < f.cao.e1.size() ? f.cao.e1[k] : NAN) << ' '
        << (k < f.cao.e2.size() ? f.cao.e2[k] : NAN) << '\n';
    s << "set output '" << D << "fnn.png'\nset title '" << f.label << ": false nearest neighbours (Kennel, Rtol 10, Atol 2) and Cao E1, E2; d = "
      << f.seed_tau << "'\nset xlabel 'embedding dimension m'\nset yrange [0:1.5]\nplot '" << D
      << "fnn.dat' u 1:2 w lp t 'FNN fraction', '' u 1:3 w lp t 'Cao E1', '' u 1:4 w lp t 'Cao E2'\nset autoscale y\n";
    out.push_back(D + "fnn.png");
  }

  if (!f.divergence.empty()) {
    std::string plot = "plot ";
    for (std::size_t k = 0; k < f.divergence.size(); ++k) {
      const LleResult& r = f.divergence[k].second;
      const std::string file = D + "divergence_" + std::to_string(k) + ".dat";
      auto d = open_text_file(file);
      for (std::size_t i = 0; i < r.divergence.size(); ++i) d << i * f.dt << ' ' << r.divergence[i] << '\n';
      const double t0 = r.fit.k_begin * f.dt, t1 = r.fit.k_end * f.dt;
      const double y0 = r.divergence.empty() ? 0.0 : r.divergence[static_cast<std::size_t>(r.fit.k_begin)];
      char title[200];
      std::snprintf(title, sizeof title, "%s: slope %.4g +- %.2g 1/s%s", f.divergence[k].first.c_str(), r.fit.slope,
                    r.fit.ci95, r.fit.scaling_region ? "" : " (no scaling region)");
      plot += (k ? ", '" : "'") + file + "' u 1:2 w l lw 2 t '" + title + "', [" + g(t0) + ":" + g(t1) + "] " + g(y0) +
              " + " + g(r.fit.slope) + "*(x - " + g(t0) + ") dt 2 lc 'black' notitle";
    }
    s << "set output '" << D << "divergence.png'\nset key bottom right\nset title '" << f.label
      << ": Rosenstein divergence of nearby orbits'\nset xlabel 'time t [s]'\nset ylabel '<ln d(t)>'\n" << plot
      << "\nset key default\nset ylabel ''\n";
    out.push_back(D + "divergence.png");
  }

  {
    const Spectrum sp = periodogram(f.x);
    auto d = open_text_file(D + "spectrum.dat");
    for (std::size_t k = 1; k < sp.freq.size(); ++k) d << sp.freq[k] / f.dt << ' ' << sp.power[k] << '\n';
    s << "set output '" << D << "spectrum.png'\nset title '" << f.label
      << ": Hann periodogram of the window'\nset xlabel 'frequency [Hz]'\nset ylabel 'power'\nset logscale y\n";
    int id = 10;
    for (const auto& [name, hz] : f.marks_Hz) {
      if (!(hz > 0)) continue;
      s << "set arrow " << id << " from " << hz << ",graph 0 to " << hz << ",graph 1 nohead dt 3 lc 'red'\n"
        << "set label " << id << " '" << name << "' at " << hz << ",graph " << 0.95 - 0.05 * (id - 10) << " tc 'red'\n";
      ++id;
    }
    s << "plot '" << D << "spectrum.dat' u 1:2 w l notitle\nunset logscale y\nunset arrow\nunset label\nset ylabel ''\n";
    out.push_back(D + "spectrum.png");
  }

  if (f.has_surrogates) {
    auto d = open_text_file(D + "surrogates.dat");
    s << "set output '" << D << "surrogates.png'\nreset\n" << png_terminal(1200, 450) << "set grid\nset multiplot layout 1,"
      << f.surrogates.statistics.size() << " title '" << f.label << ": the data (red) among " << f.surrogates.count
      << " IAAFT surrogates (black)'\n";
    int block = 0;
    for (const auto& st : f.surrogates.statistics) {
      for (double v : st.surrogates) d << block << ' ' << v << '\n';
      d << "\n\n";
      char title[160];
      std::snprintf(title, sizeof title, "%s\\nrank %d from below, %d from above; p %.3g (%s)", st.name.c_str(),
                    st.rank_low, st.rank_high, st.p, st.tail.c_str());
      s << "set title \"" << title << "\"\nset xrange [-1:1]\nset xtics ()\nset arrow 1 from -0.6," << st.data
        << " to 0.6," << st.data << " nohead lw 3 lc 'red'\nplot '" << D << "surrogates.dat' index " << block
        << " u (0):2 w p pt 7 lc 'black' notitle\nunset arrow 1\n";
      ++block;
    }
    s << "unset multiplot\nreset\n" << term;
    out.push_back(D + "surrogates.png");
  }

  if (!f.separations.empty()) {
    std::string plot = "plot ";
    int k = 0;
    for (const auto& [name, sep] : f.separations) {
      const std::string file = D + "separation_" + std::to_string(k) + ".dat";
      auto d = open_text_file(file);
      for (std::size_t i = 0; i < sep.t_s.size(); ++i)
        if (std::isfinite(sep.log_sep[i])) d << sep.t_s[i] << ' ' << sep.log_sep[i] / std::log(10.0) << '\n';
      plot += (k ? ", '" : "'") + file + "' u 1:2 w l t '" + name + "'";
      ++k;
    }
    s << "set output '" << D << "separation.png'\nset key bottom right\nset title '" << f.label
      << ": distance between runs that differ only in their numerics'\nset xlabel 'time from the release [s]'\n"
      << "set ylabel 'log10(max |a - b| / std a) per block'\n" << plot << "\nset key default\nset ylabel ''\n";
    out.push_back(D + "separation.png");
  }
  if (f.has_exponent && !f.exponent_t_s.empty()) {
    auto d = open_text_file(D + "exponent.dat");
    for (std::size_t i = 0; i < f.exponent_t_s.size(); ++i) d << f.exponent_t_s[i] << ' ' << f.exponent_running[i] << '\n';
    const double t1 = f.exponent_t_s.back();
    s << "set output '" << D << "exponent.png'\nset title sprintf('" << f.label
      << ": largest exponent of the equations, two trajectories: %.4g +- %.2g 1/s', " << f.exponent << ", "
      << f.exponent_ci95 << ")\nset xlabel 'accumulated time [s]'\nset ylabel 'running estimate [1/s]'\n"
      << "set object 2 rect from 0," << f.exponent - f.exponent_ci95 << " to " << t1 << "," << f.exponent + f.exponent_ci95
      << " fc rgb '#dddddd' fs solid noborder behind\nplot '" << D
      << "exponent.dat' u 1:2 w l lw 2 t 'running estimate', 0 lc 'black' dt 2 notitle\nunset object 2\nset ylabel ''\n";
    out.push_back(D + "exponent.png");
  }
  s.close();
  run_gnuplot(D + "evidence.gp");

  // Recurrence plot at the given embedding (seed Figs. 21-22): the matrix as
  // pixels, drawn with time axes.
  const Embedding e = delay_embed(z, f.rp_m, f.rp_tau);
  const double eps = radius_for_rr(e, f.rp_rr, 0);
  write_recurrence_png(e, eps, -1, D + "recurrence_matrix.png", 1000);
  {
    const std::size_t side = std::min<std::size_t>(e.n, 1000);
    const double px = static_cast<double>(e.n) * f.dt / static_cast<double>(side);
    const double span = static_cast<double>(e.n) * f.dt;
    auto r = open_text_file(D + "recurrence.gp");
    r << png_terminal(900, 900) << "set output '" << D << "recurrence.png'\n"
      << "set title \"" << f.label << ": recurrence plot of " << e.n << " points\\nm = " << f.rp_m << ", d = " << f.rp_tau
      << " samples, eps = " << g(eps) << " (z-scored units; recurrence rate " << g(100 * f.rp_rr) << " %), Euclidean norm\"\n"
      << "set xlabel 'time t_i [s]'\nset ylabel 'time t_j [s]'\nset size ratio -1\nset xrange [0:" << span
      << "]\nset yrange [0:" << span << "]\nset tics out\nplot '" << D << "recurrence_matrix.png' binary filetype=png dx="
      << px << " dy=" << px << " origin=(0,0) with rgbimage notitle\n";
  }
  run_gnuplot(D + "recurrence.gp");
  out.push_back(D + "recurrence.png");
  return out;
}

}  // namespace cvt::analysis
