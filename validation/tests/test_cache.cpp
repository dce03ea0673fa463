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
    cvt::mbd::MbdParams p = cvt::mbd::seed_case(1);
    p.settle_s = 0.02;
    cvt::mbd::RunOptions r;
    r.t_end_s = 0.02;
    r.sample_s = 1e-3;
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

  TEST_CASE("a cache directory that cannot be written is bad input") {
    cvt::mbd::MbdParams p = cvt::mbd::seed_case(1);
    p.settle_s = 0.02;
    cvt::mbd::RunOptions r;
    r.t_end_s = 0.005;
    CHECK_THROWS_AS(reference_run(p, r, "/proc/no/such/dir"), InputError);
  }
}
