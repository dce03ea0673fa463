#pragma once
// `cvtplant analyze <tool>` (docs/analysis.md, docs/cli.md#analyze): one
// function per tool registers it and returns its action; this header is what
// the tools' files share (cmd_analyze.cpp registers them all, the series
// tools are in cmd_analyze_series.cpp, the scene, sweep and figure tools in
// cmd_analyze_scenes.cpp).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "commands.hpp"
#include "options.hpp"
#include "cvtplant/analysis/classify.hpp"
#include "cvtplant/analysis/csv.hpp"
#include "cvtplant/analysis/lle.hpp"
#include "cvtplant/analysis/rqa.hpp"

namespace cvtcli::analyze {

// A tool: its subcommand and what runs when it is chosen.
struct Tool {
  CLI::App* app;
  Action run;
};

// Options shared by every series tool.
struct SeriesArgs {
  std::string csv, column;
  double dt = 1.0;
  long discard = 0;
  bool json = false;
  int tau = -1, m = -1, theiler = -1;
  Caps caps;
};

void add_series_options(CLI::App* c, SeriesArgs& a, bool embedding);

// The column of a CSV, read with the memory cap (the file stops being read
// once it exceeds --max-memory-mb: an endless stream such as /dev/zero ends).
cvt::analysis::CsvColumn read_column(const std::string& path, const std::string& column, const Caps& caps);

// Bytes per sample the series tools hold at their peak: the column, its
// trimmed and z-scored copies, and the delay embedding and neighbour search
// of up to --m-max = 30 dimensions (measured peak RSS per sample in
// docs/cli.md#caps: 165 B at the default dimensions, 330 B at m = 30).
inline constexpr double kSeriesBytesPerSample = 512;

// Loads, trims and z-scores the column (docs/analysis.md#input). Every
// analysis works on the normalised series, as the seed does.
std::vector<double> load(const SeriesArgs& a, std::size_t min_points);

// The delay, Theiler window and dimension: the option's, else the estimate.
int pick_tau(const SeriesArgs& a, const std::vector<double>& x);
int pick_theiler(const SeriesArgs& a, const std::vector<double>& x);
int pick_m(const SeriesArgs& a, const std::vector<double>& x, int tau, int w);

nlohmann::json lle_json(const cvt::analysis::LleResult& r, const char* method, int m, int tau);
nlohmann::json rqa_json(const cvt::analysis::RqaResult& r, int m, int tau, const cvt::analysis::RqaOptions& o);
// `classify --json` fields (docs/analysis.md#cli).
nlohmann::json classification_json(const cvt::analysis::Classification& r);

// The series tools (cmd_analyze_series.cpp); add_rqa adds `recurrence` with is_png.
Tool add_ami(CLI::App* analyze);
Tool add_fnn(CLI::App* analyze);
Tool add_cao(CLI::App* analyze);
Tool add_lle(CLI::App* analyze);
Tool add_rqa(CLI::App* analyze, bool is_png);
Tool add_test01(CLI::App* analyze);
Tool add_classify(CLI::App* analyze);
// The scene, sweep and figure tools (cmd_analyze_scenes.cpp).
Tool add_trajectory(CLI::App* analyze);
Tool add_sweep(CLI::App* analyze);
Tool add_merge(CLI::App* analyze);
Tool add_figures(CLI::App* analyze);
Tool add_seed_section4(CLI::App* analyze);
Tool add_ripple(CLI::App* analyze);

}  // namespace cvtcli::analyze
