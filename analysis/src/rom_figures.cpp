// Time histories and phase portraits of a plant scene (docs/analysis.md#figures):
// the frames `cvtplant run` computes, drawn as panels of one unit each on a
// shared time axis.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/figures.hpp"
#include "cvtplant/analysis/rom_scenes.hpp"
#include "cvtplant/integrate/method.hpp"

namespace cvt::analysis {

namespace {

// One panel: the signals drawn, the quantity and its SI unit. Panels whose
// SI unit is m or m/s are drawn in m, mm or um (m/s, mm/s or um/s) after the
// largest value shown, so that the ticks read as plain numbers.
struct Panel {
  const char* quantity;
  const char* si_unit;
  double scale;  // from SI to the unit shown (forces: kN)
  const char* unit;
  std::vector<std::pair<const char*, const char*>> curves;  // signal, legend
};

const std::vector<Panel>& panels() {
  static const std::vector<Panel> p = {
      {"speed", "rad/s", 1.0, "rad/s", {{"omega1", "omega1 (driver)"}, {"omega2", "omega2 (driven)"}}},
      {"speed ratio", "-", 1.0, "-", {{"speed_ratio", "omega1/omega2"}}},
      {"force", "N", 1e-3, "kN", {{"F_ax", "F_ax clamping"}, {"F1", "F1 friction"}, {"F2", "F2 friction"}}},
      {"slip", "-", 1.0, "-", {{"slip", "slip"}}},
      {"lump displacement", "m", 1.0, "m", {{"x1", "x1"}, {"x2", "x2"}}},
      {"lump velocity", "m/s", 1.0, "m/s", {{"xd1", "xd1"}, {"xd2", "xd2"}}},
  };
  return p;
}

// The unit for lengths (or speeds) whose largest magnitude is `peak` [SI].
void length_unit(double peak, const std::string& si, double& scale, std::string& unit) {
  const std::string per = si == "m/s" ? "/s" : "";
  if (peak >= 1.0) scale = 1.0, unit = "m" + per;
  else if (peak >= 1e-3) scale = 1e3, unit = "mm" + per;
  else scale = 1e6, unit = "um" + per;
}

// The speed ratio is undefined while the driven pulley stands nearly still.
constexpr double kRatioMinOmega2_rad_s = 1.0;

std::string frame_text(double frame_s) {
  char buf[48];
  if (frame_s >= 1e-3 && frame_s < 1) std::snprintf(buf, sizeof buf, "%g ms", frame_s * 1e3);
  else if (frame_s >= 1e-6 && frame_s < 1e-3) std::snprintf(buf, sizeof buf, "%g us", frame_s * 1e6);
  else std::snprintf(buf, sizeof buf, "%g s", frame_s);
  return buf;
}

}  // namespace

std::string rom_scene_title(const cvt::Scene& scene, const std::string& name) {
  return name + ": double, " + cvt::method_name(scene.method) + " x " + std::to_string(scene.substeps) +
         " substeps, frame " + frame_text(scene.frame_s);
}

std::vector<std::string> rom_scene_figures(const cvt::Scene& scene, const std::string& name, double t_end,
                                           const std::string& out_dir, const ProgressFn& progress) {
  std::vector<std::string> signals;
  for (const Panel& p : panels())
    for (const auto& c : p.curves) signals.push_back(c.first);
  const RomSeries run = rom_scene_series(scene, name, signals, t_end, progress);
  if (run.t.empty()) throw InputError("scene '" + name + "': no frame to draw (t_end shorter than a frame)");
  ensure_dir(out_dir);
  const std::string D = out_dir + "/";
  // At most ~20,000 rows: more than a 1600-pixel-wide figure can show.
  const std::size_t stride = std::max<std::size_t>(1, run.t.size() / 20000);
  {
    auto f = open_text_file(D + "scene.dat");
    f << "# t_s";
    for (const auto& sg : signals) f << ' ' << sg;
    f << '\n';
    const std::vector<double>& w2 = run.signal.at("omega2");
    for (std::size_t i = 0; i < run.t.size(); i += stride) {
      f << run.t[i];
      for (const auto& sg : signals) {
        const bool undefined = sg == "speed_ratio" && std::fabs(w2[i]) < kRatioMinOmega2_rad_s;
        if (undefined) f << " NaN";
        else f << ' ' << run.signal.at(sg)[i];
      }
      f << '\n';
    }
  }
  auto column = [&](const char* sig) {
    for (std::size_t k = 0; k < signals.size(); ++k)
      if (signals[k] == sig) return static_cast<int>(k) + 2;
    return 0;
  };
  // The units shown, per panel.
  std::vector<double> scale;
  std::vector<std::string> unit;
  for (const Panel& p : panels()) {
    double sc = p.scale;
    std::string u = p.unit;
    if (std::string(p.si_unit) == "m" || std::string(p.si_unit) == "m/s") {
      double peak = 0;
      for (const auto& c : p.curves)
        for (double v : run.signal.at(c.first)) peak = std::max(peak, std::fabs(v));
      length_unit(peak, p.si_unit, sc, u);
    }
    scale.push_back(sc);
    unit.push_back(u);
  }
  const std::string title = rom_scene_title(scene, name);
  const int n = static_cast<int>(panels().size());
  // 210 px a panel: the longest axis title ("lump displacement [mm]") fits.
  const int height = 210 * n + 90;
  // The speed ratio passes through infinity when a start from rest turns the
  // driven pulley backwards; its axis spans the 2nd to 98th percentile of the
  // defined samples (padded), so the settled ratio is readable and a spike
  // runs off the panel's edge instead of flattening everything else.
  std::string ratio_range;
  {
    const std::vector<double>& w2 = run.signal.at("omega2");
    const std::vector<double>& ratio = run.signal.at("speed_ratio");
    std::vector<double> v;
    for (std::size_t i = 0; i < ratio.size(); ++i)
      if (std::fabs(w2[i]) >= kRatioMinOmega2_rad_s && std::isfinite(ratio[i])) v.push_back(ratio[i]);
    if (v.size() >= 50) {
      std::sort(v.begin(), v.end());
      const double lo = v[v.size() / 50], hi = v[v.size() - 1 - v.size() / 50];
      const double pad = std::max(0.1 * (hi - lo), 0.05 * std::max(std::fabs(lo), std::fabs(hi)) + 1e-9);
      std::ostringstream r;
      r.precision(6);
      r << "[" << lo - pad << ":" << hi + pad << "]";
      ratio_range = r.str();
    }
  }
  auto s = open_text_file(D + "scene.gp");
  // Panels share the time axis: equal left/right margins, tick labels and
  // the axis title on the bottom panel only; each legend right of its panel,
  // outside the plot area, so it never covers data.
  s << png_terminal(1100, height) << "set output '" << D << "scene_time_history.png'\nset grid\n"
    << "set lmargin at screen 0.09\nset rmargin at screen 0.78\nset ytics nomirror\nset format y '%g'\n"
    << "set datafile missing 'NaN'\n"
    << "set multiplot title '" << title << (run.fault != "none" ? " (plant fault: " + run.fault + ")" : "")
    << "'\n";
  const double top = 1.0 - 60.0 / height, bottom = 50.0 / height;
  const double h = (top - bottom) / n;
  for (int k = 0; k < n; ++k) {
    const Panel& p = panels()[k];
    s << "set tmargin at screen " << top - k * h << "\nset bmargin at screen " << top - (k + 1) * h + 0.01 << '\n';
    s << "set key at screen 0.79, screen " << top - k * h << " left top Left reverse samplen 2\n";
    s << "set xrange [" << run.t.front() << ":" << run.t.back() << "]\n";
    if (k + 1 == n)
      s << "set format x '%g'\nset xlabel 'time t [s]'\n";
    else
      s << "set format x ''\nunset xlabel\n";
    if (std::string(p.curves.front().first) == "speed_ratio" && !ratio_range.empty())
      s << "set yrange " << ratio_range << "\n";
    else
      s << "set autoscale y\n";
    s << "set ylabel '" << p.quantity << " [" << unit[k] << "]'\nplot ";
    for (std::size_t c = 0; c < p.curves.size(); ++c) {
      const std::string legend = p.curves[c].second;
      s << (c ? ", " : "") << "'" << D << "scene.dat' u 1:($" << column(p.curves[c].first) << "*" << scale[k]
        << ") w l lw 1.2 t '" << legend << "'";
    }
    s << '\n';
  }
  s << "unset multiplot\n";
  // Phase portraits of the two lumps (seed Figs. 9/10 style), in the
  // panels' units.
  std::vector<std::string> out{D + "scene_time_history.png"};
  s << "reset\n" << png_terminal(800, 700) << "set grid\n";
  const std::size_t disp = 4, vel = 5;  // panels of the lump displacement and velocity
  for (int lump = 1; lump <= 2; ++lump) {
    const std::string x = "x" + std::to_string(lump), v = "xd" + std::to_string(lump);
    const std::string png = D + "scene_phase_lump" + std::to_string(lump) + ".png";
    s << "set output '" << png << "'\nset title \"" << title << "\\nphase portrait of lump " << lump << ", t = "
      << run.t.front() << " .. " << run.t.back() << " s\"\nset xlabel '" << x << " [" << unit[disp]
      << "]'\nset ylabel '" << v << " [" << unit[vel] << "]'\nplot '" << D << "scene.dat' u ($" << column(x.c_str())
      << "*" << scale[disp] << "):($" << column(v.c_str()) << "*" << scale[vel] << ") w l lw 0.8 notitle\n";
    out.push_back(png);
  }
  s.close();
  run_gnuplot(D + "scene.gp");
  return out;
}

}  // namespace cvt::analysis
