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

// Line-length histograms accumulated row by row (docs/analysis.md#rqa-streaming).
struct LineCounter {
  // Diagonal k = j - i > w (upper triangle; the lower one is its mirror).
  std::vector<std::int32_t> run, last_row;
  std::vector<std::uint64_t> diag_hist, vert_hist;
  explicit LineCounter(std::size_t n) : run(n + 1, 0), last_row(n + 1, -2), diag_hist(n + 1, 0), vert_hist(n + 1, 0) {}

  void diag_point(std::size_t i, std::size_t j) {
    const std::size_t k = j - i;
    if (last_row[k] == static_cast<std::int32_t>(i) - 1) {
      ++run[k];
    } else {
      if (run[k] > 0) diag_hist[run[k]] += 1;
      run[k] = 1;
    }
    last_row[k] = static_cast<std::int32_t>(i);
  }
  void flush() {
    for (std::size_t k = 0; k < run.size(); ++k)
      if (run[k] > 0) {
        diag_hist[run[k]] += 1;
        run[k] = 0;
      }
  }
  // Vertical lines of column i = runs of consecutive j in row i (symmetry).
  void row_runs(std::vector<std::uint32_t>& cols) {
    std::sort(cols.begin(), cols.end());
    std::size_t len = 0;
    for (std::size_t t = 0; t < cols.size(); ++t) {
      if (t > 0 && cols[t] == cols[t - 1] + 1)
        ++len;
      else {
        if (len > 0) vert_hist[len] += 1;
        len = 1;
      }
    }
    if (len > 0) vert_hist[len] += 1;
  }
};

RqaResult finish(const LineCounter& lc, std::uint64_t rec_upper, const Embedding& e, const RqaOptions& opt, double eps,
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
  double all_pts = 0, line_pts = 0, lines = 0;
  for (std::size_t l = 1; l < lc.diag_hist.size(); ++l) {
    const double c = static_cast<double>(lc.diag_hist[l]);
    all_pts += c * l;
    if (static_cast<int>(l) >= opt.lmin && c > 0) {
      line_pts += c * l;
      lines += c;
      r.lmax = static_cast<long>(l);
    }
  }
  r.det = all_pts > 0 ? line_pts / all_pts : 0;
  r.l_mean = lines > 0 ? line_pts / lines : 0;
  for (std::size_t l = static_cast<std::size_t>(opt.lmin); l < lc.diag_hist.size(); ++l) {
    if (lc.diag_hist[l] == 0) continue;
    const double p = static_cast<double>(lc.diag_hist[l]) / lines;
    r.entr -= p * std::log(p);
  }
  double v_all = 0, v_line = 0, v_lines = 0;
  for (std::size_t v = 1; v < lc.vert_hist.size(); ++v) {
    const double c = static_cast<double>(lc.vert_hist[v]);
    v_all += c * v;
    if (static_cast<int>(v) >= opt.vmin && c > 0) {
      v_line += c * v;
      v_lines += c;
      r.vmax = static_cast<long>(v);
    }
  }
  r.lam = v_all > 0 ? v_line / v_all : 0;
  r.tt = v_lines > 0 ? v_line / v_lines : 0;
  return r;
}

void check(const Embedding& e, const RqaOptions& opt) {
  if (opt.theiler < 0) throw InputError("rqa: Theiler window must be >= 0");
  if (opt.lmin < 1 || opt.vmin < 1) throw InputError("rqa: lmin and vmin must be >= 1");
  if (e.n < static_cast<std::size_t>(opt.theiler) + 2) throw InputError("rqa: too few points for the Theiler window");
}

}  // namespace

RqaResult rqa(const Embedding& e, const RqaOptions& opt) {
  check(e, opt);
  const int w = opt.theiler;
  const double eps = opt.eps > 0 ? opt.eps : radius_for_rr(e, opt.target_rr, w);
  const NeighbourIndex index(e);
  LineCounter lc(e.n);
  std::vector<std::uint32_t> row;
  std::uint64_t rec_upper = 0;
  for (std::size_t i = 0; i < e.n; ++i) {
    if ((i & 4095) == 0 && opt.progress) opt.progress(static_cast<double>(i), static_cast<double>(e.n));
    index.within(i, eps, w, row);
    for (std::uint32_t j : row)
      if (j > i) {
        lc.diag_point(i, j);
        ++rec_upper;
      }
    lc.row_runs(row);
  }
  lc.flush();
  return finish(lc, rec_upper, e, opt, eps, w);
}

RqaResult rqa_naive(const Embedding& e, const RqaOptions& opt) {
  check(e, opt);
  const int w = opt.theiler;
  const double eps = opt.eps > 0 ? opt.eps : radius_for_rr(e, opt.target_rr, w);
  LineCounter lc(e.n);
  std::vector<std::uint32_t> row;
  std::uint64_t rec_upper = 0;
  for (std::size_t i = 0; i < e.n; ++i) {
    row.clear();
    for (std::size_t j = 0; j < e.n; ++j) {
      if (std::labs(static_cast<long>(i) - static_cast<long>(j)) <= w) continue;
      if (euclid(e.row(i), e.row(j), e.m) <= eps) row.push_back(static_cast<std::uint32_t>(j));
    }
    for (std::uint32_t j : row)
      if (j > i) {
        lc.diag_point(i, j);
        ++rec_upper;
      }
    lc.row_runs(row);
  }
  lc.flush();
  return finish(lc, rec_upper, e, opt, eps, w);
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
      // Row 0 of the image is the top: put i = 0 at the bottom (usual RP layout).
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
