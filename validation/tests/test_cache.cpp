// The reference-run cache (docs/validation.md#cache): its key changes with
// every input of the reference and with nothing else, and a stored run reads
// back bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>

#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/validation/cache.hpp"
#include "cvtplant/validation/errors.hpp"

using namespace cvt::validation;

namespace {

// Changes the `index`-th field that the list visits (counting from 0) to
// another valid value of its type.
struct Perturb {
  explicit Perturb(int i) : index(i) {}
  int index, seen = 0;
  std::string name;
  template <class X>
  void operator()(const cvt::ParamField& f, X& x) {
    if (seen++ != index) return;
    name = std::string(f.group) + "." + f.name;
    if constexpr (std::is_same_v<X, bool>) {
      x = !x;
    } else if constexpr (std::is_enum_v<X>) {
      x = static_cast<X>(static_cast<int>(x) == 0 ? 1 : 0);
    } else if constexpr (std::is_same_v<X, cvt::mbd::TimeProfile>) {
      x.points.emplace_back(x.points.empty() ? 0.0 : x.points.back().first + 1.0, 7.0);
    } else if constexpr (std::is_floating_point_v<X>) {
      x = x * (1.0 + 1e-15) + 1e-300;  // the smallest change the key must still see
    } else {
      x += 1;
    }
  }
};

int field_count() {
  cvt::mbd::MbdParams p;
  int n = 0;
  cvt::mbd::visit_mbd_params(p, [&](const cvt::ParamField&, auto&) { ++n; });
  return n;
}

// Seed case 1 with a short settle: the runs below need a valid entry, not
// a settled chain.
cvt::mbd::MbdParams short_seed_case() {
  cvt::mbd::MbdParams p = cvt::mbd::seed_case(1);
  p.settle_s = 0.02;
  return p;
}

// A run of t_end_s sampled every millisecond.
cvt::mbd::RunOptions sampled_run(double t_end_s) {
  cvt::mbd::RunOptions r;
  r.t_end_s = t_end_s;
  r.sample_s = 1e-3;
  return r;
}

std::string scratch_dir(const char* name) {
  const std::string d = (std::filesystem::temp_directory_path() / ("cvt_validation_" + std::string(name))).string();
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

TEST_SUITE("cache") {
  TEST_CASE("the key of a run changes with every field of MbdParams, even by one ulp") {
    const cvt::mbd::MbdParams base = cvt::mbd::seed_case(1);
    const cvt::mbd::RunOptions run;
    const std::string key = reference_key(base, run);
    CHECK(key == reference_key(base, run));
    const int n = field_count();
    CHECK(n > 40);
    std::set<std::string> keys{key};
    for (int i = 0; i < n; ++i) {
      cvt::mbd::MbdParams p = base;
      Perturb change(i);
      cvt::mbd::visit_mbd_params(p, change);
      INFO("field " << change.name);
      CHECK(keys.insert(reference_key(p, run)).second);
    }
  }

  TEST_CASE("the key changes with every run option but the step cap") {
    const cvt::mbd::MbdParams p = cvt::mbd::seed_case(2);
    const cvt::mbd::RunOptions base;
    const std::string key = reference_key(p, base);
    for (int i = 0; i < 9; ++i) {
      cvt::mbd::RunOptions r = base;
      Perturb change(i);
      cvt::mbd::visit_run_options(r, change);
      INFO("option " << change.name);
      if (change.name == ".max_steps")
        CHECK(reference_key(p, r) == key);
      else
        CHECK(reference_key(p, r) != key);
    }
  }

  TEST_CASE("key_hash is 64-bit FNV-1a") {
    // The published test vectors of FNV-1a 64.
    CHECK(key_hash("") == "cbf29ce484222325");
    CHECK(key_hash("a") == "af63dc4c8601ec8c");
    CHECK(key_hash("foobar") == "85944171f73967e8");
  }

  TEST_CASE("a run is stored, read back bit for bit, and rerun when its files are damaged") {
    const std::string dir = scratch_dir("cache");
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r = sampled_run(0.02);
    const ReferenceRun first = reference_run(p, r, dir);
    CHECK_FALSE(first.from_cache);
    REQUIRE(first.series.size() == 21u);
    CHECK(first.failure.empty());
    const ReferenceRun second = reference_run(p, r, dir);
    CHECK(second.from_cache);
    for (const auto c : kSeriesColumns) {
      const auto& a = first.series.*c;
      const auto& b = second.series.*c;
      REQUIRE(a.size() == b.size());
      for (std::size_t i = 0; i < a.size(); ++i)
        if (!(std::isnan(a[i]) && std::isnan(b[i]))) CHECK(a[i] == b[i]);
    }
    CHECK(first.sheave1_m == second.sheave1_m);
    // A truncated CSV (a full disk) is no hit: the run is made again.
    const std::string base = dir + "/" + key_hash(reference_key(p, r));
    std::filesystem::resize_file(base + ".csv", 200);
    CHECK_FALSE(reference_run(p, r, dir).from_cache);
    CHECK(reference_run(p, r, dir).from_cache);
    // Another input is another file.
    p.friction.mu0 *= 1.01;
    CHECK_FALSE(reference_run(p, r, dir).from_cache);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("an entry is checked: each kind of damage is found and named, and the run is made again") {
    const std::string dir = scratch_dir("cache_checks");
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r = sampled_run(0.01);
    const ReferenceRun made = reference_run(p, r, dir);
    REQUIRE(made.series.size() == 11u);
    CHECK(made.cache_problem.empty());
    const std::string key = reference_key(p, r);
    const std::string base = dir + "/" + key_hash(key);
    std::string key_file, csv_file;
    format_cache_entry(made, key, key_file, csv_file);
    // What reference_run stored is what format_cache_entry makes.
    {
      std::ifstream k(base + ".key"), c(base + ".csv");
      std::stringstream ks, cs;
      ks << k.rdbuf();
      cs << c.rdbuf();
      CHECK(ks.str() == key_file);
      CHECK(cs.str() == csv_file);
    }
    ReferenceRun back;
    REQUIRE(parse_cache_entry(key_file, csv_file, key, r, "E", back) == "");
    CHECK(back.series.size() == 11u);
    CHECK(back.steps == made.steps);
    CHECK(back.ledger_residual_rel == made.ledger_residual_rel);
    // The csv with a change, and the key file with that change's checksum:
    // the cells and rows are checked for themselves, not only the sum.
    const auto resummed = [&](const std::string& csv) {
      std::string k = key_file;
      const std::size_t at = k.find("entry csv_fnv1a64 ") + 18;
      k.replace(at, 16, key_hash(csv));
      return k;
    };
    const auto problem = [&](const std::string& csv, const std::string& kf) {
      ReferenceRun out;
      return parse_cache_entry(kf, csv, key, r, "E", out);
    };
    const std::size_t row3 = [&] {
      std::size_t at = 0;
      for (int i = 0; i < 3; ++i) at = csv_file.find('\n', at) + 1;
      return at;
    }();  // the start of the third data row (after the header and two rows)
    const std::size_t row3_end = csv_file.find('\n', row3);
    const std::string first_cell = csv_file.substr(row3, csv_file.find(',', row3) - row3);
    const auto with_row3 = [&](const std::string& line) {
      return csv_file.substr(0, row3) + line + csv_file.substr(row3_end);
    };
    const std::string row3_text = csv_file.substr(row3, row3_end - row3);
    const std::size_t second = row3_text.find(',') + 1;
    const std::string omega = row3_text.substr(second, row3_text.find(',', second) - second);
    // A cut CSV (a full disk, a killed writer): the checksum no longer fits.
    CHECK(problem(csv_file.substr(0, csv_file.size() - 40), key_file).find("E.csv: its bytes do not match") == 0);
    // Rows dropped at a row boundary, with a consistent key file: short of the span.
    {
      std::string cut = csv_file.substr(0, row3);
      std::string kf = resummed(cut);
      kf.replace(kf.find("entry rows 11"), 13, "entry rows 2");
      CHECK(problem(cut, kf).find("E.csv: 2 rows where the run's span has 11 samples") == 0);
    }
    // A non-numeric cell, a ragged row, nan and 1e308 where not allowed.
    std::string bad = with_row3(first_cell + ",abc" + row3_text.substr(row3_text.find(',', second)));
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: 'abc' is not a number") == 0);
    bad = with_row3(row3_text + ",1");
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: not 15 cells") == 0);
    bad = with_row3(row3_text.substr(0, row3_text.rfind(',')));
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: not 15 cells") == 0);
    bad = with_row3(first_cell + ",nan" + row3_text.substr(row3_text.find(',', second)));
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: 'nan' is out of range") == 0);
    bad = with_row3(first_cell + ",1e308" + row3_text.substr(row3_text.find(',', second)));
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: '1e308' is out of range") == 0);
    // A row at another time than the run samples.
    bad = with_row3("0.0025" + row3_text.substr(row3_text.find(',')));
    CHECK(problem(bad, resummed(bad)).find("E.csv: row 3: t = 0.0025 s") == 0);
    // The key file: another run's key, no checksum.
    CHECK(problem(csv_file, "x" + key_file).find("E.key: the stored key is not this run's") == 0);
    CHECK(problem(csv_file, key).find("E.key: no row count") == 0);
    // The driver's slip may be nan (no bolt in the wrap): still an entry.
    {
      std::string ok = csv_file;
      const std::size_t slip = [&] {
        std::size_t at = row3;
        for (int i = 0; i < 5; ++i) at = ok.find(',', at) + 1;
        return at;
      }();
      ok.replace(slip, ok.find(',', slip) - slip, "nan");
      CHECK(problem(ok, resummed(ok)) == "");
    }
    CHECK(omega.size() > 0);
    // Through reference_run: a damaged entry is named and run again, and
    // the new entry is whole.
    std::ofstream(base + ".csv") << bad;
    const ReferenceRun again = reference_run(p, r, dir);
    CHECK_FALSE(again.from_cache);
    CHECK(again.cache_problem.find(base + ".csv: ") == 0);
    CHECK(again.series.t_s == made.series.t_s);
    CHECK(again.series.omega1_rad_s == made.series.omega1_rad_s);
    const ReferenceRun hit = reference_run(p, r, dir);
    CHECK(hit.from_cache);
    CHECK(hit.cache_problem.empty());
    CHECK(std::isnan(hit.cpu_s));  // nothing was spent now
    CHECK(hit.steps == made.steps);
    // No temporary is left beside the entry.
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      ++files;
      CHECK(e.path().filename().string()[0] != '.');
    }
    CHECK(files == 2);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("an entry has fifteen columns; the slips and the geometric ratio may be nan, nothing else") {
    const std::string dir = scratch_dir("cache_columns");
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r = sampled_run(0.005);
    const ReferenceRun made = reference_run(p, r, dir);
    const std::string key = reference_key(p, r);
    std::string key_file, csv_file;
    format_cache_entry(made, key, key_file, csv_file);
    const std::string header = csv_file.substr(0, csv_file.find('\n'));
    CHECK(header ==
          "t_s,omega1_rad_s,omega2_rad_s,F_ax1_N,torque_driver_Nm,slip1_m_s,wrap_slip1_m_s,ratio_geom,F_ax2_N,"
          "clamp1_N,clamp2_N,tau_in_Nm,tau_load_Nm,sheave1_m,sheave2_m");
    // The second data row with cell `col` replaced by `text`, the checksum fixed.
    const auto with_cell = [&](int col, const std::string& text) {
      std::size_t at = csv_file.find('\n', csv_file.find('\n') + 1) + 1;
      for (int i = 0; i < col; ++i) at = csv_file.find(',', at) + 1;
      std::size_t end = csv_file.find_first_of(",\n", at);
      std::string csv = csv_file.substr(0, at) + text + csv_file.substr(end);
      std::string k = key_file;
      k.replace(k.find("entry csv_fnv1a64 ") + 18, 16, key_hash(csv));
      ReferenceRun out;
      return parse_cache_entry(k, csv, key, r, "E", out);
    };
    for (int col = 0; col < 15; ++col) {
      INFO("column " << col);
      const bool may_be_nan = col == 5 || col == 6 || col == 7;
      if (may_be_nan)
        CHECK(with_cell(col, "nan") == "");
      else
        CHECK(with_cell(col, "nan").find("E.csv: row 2: 'nan' is out of range") == 0);
      CHECK(with_cell(col, "2e12").find("E.csv: row 2: '2e12' is out of range") == 0);
    }
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("cached_run and store_run: a run under any key, its failure kept, a damaged entry named") {
    const std::string dir = scratch_dir("cache_store");
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r = sampled_run(0.005);
    const std::string ref_dir = scratch_dir("cache_store_ref");
    const ReferenceRun run = reference_run(p, r, ref_dir);
    std::filesystem::remove_all(ref_dir);
    // A manoeuvre's run: its own key, rows cut short by a stop that is no
    // failure, then one with a failure.
    const std::string key = "a manoeuvre's key\nmanoeuvre.t_end_s 0.005\n";
    std::string problem = "x";
    CHECK_FALSE(cached_run(key, dir, &problem).has_value());
    CHECK(problem.empty());  // no entry: a miss, no problem
    ReferenceRun cut = run;
    for (const auto c : kSeriesColumns) (cut.series.*c).resize(3);
    cut.sheave1_m.resize(3);
    cut.sheave2_m.resize(3);
    cut.failure = "the reference stopped at t = 0.002 s (ledger)";
    REQUIRE(store_run(key, dir, cut));
    const auto hit = cached_run(key, dir, &problem);
    REQUIRE(hit.has_value());
    CHECK(problem.empty());
    CHECK(hit->from_cache);
    CHECK(std::isnan(hit->cpu_s));
    CHECK(hit->failure == cut.failure);
    CHECK(hit->steps == cut.steps);
    CHECK(hit->series.t_s == cut.series.t_s);
    CHECK(hit->series.clamp1_N == cut.series.clamp1_N);
    CHECK(hit->series.tau_load_Nm == cut.series.tau_load_Nm);
    CHECK(hit->sheave2_m == cut.sheave2_m);
    // Stored again without the failure: the failure is gone with it.
    cut.failure.clear();
    REQUIRE(store_run(key, dir, cut));
    CHECK(cached_run(key, dir)->failure.empty());
    // Damaged: no hit, and the problem names the file.
    const std::string base = dir + "/" + key_hash(key);
    std::filesystem::resize_file(base + ".csv", 300);
    CHECK_FALSE(cached_run(key, dir, &problem).has_value());
    CHECK(problem.find(base + ".csv: its bytes do not match") == 0);
    // A run the checks would refuse (a driver speed beyond any the reference
    // reaches) is used by the caller but not stored.
    ReferenceRun wild = run;
    wild.series.omega1_rad_s[1] = std::nan("");
    CHECK_FALSE(store_run("wild\n", dir, wild));
    CHECK_FALSE(std::filesystem::exists(dir + "/" + key_hash("wild\n") + ".key"));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a run that its step cap ended is used but not stored") {
    const std::string dir = scratch_dir("cache_cap");
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r;
    r.t_end_s = 0.02;
    r.max_steps = 200;  // about 500 are needed
    const ReferenceRun capped = reference_run(p, r, dir);
    CHECK(capped.failure.find("step cap") != std::string::npos);
    CHECK(capped.series.size() >= 2u);
    CHECK(capped.series.size() < 21u);
    CHECK(std::filesystem::is_empty(dir));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a cache directory that cannot be written is bad input") {
    cvt::mbd::MbdParams p = short_seed_case();
    cvt::mbd::RunOptions r;
    r.t_end_s = 0.005;
    CHECK_THROWS_AS(reference_run(p, r, "/proc/no/such/dir"), InputError);
  }
}
