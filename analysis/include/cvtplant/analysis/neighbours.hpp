#pragma once
// k-d tree neighbour search over an Embedding (nanoflann), Euclidean metric,
// with a Theiler window: a point j is a candidate neighbour of i only if
// |i - j| > w (docs/analysis.md#theiler). Memory O(N).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "cvtplant/analysis/series.hpp"

namespace cvt::analysis {

class NeighbourIndex {
 public:
  // Indexes the first `n_points` rows of `e` (all rows if 0). `e` must outlive
  // the index.
  explicit NeighbourIndex(const Embedding& e, std::size_t n_points = 0);
  ~NeighbourIndex();
  NeighbourIndex(const NeighbourIndex&) = delete;
  NeighbourIndex& operator=(const NeighbourIndex&) = delete;

  std::size_t size() const;

  // Nearest neighbour of row i with |i-j| > w; returns false if none. dist is
  // Euclidean (not squared). Of equally near rows the lowest index, so the
  // answer does not depend on the tree's layout.
  bool nearest(std::size_t i, int w, std::size_t& j, double& dist) const;
  // Nearest neighbour of an arbitrary point (excluding indices |idx-i|<=w
  // around `i`; pass w < 0 to exclude nothing).
  bool nearest_to(const double* q, std::size_t i, int w, std::size_t& j, double& dist) const;

  // All j with |i-j| > w and ||y_i - y_j|| <= eps (the `<=` rule), unsorted.
  void within(std::size_t i, double eps, int w, std::vector<std::uint32_t>& out) const;
  // Distance of the k-th nearest neighbour of row i (k >= 1), no exclusion.
  double kth_distance(std::size_t i, int k) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Nearest neighbours in the delay embeddings of one series, dimension by
// dimension (FNN, Cao; docs/analysis.md#fnn): a k-d tree per dimension built
// from the series in place, the rows labelled in the tree's leaf order.
// Answers as NeighbourIndex::nearest on delay_embed's rows: the same neighbour
// (the lowest index among equals) and the same distance bits.
class DelayNeighbours {
 public:
  static constexpr std::size_t kNoHint = ~std::size_t{0};
  // `x` must outlive the object.
  DelayNeighbours(const std::vector<double>& x, int tau);
  ~DelayNeighbours();
  DelayNeighbours(const DelayNeighbours&) = delete;
  DelayNeighbours& operator=(const DelayNeighbours&) = delete;

  // Indexes dimension m over rows 0..rows-1 (each needs x[i + (m-1) tau]).
  void set_dimension(int m, std::size_t rows);
  // The rows, and the row of each label: queries in label order reuse the
  // tree's nodes and leaves in cache.
  std::size_t size() const;
  std::size_t row_of(std::size_t label) const;
  // Nearest row j to the row of `label` with |i-j| > w. A hint (a row near
  // it, e.g. its neighbour in dimension m-1) bounds the search from the
  // start; the answer is the same with or without.
  bool nearest(std::size_t label, int w, std::size_t& j, double& dist, std::size_t hint = kNoHint) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

inline double euclid(const double* a, const double* b, int m) {
  double s = 0;
  for (int k = 0; k < m; ++k) {
    const double d = a[k] - b[k];
    s += d * d;
  }
  return __builtin_sqrt(s);
}

}  // namespace cvt::analysis
