#pragma once
// Recurrence quantification (docs/analysis.md#rqa).
// Rule: R(i,j) = 1 iff ||y_i - y_j||_2 <= eps (Euclidean, `<=`).
// Excluded: every pair with |i-j| <= w (w = Theiler window; w = 0 removes
// exactly the line of identity, which therefore never counts in RR, DET, ...).
// Streaming (docs/analysis.md#rqa-streaming): rows in order, only the upper
// triangle's recurrences visited, found in a grid of cells of side eps and
// consumed at once; memory is O(N) (no N x N matrix).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

struct RqaOptions {
  double eps = -1;          // absolute radius; if <= 0, chosen for target_rr
  double target_rr = 0.02;  // used when eps <= 0
  int theiler = 0;          // w: pairs |i-j| <= w excluded
  int lmin = 2;             // minimal diagonal line length (DET, L, ENTR)
  int vmin = 2;             // minimal vertical line length (LAM, TT)
  // Called every few thousand rows with (rows done, rows), e.g. by a
  // progress bar; empty: not called.
  std::function<void(double done, double total)> progress;
};

struct RqaResult {
  double eps = 0;
  double rr = 0, det = 0, l_mean = 0, entr = 0, lam = 0, tt = 0;
  long lmax = 0, vmax = 0;
  std::uint64_t recurrences = 0;  // counted points (both triangles)
  std::uint64_t pairs = 0;        // eligible points (both triangles)
  std::size_t n = 0;
  int theiler = 0;
};

// Minimal diagonal line that delay embedding alone cannot create
// (docs/analysis.md#rqa-lmin): with tau < m-1, consecutive delay vectors share
// coordinates, so even noise makes diagonals of length up to (m-1)/tau + 1.
inline int default_lmin(int m, int tau) {
  const int span = (m - 1 + tau - 1) / tau;  // ceil((m-1)/tau)
  return span + 1 > 2 ? span + 1 : 2;
}

// Radius giving recurrence rate `rr` among eligible pairs, from a fixed-seed
// sample of pairs (deterministic).
double radius_for_rr(const Embedding& e, double rr, int theiler);

// Time O(N + recurrences x (candidates per recurrence)), memory about
// 8 (m + 6) bytes per point besides the embedding.
RqaResult rqa(const Embedding& e, const RqaOptions& opt);
// The same measures from a k-d tree radius search over both triangles, with
// each row sorted for its vertical runs: the reference method of the tests
// and the benchmark.
RqaResult rqa_kdtree(const Embedding& e, const RqaOptions& opt);
// O(N^2)-time, O(N)-memory brute force with the same conventions: the
// reference for the tests and the benchmark.
RqaResult rqa_naive(const Embedding& e, const RqaOptions& opt);

// Writes a recurrence plot as a greyscale PNG of at most `max_pixels` per side
// (a pixel is black if any recurrence falls in its block; the line of identity
// is drawn only if theiler < 0). Throws InputError if the file cannot be written.
void write_recurrence_png(const Embedding& e, double eps, int theiler, const std::string& path, int max_pixels = 1000);

}  // namespace cvt::analysis
