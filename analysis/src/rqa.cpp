#include "cvtplant/analysis/rqa.hpp"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "cvtplant/analysis/errors.hpp"
#include "cvtplant/analysis/neighbours.hpp"

namespace cvt::analysis {

double radius_for_rr(const Embedding& e, double rr, int theiler) {
  if (!(rr > 0 && rr < 1)) throw InputError("rqa: target recurrence rate must be in (0, 1)");
  if (e.n < static_cast<std::size_t>(2 * theiler + 10)) throw InputError("rqa: too few points for the Theiler window");
  std::mt19937_64 gen(12345);
  std::uniform_int_distribution<std::size_t> pick(0, e.n - 1);
  std::vector<double> d;
  const std::size_t samples = 200000;
  d.reserve(samples);
  while (d.size() < samples) {
    const std::size_t i = pick(gen), j = pick(gen);
    if (std::labs(static_cast<long>(i) - static_cast<long>(j)) <= theiler) continue;
    d.push_back(euclid(e.row(i), e.row(j), e.m));
  }
  const std::size_t k = std::min(d.size() - 1, static_cast<std::size_t>(rr * static_cast<double>(d.size())));
  std::nth_element(d.begin(), d.begin() + k, d.end());
  return d[k];
}

namespace {

// Line-length histograms (docs/analysis.md#rqa-streaming).
struct Histograms {
  std::vector<std::uint64_t> diag, vert;
  explicit Histograms(std::size_t n) : diag(n + 1, 0), vert(n + 1, 0) {}
};

// Kept by the k-d tree reference: runs per diagonal offset k = j - i > w
// (upper triangle; the lower one is its mirror) and, by symmetry, vertical
// lines of column i as the runs of consecutive j in full row i.
struct LineCounter {
  std::vector<std::int32_t> run, last_row;
  Histograms& h;
  LineCounter(std::size_t n, Histograms& hist) : run(n + 1, 0), last_row(n + 1, -2), h(hist) {}

  void diag_point(std::size_t i, std::size_t j) {
    const std::size_t k = j - i;
    if (last_row[k] == static_cast<std::int32_t>(i) - 1) {
      ++run[k];
    } else {
      if (run[k] > 0) h.diag[run[k]] += 1;
      run[k] = 1;
    }
    last_row[k] = static_cast<std::int32_t>(i);
  }
  void flush() {
    for (std::size_t k = 0; k < run.size(); ++k)
      if (run[k] > 0) {
        h.diag[run[k]] += 1;
        run[k] = 0;
      }
  }
  void row_runs(std::vector<std::uint32_t>& cols) {
    std::sort(cols.begin(), cols.end());
    std::size_t len = 0;
    for (std::size_t t = 0; t < cols.size(); ++t) {
      if (t > 0 && cols[t] == cols[t - 1] + 1)
        ++len;
      else {
        if (len > 0) h.vert[len] += 1;
        len = 1;
      }
    }
    if (len > 0) h.vert[len] += 1;
  }
};

// Upper-triangle streaming (docs/analysis.md#rqa-streaming): only pairs
// j > i + w are visited, rows in order. Diagonal lines run along k = j - i;
// vertical lines of the full matrix are the upper triangle's columns plus,
// transposed, its rows (the band |i-j| <= w, never empty, separates the two
// halves of every column, so no line crosses it). Each row's points are a
// bit set; against the previous row's, 64 columns at a time, a diagonal
// run starts at (i, j) when (i - 1, j - 1) is not a point and ends after
// (i - 1, j - 1) when (i, j) is not, a column's likewise with (i - 1, j).
// Only a run's start row is stored (by diagonal k and by column j), read
// back when it ends: work per run rather than per recurrence.
class UpperLines {
 public:
  UpperLines(std::size_t n, Histograms& h)
      : diag_start_(n + 1, 0), col_start_(n + 1, 0), bits_{std::vector<std::uint64_t>((n + 64) / 64 + 1, 0),
                                                           std::vector<std::uint64_t>((n + 64) / 64 + 1, 0)},
        words_{std::vector<std::uint32_t>(n + 1), std::vector<std::uint32_t>(n + 1)}, h_(h) {}

  // The recurrences (i, j), j > i + w, of row i, in any order; rows 0, 1, ...
  void row(std::uint32_t i, const std::uint32_t* js, std::size_t count) {
    const int p = static_cast<int>(i & 1), q = p ^ 1;  // rows i and i - 1
    std::vector<std::uint64_t>& cur = bits_[p];
    std::vector<std::uint32_t>& words = words_[p];
    // The bit set of row i - 2 is cleared for row i.
    for (std::size_t t = 0; t < touched_[p]; ++t) cur[words[t]] = 0;
    std::size_t touched = 0;
    for (std::size_t t = 0; t < count; ++t) {
      const std::uint32_t j = js[t];
      // The row's set of points, and each word of it once in `words`.
      std::uint64_t& word = cur[j >> 6];
      words[touched] = j >> 6;
      touched += word == 0 ? 1 : 0;
      word |= std::uint64_t{1} << (j & 63);
    }
    touched_[p] = touched;
    last_ = p;
    const std::vector<std::uint64_t>& prev = bits_[q];
    // Runs that end: points of row i - 1 not continued in row i.
    for (std::size_t t = 0; t < touched_[q]; ++t) {
      const std::uint32_t u = words_[q][t];
      end_runs(u, prev[u] & ~((cur[u] >> 1) | (cur[u + 1] << 63)), i, 1, diag_start_, h_.diag);
      end_runs(u, prev[u] & ~cur[u], i, 0, col_start_, h_.vert);
    }
    // Runs that start: points of row i not continuing a run of row i - 1;
    // and the row's horizontal runs, the lower triangle's vertical lines.
    for (std::size_t t = 0; t < touched; ++t) {
      const std::uint32_t w = words[t];
      const std::uint64_t b = cur[w];
      const std::uint64_t prev_below = w > 0 ? prev[w - 1] >> 63 : 0;
      for (std::uint64_t m = b & ~((prev[w] << 1) | prev_below); m != 0; m &= m - 1)
        diag_start_[(w << 6) + static_cast<std::uint32_t>(__builtin_ctzll(m)) - i] = i;
      for (std::uint64_t m = b & ~prev[w]; m != 0; m &= m - 1)
        col_start_[(w << 6) + static_cast<std::uint32_t>(__builtin_ctzll(m))] = i;
      // A horizontal run starts at a set bit whose lower neighbour (the
      // previous word's top bit across a word boundary) is clear.
      const std::uint64_t below = w > 0 ? cur[w - 1] >> 63 : 0;
      for (std::uint64_t m = b & ~((b << 1) | below); m != 0; m &= m - 1)
        h_.vert[run_from(cur, w, __builtin_ctzll(m))] += 1;
    }
  }
  // After the last row (i): its points end their diagonal and column runs.
  void flush(std::uint32_t rows) {
    for (std::size_t t = 0; t < touched_[last_]; ++t) {
      const std::uint32_t u = words_[last_][t];
      end_runs(u, bits_[last_][u], rows, 1, diag_start_, h_.diag);
      end_runs(u, bits_[last_][u], rows, 0, col_start_, h_.vert);
    }
  }

 private:
  // The runs through the points `ended` of word u of row i - 1, which row i
  // does not continue: a diagonal's (shift 1) is stored at k = j + 1 - i,
  // a column's (shift 0) at j.
  static void end_runs(std::uint32_t u, std::uint64_t ended, std::uint32_t i, std::uint32_t shift,
                       const std::vector<std::uint32_t>& start, std::vector<std::uint64_t>& hist) {
    for (; ended != 0; ended &= ended - 1) {
      const std::uint32_t j = (u << 6) + static_cast<std::uint32_t>(__builtin_ctzll(ended));
      hist[i - start[j + shift - (shift != 0 ? i : 0)]] += 1;
    }
  }
  // Length of the run of set bits from bit s of word w on (the bit set has
  // a clear word past the last point, so it ends).
  static std::uint32_t run_from(const std::vector<std::uint64_t>& b, std::uint32_t w, int s) {
    const std::uint64_t rest = ~(b[w] >> s);  // 0 bits where the run goes on
    if (rest != 0 && __builtin_ctzll(rest) < 64 - s) return static_cast<std::uint32_t>(__builtin_ctzll(rest));
    std::uint32_t len = static_cast<std::uint32_t>(64 - s);
    while (b[++w] == ~std::uint64_t{0}) len += 64;
    return len + static_cast<std::uint32_t>(__builtin_ctzll(~b[w]));
  }
  std::vector<std::uint32_t> diag_start_;  // the start row of each diagonal k's current run
  std::vector<std::uint32_t> col_start_;   // and of each column j's
  std::vector<std::uint64_t> bits_[2];     // rows i and i - 1 (by parity): their points
  std::vector<std::uint32_t> words_[2];    // the words each of them set
  std::size_t touched_[2] = {0, 0};
  int last_ = 0;  // parity of the last row
  Histograms& h_;
};

// Uniform grid over the first g = min(m, 3) coordinates with cells of side
// h just above eps / 2: every point within eps of y_i lies in the 5^g cells
// around y_i's cell (two cells either way), and of those only the cells
// whose box comes within eps of y_i are scanned, which leaves about half the
// candidates of 3^g cells of side eps. Points are stored cell by cell, by
// index within a cell, their coordinates copied in that order one array per
// coordinate, so a cell is a contiguous block of each.
class Grid {
 public:
  static constexpr int kReach = 2;  // cells either way: h > eps / 2

  Grid(const Embedding& e, double eps) : e_(e), g_(std::min(e.m, 3)) {
    double span = 0;
    for (int d = 0; d < g_; ++d) {
      lo_[d] = hi_[d] = e.row(0)[d];
      for (std::size_t i = 1; i < e.n; ++i) {
        lo_[d] = std::min(lo_[d], e.row(i)[d]);
        hi_[d] = std::max(hi_[d], e.row(i)[d]);
      }
      span = std::max(span, hi_[d] - lo_[d]);
    }
    // Slightly above eps / 2, so that two values within eps, each rounded
    // into its cell, are at most two cells apart. At most 2^20 cells per
    // axis keeps the cell key in 60 bits; a coarser cell only adds
    // candidates.
    side_ = std::max(0.5 * eps * (1 + 1e-6), span / static_cast<double>(1 << 20));
    // A series constant on the grid's axes with eps = 0 (the radius that a
    // target rate gives when every sampled distance is 0): one cell holds
    // every point, and a zero side would divide 0 by 0.
    if (!(side_ > 0)) side_ = 1.0;
    // A cell's box is widened by this much before the distance to it is
    // bounded: far above the rounding that put a point in its cell.
    double reach = side_ + span;
    for (int d = 0; d < g_; ++d) reach += std::abs(lo_[d]);
    slack_ = 1e-7 * reach;
    for (int d = 0; d < g_; ++d) cells_[d] = cell_of(hi_[d], d) + 1;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(e.n);
    for (std::size_t i = 0; i < e.n; ++i) order[i] = {key_of(e.row(i)), static_cast<std::uint32_t>(i)};
    std::sort(order.begin(), order.end());
    idx_.resize(e.n);
    pts_.resize(e.n * static_cast<std::size_t>(e.m));
    for (std::size_t p = 0; p < e.n; ++p) {
      idx_[p] = order[p].second;
      for (int d = 0; d < e.m; ++d) pts_[static_cast<std::size_t>(d) * e.n + p] = e.row(idx_[p])[d];
      if (p == 0 || order[p].first != order[p - 1].first) {
        keys_.push_back(order[p].first);
        start_.push_back(static_cast<std::uint32_t>(p));
      }
    }
    start_.push_back(static_cast<std::uint32_t>(e.n));
  }

  // Writes to `out` every j >= j_min with ||y_i - y_j||^2 <= eps2 (the
  // squared distance summed over the coordinates in order, as the k-d tree
  // does), cell by cell, increasing j within a cell; returns their count.
  // `out` holds at least N + 2 entries (the stores run one ahead).
  std::size_t within(std::size_t i, std::uint32_t j_min, double eps2, std::uint32_t* out) {
    const double* q = e_.row(i);
    near_cells(q, eps2);
    switch (e_.m) {
      case 1:
        return scan<1>(q, j_min, eps2, out);
      case 2:
        return scan<2>(q, j_min, eps2, out);
      case 3:
        return scan<3>(q, j_min, eps2, out);
      case 4:
        return scan<4>(q, j_min, eps2, out);
      default:
        return scan<0>(q, j_min, eps2, out);
    }
  }

 private:
  using v2d = double __attribute__((vector_size(16)));
  using v2l = std::int64_t __attribute__((vector_size(16)));

  // M > 0: the dimension known at compile time; 0: e_.m. Two candidates at
  // a time: the same operations in the same order per lane as the scalar
  // sum (squares of y_j - y_i added coordinate by coordinate from 0), so
  // the test is bit for bit the k-d tree's. The stores are unconditional
  // and the count advances on a recurrence (no branch to mispredict at a
  // recurrence rate of tens of percent among candidates).
  template <int M>
  std::size_t scan(const double* q, std::uint32_t j_min, double eps2, std::uint32_t* out) const {
    const int m = M > 0 ? M : e_.m;
    const std::size_t n = e_.n;
    const v2d e2 = {eps2, eps2};
    std::size_t count = 0;
    for (std::size_t c = 0; c < n_near_; ++c) {
      const std::uint32_t* first = idx_.data() + near_[c].first;
      const std::uint32_t* last = idx_.data() + near_[c].second;
      std::size_t p = static_cast<std::size_t>(std::lower_bound(first, last, j_min) - idx_.data());
      const std::size_t end = static_cast<std::size_t>(last - idx_.data());
      for (; p + 2 <= end; p += 2) {
        v2d d2 = {0, 0};
#pragma GCC unroll 4
        for (int d = 0; d < m; ++d) {
          v2d y;
          std::memcpy(&y, pts_.data() + static_cast<std::size_t>(d) * n + p, sizeof y);
          const v2d diff = y - q[d];
          d2 += diff * diff;
        }
        const v2l hit = d2 <= e2;  // -1 or 0 per lane
        out[count] = idx_[p];
        count -= static_cast<std::size_t>(hit[0]);
        out[count] = idx_[p + 1];
        count -= static_cast<std::size_t>(hit[1]);
      }
      if (p < end) {
        double d2 = 0;
        for (int d = 0; d < m; ++d) {
          const double diff = pts_[static_cast<std::size_t>(d) * n + p] - q[d];
          d2 += diff * diff;
        }
        out[count] = idx_[p];
        count += d2 <= eps2;
      }
    }
    return count;
  }

  std::int64_t cell_of(double v, int d) const {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>((v - lo_[d]) / side_), 0, (1 << 20) - 1);
  }
  std::uint64_t key_of(const double* y) const {
    std::uint64_t k = 0;
    for (int d = 0; d < g_; ++d)
      k = k * static_cast<std::uint64_t>(cells_[d]) + static_cast<std::uint64_t>(cell_of(y[d], d));
    return k;
  }
  // Squared distance from q's coordinate d to cell c's extent, widened by
  // the slack: a lower bound for every point stored in that cell.
  double gap2(const double* q, int d, std::int64_t c) const {
    const double below = (lo_[d] + static_cast<double>(c) * side_ - slack_) - q[d];
    const double above = q[d] - (lo_[d] + static_cast<double>(c + 1) * side_ + slack_);
    const double gap = std::max(0.0, std::max(below, above));
    return gap * gap;
  }
  // The occupied cells within reach of q whose box comes within eps of q.
  // Cells along the last grid axis have consecutive keys: one bisection per
  // line of cells, then steps along it.
  void near_cells(const double* q, double eps2) {
    n_near_ = 0;
    std::int64_t c0[3] = {0, 0, 0};
    for (int d = 0; d < g_; ++d) c0[d] = cell_of(q[d], d);
    const int last = g_ - 1;
    const int lines = g_ == 1 ? 1 : (g_ == 2 ? 2 * kReach + 1 : (2 * kReach + 1) * (2 * kReach + 1));
    for (int t = 0; t < lines; ++t) {
      // The line's cell on the axes before the last one.
      std::uint64_t k = 0;
      double base2 = 0;
      bool inside = true;
      for (int d = 0, r = t; d < last; ++d, r /= 2 * kReach + 1) {
        const std::int64_t c = c0[d] + r % (2 * kReach + 1) - kReach;
        inside = inside && c >= 0 && c < cells_[d];
        if (inside) base2 += gap2(q, d, c);
        k = k * static_cast<std::uint64_t>(cells_[d]) + static_cast<std::uint64_t>(inside ? c : 0);
      }
      if (!inside || base2 > eps2) continue;
      const std::int64_t c_from = std::max<std::int64_t>(0, c0[last] - kReach);
      const std::int64_t c_to = std::min<std::int64_t>(cells_[last] - 1, c0[last] + kReach);
      const std::uint64_t row = k * static_cast<std::uint64_t>(cells_[last]);
      auto it = std::lower_bound(keys_.begin(), keys_.end(), row + static_cast<std::uint64_t>(c_from));
      for (; it != keys_.end() && *it <= row + static_cast<std::uint64_t>(c_to); ++it) {
        const std::int64_t c = static_cast<std::int64_t>(*it - row);
        if (base2 + gap2(q, last, c) > eps2) continue;
        const std::size_t s = static_cast<std::size_t>(it - keys_.begin());
        near_[n_near_++] = {start_[s], start_[s + 1]};
      }
    }
  }

  const Embedding& e_;
  int g_;
  double lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
  double side_ = 1, slack_ = 0;
  std::int64_t cells_[3] = {1, 1, 1};
  std::vector<std::uint64_t> keys_;   // occupied cells, ascending
  std::vector<std::uint32_t> start_;  // their first point, plus the end
  std::vector<std::uint32_t> idx_;    // point indices, cell by cell
  std::vector<double> pts_;           // their coordinates: coordinate d of the p-th at [d n + p]
  std::pair<std::uint32_t, std::uint32_t> near_[125];
  std::size_t n_near_ = 0;
};

// From a histogram of line lengths (index: length): the recurrent points it
// counts, those on lines of at least min_length, the number of such lines
// and the longest: DET, L and Lmax from the diagonals, LAM, TT and Vmax
// from the verticals (docs/analysis.md#rqa).
struct LineCounts {
  double all = 0, on_lines = 0, lines = 0;
  long longest = 0;
};
LineCounts line_counts(const std::vector<std::uint64_t>& hist, int min_length) {
  LineCounts c;
  for (std::size_t l = 1; l < hist.size(); ++l) {
    const double n = static_cast<double>(hist[l]);
    c.all += n * l;
    if (static_cast<int>(l) >= min_length && n > 0) {
      c.on_lines += n * l;
      c.lines += n;
      c.longest = static_cast<long>(l);
    }
  }
  return c;
}

RqaResult finish(const Histograms& hist, std::uint64_t rec_upper, const Embedding& e, const RqaOptions& opt, double eps,
                 int w) {
  RqaResult r;
  r.eps = eps;
  r.n = e.n;
  r.theiler = w;
  const std::uint64_t n = e.n;
  const std::uint64_t band = std::min<std::uint64_t>(n, static_cast<std::uint64_t>(w) + 1);
  // Eligible upper-triangle pairs: sum over k = w+1..n-1 of (n - k).
  const std::uint64_t m = n - band;
  const std::uint64_t upper = m * (m + 1) / 2;
  r.pairs = 2 * upper;
  r.recurrences = 2 * rec_upper;
  r.rr = upper > 0 ? static_cast<double>(rec_upper) / static_cast<double>(upper) : 0.0;
  // Diagonal measures on the upper triangle (identical to both triangles).
  const LineCounts d = line_counts(hist.diag, opt.lmin);
  r.lmax = d.longest;
  r.det = d.all > 0 ? d.on_lines / d.all : 0;
  r.l_mean = d.lines > 0 ? d.on_lines / d.lines : 0;
  for (std::size_t l = static_cast<std::size_t>(opt.lmin); l < hist.diag.size(); ++l) {
    if (hist.diag[l] == 0) continue;
    const double p = static_cast<double>(hist.diag[l]) / d.lines;
    r.entr -= p * std::log(p);
  }
  const LineCounts v = line_counts(hist.vert, opt.vmin);
  r.vmax = v.longest;
  r.lam = v.all > 0 ? v.on_lines / v.all : 0;
  r.tt = v.lines > 0 ? v.on_lines / v.lines : 0;
  return r;
}

void check(const Embedding& e, const RqaOptions& opt) {
  if (opt.theiler < 0) throw InputError("rqa: Theiler window must be >= 0");
  if (opt.lmin < 1 || opt.vmin < 1) throw InputError("rqa: lmin and vmin must be >= 1");
  if (e.n < static_cast<std::size_t>(opt.theiler) + 2) throw InputError("rqa: too few points for the Theiler window");
  if (e.n >= (std::size_t{1} << 31)) throw InputError("rqa: more than 2^31 points");
}

// Progress every 1,024 rows, as (rows done, rows).
void report(const RqaOptions& opt, std::size_t i, std::size_t n) {
  if (opt.progress && (i & 1023) == 0) opt.progress(static_cast<double>(i), static_cast<double>(n));
}

}  // namespace

RqaResult rqa(const Embedding& e, const RqaOptions& opt) {
  check(e, opt);
  const int w = opt.theiler;
  const double eps = opt.eps > 0 ? opt.eps : radius_for_rr(e, opt.target_rr, w);
  Grid grid(e, eps);
  Histograms hist(e.n);
  UpperLines lines(e.n, hist);
  std::vector<std::uint32_t> row(e.n + 2);
  std::uint64_t rec_upper = 0;
  std::uint32_t rows = 0;
  const double eps2 = eps * eps;
  for (std::size_t i = 0; i + static_cast<std::size_t>(w) + 1 < e.n; ++i) {
    report(opt, i, e.n);
    const std::size_t count =
        grid.within(i, static_cast<std::uint32_t>(i + static_cast<std::size_t>(w) + 1), eps2, row.data());
    lines.row(static_cast<std::uint32_t>(i), row.data(), count);
    rec_upper += count;
    rows = static_cast<std::uint32_t>(i + 1);
  }
  lines.flush(rows);
  if (opt.progress) opt.progress(static_cast<double>(e.n), static_cast<double>(e.n));
  return finish(hist, rec_upper, e, opt, eps, w);
}

namespace {

// The RQA of e with the recurrent points of each row i (j != i, outside the
// Theiler window, within eps) given by within(i, eps, w, row): the two
// neighbour searches below share every count.
template <class Within>
RqaResult rqa_rows(const Embedding& e, const RqaOptions& opt, Within&& within) {
  check(e, opt);
  const int w = opt.theiler;
  const double eps = opt.eps > 0 ? opt.eps : radius_for_rr(e, opt.target_rr, w);
  Histograms hist(e.n);
  LineCounter lc(e.n, hist);
  std::vector<std::uint32_t> row;
  std::uint64_t rec_upper = 0;
  for (std::size_t i = 0; i < e.n; ++i) {
    if ((i & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(i), static_cast<double>(e.n));
    within(i, eps, w, row);
    for (std::uint32_t j : row)
      if (j > i) {
        lc.diag_point(i, j);
        ++rec_upper;
      }
    lc.row_runs(row);
  }
  lc.flush();
  return finish(hist, rec_upper, e, opt, eps, w);
}

}  // namespace

RqaResult rqa_kdtree(const Embedding& e, const RqaOptions& opt) {
  check(e, opt);  // before the index is built
  const NeighbourIndex index(e);
  return rqa_rows(e, opt, [&](std::size_t i, double eps, int w, std::vector<std::uint32_t>& row) {
    index.within(i, eps, w, row);
  });
}

RqaResult rqa_naive(const Embedding& e, const RqaOptions& opt) {
  return rqa_rows(e, opt, [&](std::size_t i, double eps, int w, std::vector<std::uint32_t>& row) {
    row.clear();
    for (std::size_t j = 0; j < e.n; ++j) {
      if (std::labs(static_cast<long>(i) - static_cast<long>(j)) <= w) continue;
      if (euclid(e.row(i), e.row(j), e.m) <= eps) row.push_back(static_cast<std::uint32_t>(j));
    }
  });
}

void write_recurrence_png(const Embedding& e, double eps, int theiler, const std::string& path, int max_pixels) {
  if (max_pixels < 16) max_pixels = 16;
  const std::size_t side = std::min<std::size_t>(e.n, static_cast<std::size_t>(max_pixels));
  const double scale = static_cast<double>(side) / static_cast<double>(e.n);
  std::vector<std::uint8_t> img(side * side, 255);
  const NeighbourIndex index(e);
  std::vector<std::uint32_t> row;
  const int w = theiler < 0 ? -1 : theiler;
  for (std::size_t i = 0; i < e.n; ++i) {
    index.within(i, eps, w, row);
    const std::size_t pi = std::min(side - 1, static_cast<std::size_t>(static_cast<double>(i) * scale));
    for (std::uint32_t j : row) {
      const std::size_t pj = std::min(side - 1, static_cast<std::size_t>(static_cast<double>(j) * scale));
      // Row 0 of the image is the top: put i = 0 at the bottom (usual RP
      // layout).
      img[(side - 1 - pi) * side + pj] = 0;
    }
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    throw InputError("libpng failed writing '" + path + "'");
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(side), static_cast<png_uint_32>(side), 8, PNG_COLOR_TYPE_GRAY,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (std::size_t r = 0; r < side; ++r) png_write_row(png, img.data() + r * side);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) throw InputError("closing '" + path + "' failed");
}

}  // namespace cvt::analysis
