#pragma once
// Parameter sweeps over a scene (docs/analysis.md#sweeps): Lyapunov spectrum
// and bifurcation data (local maxima of one state) on a 1-D or 2-D grid.
// Parallel over local cores (std::thread) and shardable: point k belongs to
// shard i of N iff k % N == i, so `--shard i/N` jobs can run as a Slurm array
// or under GNU parallel and be merged afterwards.
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/analysis/systems.hpp"

namespace cvt::analysis {

struct SweepAxis {
  std::string param;
  double lo = 0, hi = 0;
  int n = 1;
  double value(int k) const { return n <= 1 ? lo : lo + (hi - lo) * k / (n - 1); }
};

// Parses "name=lo:hi:n" (n >= 1). Throws InputError.
SweepAxis parse_axis(const std::string& spec);

struct SweepSpec {
  std::string scene;              // name written to the output
  const Model* model = nullptr;   // the model swept; nullptr: find_model(scene)
  Params overrides;
  std::vector<double> x0;  // empty: scene default
  SweepAxis a1;
  bool has_a2 = false;
  SweepAxis a2;
  BenettinOptions benettin;
  int bif_state = 0;     // state index whose local maxima are recorded
  double t_peaks = 50;   // time (or iterations) after the spectrum run used for peaks
  int max_peaks = 64;
  long total() const { return static_cast<long>(a1.n) * (has_a2 ? a2.n : 1); }
  // One-line description written as the first comment line of every shard,
  // so the merge step can refuse shards from different sweeps.
  std::string signature() const;
};

struct SweepPoint {
  long index = 0;
  double p1 = 0, p2 = 0;
  std::vector<double> exponents, ci95;
  std::vector<double> peaks;
  std::string error;  // non-empty: this point failed (e.g. diverged)
};

// Runs the points of shard `shard_i` of `shard_n` on `jobs` threads
// (jobs <= 0: hardware concurrency). Results sorted by index. `on_point`,
// if set, is called after each point with (points done, points of the
// shard), from the worker threads.
std::vector<SweepPoint> run_sweep(const SweepSpec& spec, int shard_i, int shard_n, int jobs,
                                  const std::function<void(long done, long total)>& on_point = {});

void write_sweep_csv(std::FILE* f, const SweepSpec& spec, int dim, const std::vector<SweepPoint>& pts);

// Merges shard files: same signature, every index 0..total-1 exactly once.
// Throws InputError naming the offending file / missing indices.
void merge_sweep_csv(const std::vector<std::string>& shards, std::FILE* out);

}  // namespace cvt::analysis
