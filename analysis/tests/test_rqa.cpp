// Streaming RQA against the brute-force reference and hand-countable cases
// (docs/analysis.md#rqa).
#include <doctest/doctest.h>

#include <cmath>
#include <map>

#include "cvtplant/analysis/rqa.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {
// The measures straight from a stored N x N matrix, by definition
// (docs/analysis.md#rqa): diagonal lines of the upper triangle, vertical
// lines of every column, the band |i-j| <= w left out.
RqaResult from_matrix(const Embedding& e, double eps, int w, int lmin, int vmin) {
  const long n = static_cast<long>(e.n);
  std::vector<char> R(static_cast<std::size_t>(n * n), 0);
  std::uint64_t rec = 0;
  for (long i = 0; i < n; ++i)
    for (long j = 0; j < n; ++j) {
      double s = 0;
      for (int d = 0; d < e.m; ++d) s += (e.row(i)[d] - e.row(j)[d]) * (e.row(i)[d] - e.row(j)[d]);
      const bool r = std::labs(i - j) > w && s <= eps * eps;
      R[static_cast<std::size_t>(i * n + j)] = r;
      rec += r;
    }
  const auto at = [&](long i, long j) {
    return i >= 0 && j >= 0 && i < n && j < n && R[static_cast<std::size_t>(i * n + j)];
  };
  std::map<long, long> diag, vert;  // length -> count
  for (long k = w + 1; k < n; ++k)
    for (long i = 0; i + k < n; ++i)
      if (at(i, i + k) && !at(i - 1, i + k - 1)) {
        long l = 1;
        while (at(i + l, i + k + l)) ++l;
        ++diag[l];
      }
  for (long j = 0; j < n; ++j)
    for (long i = 0; i < n; ++i)
      if (at(i, j) && !at(i - 1, j)) {
        long l = 1;
        while (at(i + l, j)) ++l;
        ++vert[l];
      }
  RqaResult r;
  r.recurrences = rec;
  const double m = static_cast<double>(n - (w + 1));
  r.pairs = static_cast<std::uint64_t>(m * (m + 1));
  r.rr = static_cast<double>(rec) / static_cast<double>(r.pairs);
  // Points on all lines, points on lines of at least `lmin`, those lines, the longest.
  struct Tally {
    double all = 0, in_lines = 0, lines = 0;
    long longest = 0;
  };
  const auto tally = [](const std::map<long, long>& h, int lmin) {
    Tally t;
    for (auto [l, c] : h) {
      t.all += static_cast<double>(l * c);
      if (l < lmin) continue;
      t.in_lines += static_cast<double>(l * c);
      t.lines += static_cast<double>(c);
      t.longest = l;
    }
    return t;
  };
  const Tally d = tally(diag, lmin), v = tally(vert, vmin);
  r.det = d.in_lines / d.all;
  r.l_mean = d.in_lines / d.lines;
  r.lmax = d.longest;
  for (auto [l, c] : diag)
    if (l >= lmin) r.entr -= c / d.lines * std::log(c / d.lines);
  r.lam = v.in_lines / v.all;
  r.tt = v.in_lines / v.lines;
  r.vmax = v.longest;
  return r;
}

void same(const RqaResult& a, const RqaResult& b) {
  CHECK(a.recurrences == b.recurrences);
  CHECK(a.pairs == b.pairs);
  CHECK(a.rr == doctest::Approx(b.rr).epsilon(1e-15));
  CHECK(a.det == doctest::Approx(b.det).epsilon(1e-15));
  CHECK(a.l_mean == doctest::Approx(b.l_mean).epsilon(1e-15));
  CHECK(a.lmax == b.lmax);
  CHECK(a.entr == doctest::Approx(b.entr).epsilon(1e-12));
  CHECK(a.lam == doctest::Approx(b.lam).epsilon(1e-15));
  CHECK(a.tt == doctest::Approx(b.tt).epsilon(1e-15));
  CHECK(a.vmax == b.vmax);
}
}  // namespace

TEST_CASE("streaming RQA equals brute force (Lorenz, noise, sine; several Theiler windows)") {
  for (int w : {0, 1, 5}) {
    RqaOptions o;
    o.theiler = w;
    o.eps = 0.3;
    const auto lz = testsig::lorenz_x(2000);
    std::vector<double> z(lz.size());
    for (std::size_t i = 0; i < z.size(); ++i) z[i] = lz[i] / 8.0;
    const Embedding e1 = delay_embed(z, 3, 18);
    same(rqa(e1, o), rqa_naive(e1, o));
    same(rqa_kdtree(e1, o), rqa_naive(e1, o));
    const Embedding e2 = delay_embed(testsig::white_noise(1500), 2, 1);
    o.eps = 0.4;
    same(rqa(e2, o), rqa_naive(e2, o));
    const Embedding e3 = delay_embed(testsig::sine(1500, 33.3), 2, 8);
    o.eps = 0.1;
    same(rqa(e3, o), rqa_naive(e3, o));
  }
}

TEST_CASE("grid RQA equals the k-d tree method and the stored matrix (m = 1..6, radii from one cell to all)") {
  const auto lz = testsig::lorenz_x(5000);
  std::vector<double> z(lz.size());
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = lz[i] / 8.0;
  // m = 1, 2 use fewer grid axes than 3; m = 4, 6 check coordinates the grid
  // does not index. eps 1e-9 forces the finest grid; 50 puts all in one cell.
  for (int m : {1, 2, 3, 4, 6})
    for (double eps : {1e-9, 0.05, 0.3, 50.0})
      if (eps < 50.0 || m == 2)
        for (int w : {0, 3}) {
          CAPTURE(m);
          CAPTURE(eps);
          CAPTURE(w);
          RqaOptions o;
          o.eps = eps;
          o.theiler = w;
          const Embedding e = delay_embed(z, m, 9);
          const RqaResult g = rqa(e, o);
          same(g, rqa_kdtree(e, o));
          if (eps == 0.3 && (m == 1 || m == 3)) {
            const Embedding small = delay_embed(std::vector<double>(z.begin(), z.begin() + 1500), m, 9);
            RqaOptions os = o;
            os.lmin = 3;
            os.vmin = 2;
            same(rqa(small, os), from_matrix(small, eps, w, os.lmin, os.vmin));
          }
        }
}

TEST_CASE("grid RQA of a constant series: every pair recurs at eps 0, as by the k-d tree and brute force") {
  const Embedding e = delay_embed(std::vector<double>(600, 2.5), 3, 4);
  RqaOptions o;
  o.target_rr = 0.05;  // every sampled distance is 0, so the radius is 0
  o.theiler = 1;
  const RqaResult g = rqa(e, o);
  same(g, rqa_kdtree(e, o));
  same(g, rqa_naive(e, o));
  CHECK(g.eps == 0.0);
  CHECK(g.rr == doctest::Approx(1.0));
}

TEST_CASE("RQA reports progress from 0 to 1, never backwards") {
  RqaOptions o;
  o.eps = 0.2;
  std::vector<double> seen;
  o.progress = [&](double done, double total) { seen.push_back(done / total); };
  rqa(delay_embed(testsig::sine(3000, 41.0), 2, 10), o);
  REQUIRE(seen.size() >= 2);
  CHECK(seen.front() == 0.0);
  CHECK(seen.back() == 1.0);
  for (std::size_t i = 1; i < seen.size(); ++i) CHECK(seen[i] >= seen[i - 1]);
}

TEST_CASE("RQA conventions on a hand-countable series") {
  // Scalar series 0 0 0 5 0 0 0 (m=1): points {0,1,2,4,5,6} are mutually
  // recurrent (distance 0 <= eps), point 3 recurs with nobody.
  const std::vector<double> x{0, 0, 0, 5, 0, 0, 0};
  const Embedding e = delay_embed(x, 1, 1);
  RqaOptions o;
  o.eps = 0.5;
  o.theiler = 0;  // only the line of identity excluded
  const RqaResult r = rqa(e, o);
  // Upper triangle: 6 points -> 15 pairs; eligible pairs (w=0): 21.
  CHECK(r.recurrences == 30);
  CHECK(r.pairs == 42);
  CHECK(r.rr == doctest::Approx(15.0 / 21.0));
  // Upper-triangle diagonals: k=1: (0,1),(1,2) run 2 | (4,5),(5,6) run 2;
  // k=2: (0,2) | (4,6); k=3: (1,4),(2,5) run 2; k=4: (0,4),(1,5),(2,6) run 3;
  // k=5: (0,5),(1,6) run 2; k=6: (0,6). Lines >= 2: 2,2,2,3,2 = 11 of 15 points.
  CHECK(r.det == doctest::Approx(11.0 / 15.0));
  CHECK(r.lmax == 3);
  CHECK(r.l_mean == doctest::Approx(11.0 / 5.0));
  // The `<=` rule: eps exactly equal to the distance counts.
  RqaOptions tight = o;
  tight.eps = 5.0;
  CHECK(rqa(e, tight).rr == doctest::Approx(1.0));
  // A wider Theiler window removes the short diagonals: w=1 drops k=1.
  RqaOptions w1 = o;
  w1.theiler = 1;
  const RqaResult r1 = rqa(e, w1);
  CHECK(r1.recurrences == 2 * 11);
  CHECK(r1.pairs == 2 * 15);
}

TEST_CASE("RQA separates determinism from noise") {
  RqaOptions o;
  o.target_rr = 0.02;
  o.theiler = 1;
  const RqaResult s = rqa(delay_embed(testsig::sine(4000, 37.3), 2, 9), o);
  // m=3, tau=1: lines up to length 3 come from shared coordinates alone.
  o.lmin = default_lmin(3, 1);
  CHECK(o.lmin == 3);
  const RqaResult n = rqa(delay_embed(testsig::white_noise(4000), 3, 1), o);
  CHECK(s.rr == doctest::Approx(0.02).epsilon(0.25));
  CHECK(n.rr == doctest::Approx(0.02).epsilon(0.25));
  CHECK(s.det > 0.95);
  CHECK(n.det < 0.3);
}
