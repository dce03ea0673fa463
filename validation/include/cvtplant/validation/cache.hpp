#pragma once
// Multibody reference runs kept on disk by their inputs
// (docs/validation.md#cache): the key is every field of the reference's
// parameters and run options (cvt::mbd::visit_mbd_params,
// visit_run_options) and the reference's version, so two runs with equal
// keys are the same run.
#include <optional>
#include <string>
#include <vector>

#include "cvtplant/mbd/params.hpp"
#include "cvtplant/mbd/run.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// The text that identifies a reference run: one line per field, "group.name
// value" with every double to 17 significant digits, and a head line with
// the reference's version (cvt::mbd::kReferenceVersion) and the cache's
// format. Caps on work (RunOptions::max_steps) are left out.
std::string reference_key(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r);

// 64-bit FNV-1a of the key, as 16 hex digits (the cache file's name).
std::string key_hash(const std::string& key);

struct ReferenceRun {
  Series series;
  // Movable sheave openings [m] per sample (docs/mbd.md#clamped-sheaves).
  std::vector<double> sheave1_m, sheave2_m;
  bool from_cache = false;
  double cpu_s = 0, wall_s = 0, ledger_residual_rel = 0;
  long long steps = 0;
  // A run that stopped early (a link left the drive, the ledger, the step
  // cap): the reason, and `series` holds the samples up to then.
  std::string failure;
};

// The reference run for (p, r): read from `cache_dir` if a run with the same
// key is there, else run (on_progress gets the simulated time now and then)
// and stored. A run that stops early is kept and stored with its reason;
// one that makes fewer than two samples throws RunError; a cache that cannot
// be written throws InputError.
ReferenceRun reference_run(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r, const std::string& cache_dir,
                           const cvt::mbd::ProgressSink& on_progress = {});

// The run stored under `key` in cache_dir, if it is there whole (its key
// file equal to `key` byte for byte, its CSV readable to the end).
std::optional<ReferenceRun> cached_run(const std::string& key, const std::string& cache_dir);
// Stores a run under `key` (the key file last, so a run cut short is never
// a hit); throws InputError if the cache cannot be written.
void store_run(const std::string& key, const std::string& cache_dir, const ReferenceRun& run);
// Appends one of the reference's samples to a run's series and sheave columns.
void append_sample(ReferenceRun& run, const cvt::mbd::Sample& s);

// The first sample time at which the reference's movable sheave (0 driver,
// 1 driven) is within 0.1 mm of its end stop (the chain at a ratio limit: the
// stop, not only the clamping force, then holds the sheave), or -1: never.
double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m);

}  // namespace cvt::validation
