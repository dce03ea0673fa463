#pragma once
// `cvtplant mbd` and `cvtplant mbd figures`: shared option handling and the
// run driver of the multibody reference (docs/cli.md#mbd, docs/mbd.md).
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "cvtplant/mbd/model.hpp"
#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/mbd/summary.hpp"

namespace cvtcli::mbdcli {

// Options that choose the model and the numerics (both subcommands).
struct ModelOptions {
  std::string set = "seed";  // parameter set (docs/mbd-production.md): seed | production
  double t_end_s = 10.0;
  std::string sheaves;  // empty: the set's own (seed: fixed, production: clamped)
  std::string clamp1, clamp2;  // "F" or "t:F,t:F,..." [s:N]
  std::string method = "bdf";
  double dt_s = 1e-6;
  double rtol = 5e-7;
  std::string linear_solver = "chain";  // the BDF's Newton systems: chain | klu (docs/mbd.md#linear-algebra)
  int links = 44;
  double sample_s = 1e-3;
  std::string tau_in = "100", tau_load = "50";  // "T" or "t:T,t:T,..." [s:N m]
  std::string road_load;                        // "T0,cv,ca[,w_eps]"; empty: none
  std::string omega0;                           // "W1,W2" [rad/s]; empty: from rest
  double ledger_tol = 1e-6;
  long long max_steps = 100000000;
  long long max_rows = 2000000;
  // set by CLI11 when given (options that only apply to one method or mode)
  CLI::Option* dt_opt = nullptr;
  CLI::Option* rtol_opt = nullptr;
  CLI::Option* solver_opt = nullptr;
  CLI::Option* clamp1_opt = nullptr;
  CLI::Option* clamp2_opt = nullptr;
  CLI::Option* road_opt = nullptr;
  CLI::Option* omega0_opt = nullptr;
  CLI::Option* links_opt = nullptr;
  bool production() const { return set == "production"; }
  std::string sheave_mode() const { return !sheaves.empty() ? sheaves : production() ? "clamped" : "fixed"; }
};

void add_model_options(CLI::App* sub, ModelOptions& o);

// Checks every option against its range and their combinations; throws
// UsageError (exit 2) before any work is done.
void validate(const ModelOptions& o);

cvt::mbd::MbdParams params_for(const ModelOptions& o, int friction_case);
cvt::mbd::RunOptions run_options_for(const ModelOptions& o);

std::string num(double v);                        // %g, for messages and figure titles
std::string method_label(const ModelOptions& o);  // "BDF rtol 1e-06" / "RK4 dt 1e-06 s"
std::string case_label(int friction_case);        // "case 1 (Coulomb)" ...

// Per-sample CSV (docs/cli.md#mbd-csv); nullptr: none.
void write_csv_header(std::FILE* f, bool clamped);
void write_csv_row(std::FILE* f, const cvt::mbd::Sample& s, double residual_rel, bool clamped);
void write_links_header(std::FILE* f);
void write_links_rows(std::FILE* f, double t_s, const std::vector<cvt::mbd::LinkState>& links);

struct RunOutcome {
  cvt::mbd::RunStats stats;
  cvt::mbd::RunSummary summary;
  bool failed = false;
  double fail_t_s = 0;
  std::string fail_quantity;
  std::vector<cvt::mbd::LinkState> picture;  // links at picture_t (if asked)
  double picture_t_s = -1;
};

// Runs one case with a progress bar; writes the CSVs as it goes. picture_t_s
// >= 0 keeps the links at the first sample at or after that time.
RunOutcome run_case(const ModelOptions& o, int friction_case, std::FILE* csv, std::FILE* links_csv,
                    double links_every_s, double picture_t_s, const std::string& progress_label);

// `cvtplant mbd figures` (cmd_mbd_figures.cpp).
struct FigureOptions {
  std::string out_dir;
  double picture_t_s = -1;  // -1 (not given): the end of the run
  bool json = false;
  ModelOptions model;
};
void add_figure_options(CLI::App* sub, FigureOptions& o);
int run_figures(const FigureOptions& o);

}  // namespace cvtcli::mbdcli
