// Sweeps and their merge (docs/analysis.md#sweeps): peaks, axis labels, and
// shard files treated as input to be checked.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/sweep.hpp"

using namespace cvt::analysis;

namespace {

SweepSpec logistic_sweep(double lo, double hi, int n) {
  SweepSpec sp;
  sp.scene = "logistic";
  const Model& m = find_model("logistic");
  sp.benettin = m.defaults;
  sp.benettin.t_end = 2000;
  sp.t_peaks = 400;
  sp.a1.param = "r";
  sp.a1.lo = lo;
  sp.a1.hi = hi;
  sp.a1.n = n;
  return sp;
}

std::string temp_path(const char* name) { return std::string("cvt_sweep_test_") + name; }

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

// merge_sweep_csv into a scratch file; the message of its InputError, or "".
std::string merge_error(const std::vector<std::string>& shards) {
  std::FILE* out = std::tmpfile();
  std::string err;
  try {
    merge_sweep_csv(shards, out);
  } catch (const InputError& e) {
    err = e.what();
  }
  std::fclose(out);
  return err;
}

}  // namespace

TEST_CASE("sweep: the logistic map's peaks are iterates, never above the map's maximum r/4") {
  // A parabola through three iterates is no refinement for a map: it put the
  // peaks at r = 4 up to 1.02, above the largest value the map can take.
  const SweepSpec sp = logistic_sweep(3.6, 4.0, 5);
  const std::vector<SweepPoint> pts = run_sweep(sp, 0, 1, 1);
  REQUIRE(pts.size() == 5);
  for (const SweepPoint& p : pts) {
    CAPTURE(p.p1);
    REQUIRE(p.error.empty());
    REQUIRE(!p.peaks.empty());
    for (double v : p.peaks) {
      CHECK(v <= p.p1 / 4);
      CHECK(v > 0);
    }
  }
  // At r = 4 the orbit comes within a few 1e-3 of 1 in 400 iterations.
  double top = 0;
  for (double v : pts.back().peaks) top = std::max(top, v);
  CHECK(top > 0.99);
}

TEST_CASE("sweep: both axes on one parameter, or an axis also fixed by --param, are refused") {
  SweepSpec sp = logistic_sweep(3.6, 4.0, 2);
  sp.has_a2 = true;
  sp.a2 = sp.a1;
  sp.a2.lo = 3.0;
  CHECK_THROWS_WITH_AS(run_sweep(sp, 0, 1, 1), doctest::Contains("two different parameters"), InputError);
  SweepSpec sq = logistic_sweep(3.6, 4.0, 2);
  sq.overrides["r"] = 3.9;
  CHECK_THROWS_WITH_AS(run_sweep(sq, 0, 1, 1), doctest::Contains("'r' is swept"), InputError);
}

TEST_CASE("merge: shard files are validated, a forged total is refused at once") {
  const std::string head = "index,r,p2,lambda1,ci1,n_peaks,peaks,error\n";
  const std::string sig = "# cvtplant sweep scene=logistic a1=r:3.6:4:2 x0= dt=1 t_transient=1000 t_end=2000 state=0";
  const std::string row0 = "0,3.6,0,0.18,0.01,1,0.9,\n", row1 = "1,4,0,0.69,0.01,1,0.99,\n";
  const std::string good = temp_path("good.csv"), forged = temp_path("forged.csv"), big = temp_path("big.csv"),
                    range = temp_path("range.csv"), cols = temp_path("cols.csv"), junk = temp_path("junk.csv");
  write_file(good, sig + " total=2\n" + head + row0 + row1);
  CHECK(merge_error({good}) == "");

  // A total that disagrees with the axes: refused before any point is read
  // (walking 0..total-1 would take hours).
  write_file(forged, sig + " total=1000000000000\n" + head + row0 + row1);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(merge_error({forged}).find("declares total=1000000000000 but its axes give 2 points") != std::string::npos);
  write_file(junk, sig + " total=2x\n" + head + row0 + row1);
  CHECK(merge_error({junk}).find("malformed total") != std::string::npos);

  // The largest consistent sweep (1e5 x 1e5 points) with one row: the missing
  // points are counted, not walked.
  write_file(big,
             "# cvtplant sweep scene=logistic a1=r:3:4:100000 a2=q:0:1:100000 x0= dt=1 total=10000000000\n" + head +
                 row0);
  CHECK(merge_error({big}).find("9999999999 of 10000000000 points missing (first: 1,2,3") != std::string::npos);
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5));

  write_file(range, sig + " total=2\n" + head + row0 + "7,4,0,0.69,0.01,1,0.99,\n");
  CHECK(merge_error({range}).find("point 7 is outside 0..1") != std::string::npos);
  write_file(cols, sig + " total=2\n" + head + row0 + "1,4,0,0.69\n");
  CHECK(merge_error({cols}).find("4 columns, the header has 8") != std::string::npos);
  for (const auto& p : {good, forged, big, range, cols, junk}) std::remove(p.c_str());
}
