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
  // The work of this call: NaN when the run came from the cache (nothing
  // was measured now).
  double cpu_s = 0, wall_s = 0;
  // The run's, whether made now or stored with it.
  double ledger_residual_rel = 0;
  long long steps = 0;
  // A run that stopped early (a link left the drive, the ledger, the step
  // cap): the reason, and `series` holds the samples up to then.
  std::string failure;
  // An entry with this run's key that failed its checks and was replaced
  // by a new run: "reference-cache/<hash>.csv: row 17: 'x' is not a number".
  std::string cache_problem;
};

// The reference run for (p, r): read from `cache_dir` if an entry with the
// same key is there and passes its checks (parse_cache_entry), else run
// (on_progress gets the simulated time now and then) and stored. A run that
// stops early is kept and stored with its reason, unless it was the step
// cap that stopped it (the cap is not part of the key: a larger one would
// go further); one that makes fewer than two samples throws RunError; a
// cache that cannot be written throws InputError. The entry's files are
// written whole by a temporary and a rename, the key last, so a run killed
// in the middle, or two runs at once, never leave half an entry.
ReferenceRun reference_run(const cvt::mbd::MbdParams& p, const cvt::mbd::RunOptions& r, const std::string& cache_dir,
                           const cvt::mbd::ProgressSink& on_progress = {});

// The checks of a cache entry (docs/validation.md#cache): `key_file` must be
// `key` followed by the entry's lines (its row count, the FNV-1a 64 of the
// CSV's bytes, the run's steps and ledger residual, its failure if any);
// `csv_file` must have that checksum, the cache's header, and the recorded
// number of rows (at least one) of fifteen numbers each (the columns of
// kSeriesColumns, then the two sheave openings; finite, |v| <= 1e12; the
// two slip columns and the geometric ratio may be nan: no bolt in a wrap),
// their times increasing. Returns "" and fills `out` when the entry passes,
// else the first problem found (naming "<name>.key" or "<name>.csv" and the
// row). Never throws on any bytes.
std::string parse_cache_entry(const std::string& key_file, const std::string& csv_file, const std::string& key,
                              const std::string& name, ReferenceRun& out);
// The same, and the rows on the sample times of a run made with options r:
// t = 0, sample_s, ... up to t_end_s, every one of them unless the entry
// records a failure (then at least two).
std::string parse_cache_entry(const std::string& key_file, const std::string& csv_file, const std::string& key,
                              const cvt::mbd::RunOptions& r, const std::string& name, ReferenceRun& out);

// The files of an entry for `run`: the key file's text and the CSV's, as
// store_run writes them.
void format_cache_entry(const ReferenceRun& run, const std::string& key, std::string& key_file,
                        std::string& csv_file);

// The run stored under `key` in cache_dir, if its entry is there and passes
// its checks (parse_cache_entry; its cpu_s and wall_s NaN: nothing was spent
// now). An entry that is there but fails a check is no hit, and `problem`
// (if given) names the check; else it is left empty.
std::optional<ReferenceRun> cached_run(const std::string& key, const std::string& cache_dir,
                                       std::string* problem = nullptr);
// Stores a run under `key`, its failure (if any) with it: both files whole
// by a temporary and a rename, the key last, so a run cut short is never a
// hit. A run the checks would refuse is not stored (false). Throws
// InputError if the cache directory cannot be used, RunError if a write
// fails.
bool store_run(const std::string& key, const std::string& cache_dir, const ReferenceRun& run);
// Appends one of the reference's samples to a run's series and sheave columns.
void append_sample(ReferenceRun& run, const cvt::mbd::Sample& s);

// The first sample time at which the reference's movable sheave (0 driver,
// 1 driven) is within 0.1 mm of its end stop (the chain at a ratio limit: the
// stop, not only the clamping force, then holds the sheave), or -1: never.
double first_at_stop_s(const ReferenceRun& r, int sheave, double sheave_stop_m);

}  // namespace cvt::validation
