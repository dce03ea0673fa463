#pragma once
// The seed's kinds of figures as PNG (docs/analysis.md#figures), drawn by
// gnuplot (Debian gnuplot-nox, pngcairo terminal) from data files written next
// to the images; recurrence plots are written directly with libpng.
#include <fstream>
#include <string>
#include <vector>

#include "cvtplant/analysis/systems.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt::analysis {

// Time history, delay reconstruction, AMI, FNN, Cao, divergence curve with
// the fitted scaling region, recurrence plot. tau/m <= 0: chosen as in
// classify. Returns the PNG paths written.
std::vector<std::string> series_figures(const std::vector<double>& x, double dt, const std::string& label,
                                        const std::string& out_dir, int tau = -1, int m = -1);

// Time history of a whole sampled run (t = i dt) with the first `discard`
// samples (the transient) marked; the y range is widened for a constant
// series. Returns the PNG path (out_dir/run_time_history.png).
std::string run_time_history_figure(const std::vector<double>& x, double dt, long discard, const std::string& label,
                                    const std::string& out_dir);

// A plant scene run as `cvtplant run` runs it (double), drawn as stacked
// panels of one unit each on a shared time axis in s: speeds [rad/s], speed
// ratio, forces [kN], slip, lump displacements [um] and velocities [mm/s];
// the title names the scene, scalar type, integrator, substeps and frame
// step. Plus the phase portraits of the two lumps. Returns the PNG paths
// (scene_time_history.png, scene_phase_lump1.png, scene_phase_lump2.png).
std::vector<std::string> rom_scene_figures(const cvt::Scene& scene, const std::string& name, double t_end,
                                           const std::string& out_dir, const ProgressFn& progress = {});
// "NAME: double, ros2 x 1 substeps, frame 1 ms": the figures' title.
std::string rom_scene_title(const cvt::Scene& scene, const std::string& name);

// Time histories (one panel per state, shared time axis) and phase portraits
// of a model of the registry (seed Figs. 9/10 style).
// `progress` as Model::trajectory's.
std::vector<std::string> model_figures(const Model& s, const Params& p, const std::vector<double>& x0, double dt,
                                       double t_end, const std::string& out_dir, const ProgressFn& progress = {});

// Bifurcation diagram (peaks vs first parameter) and, for 2-D sweeps, the
// largest-exponent map; for 1-D sweeps the exponents vs the parameter.
std::vector<std::string> sweep_figures(const std::string& sweep_csv, const std::string& out_dir);

// Creates directory d (one level) unless it exists; InputError otherwise.
void ensure_dir(const std::string& d);

// A data file or gnuplot script to write next to the figures (10 significant
// digits); InputError if it cannot be opened.
std::ofstream open_text_file(const std::string& path);

// The first line of every figure script: PNG through cairo, w x h pixels,
// the figures' font, labels printed literally.
std::string png_terminal(int width_px, int height_px);

// Runs gnuplot on a script; throws std::runtime_error if it fails.
void run_gnuplot(const std::string& script_path);

}  // namespace cvt::analysis
