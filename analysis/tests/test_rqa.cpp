// Streaming RQA against the brute-force reference and hand-countable cases
// (docs/analysis.md#rqa).
#include <doctest/doctest.h>

#include "cvtplant/analysis/rqa.hpp"
#include "signals.hpp"

using namespace cvt::analysis;

namespace {
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
    const Embedding e2 = delay_embed(testsig::white_noise(1500), 2, 1);
    o.eps = 0.4;
    same(rqa(e2, o), rqa_naive(e2, o));
    const Embedding e3 = delay_embed(testsig::sine(1500, 33.3), 2, 8);
    o.eps = 0.1;
    same(rqa(e3, o), rqa_naive(e3, o));
  }
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
