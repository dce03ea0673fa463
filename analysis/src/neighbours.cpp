#include "cvtplant/analysis/neighbours.hpp"

#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace cvt::analysis {
namespace {

struct Cloud {
  const Embedding* e;
  std::size_t n;
  std::size_t kdtree_get_point_count() const { return n; }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return e->data[i * e->m + d]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, -1, std::uint32_t>;

// Single nearest neighbour outside the Theiler band around `centre`.
struct NearestExcluding {
  long centre;
  long w;
  double best = std::numeric_limits<double>::max();
  std::uint32_t idx = 0;
  bool found = false;
  void init() {}
  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return true; }
  bool addPoint(double d2, std::uint32_t j) {
    if (w >= 0 && std::labs(static_cast<long>(j) - centre) <= w) return true;
    if (d2 < best) {
      best = d2;
      idx = j;
      found = true;
    }
    return true;
  }
  double worstDist() const { return best; }
};

// All points with squared distance <= r2 outside the band (note nanoflann
// tests `dist < worstDist()`, hence the nextafter to make the rule `<=`).
struct WithinExcluding {
  long centre;
  long w;
  double r2;
  double worst;
  std::vector<std::uint32_t>* out;
  void init() {}
  std::size_t size() const { return out->size(); }
  bool full() const { return true; }
  bool addPoint(double d2, std::uint32_t j) {
    if (d2 <= r2 && std::labs(static_cast<long>(j) - centre) > w) out->push_back(j);
    return true;
  }
  double worstDist() const { return worst; }
};

}  // namespace

struct NeighbourIndex::Impl {
  Cloud cloud;
  Tree tree;
  Impl(const Embedding& e, std::size_t n)
      : cloud{&e, n}, tree(e.m, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

NeighbourIndex::NeighbourIndex(const Embedding& e, std::size_t n_points)
    : impl_(std::make_unique<Impl>(e, n_points == 0 || n_points > e.n ? e.n : n_points)) {}
NeighbourIndex::~NeighbourIndex() = default;

std::size_t NeighbourIndex::size() const { return impl_->cloud.n; }

bool NeighbourIndex::nearest_to(const double* q, std::size_t i, int w, std::size_t& j, double& dist) const {
  NearestExcluding rs{static_cast<long>(i), w};
  impl_->tree.findNeighbors(rs, q, nanoflann::SearchParams());
  if (!rs.found) return false;
  j = rs.idx;
  dist = std::sqrt(rs.best);
  return true;
}

bool NeighbourIndex::nearest(std::size_t i, int w, std::size_t& j, double& dist) const {
  return nearest_to(impl_->cloud.e->row(i), i, w, j, dist);
}

void NeighbourIndex::within(std::size_t i, double eps, int w, std::vector<std::uint32_t>& out) const {
  out.clear();
  const double r2 = eps * eps;
  WithinExcluding rs{static_cast<long>(i), w, r2, std::nextafter(r2, std::numeric_limits<double>::max()), &out};
  impl_->tree.findNeighbors(rs, impl_->cloud.e->row(i), nanoflann::SearchParams(32, 0, false));
}

double NeighbourIndex::kth_distance(std::size_t i, int k) const {
  std::vector<std::uint32_t> idx(static_cast<std::size_t>(k) + 1);
  std::vector<double> d2(static_cast<std::size_t>(k) + 1);
  const std::size_t got = impl_->tree.knnSearch(impl_->cloud.e->row(i), k + 1, idx.data(), d2.data());
  if (got == 0) return 0;
  // Entry 0 is the point itself.
  return std::sqrt(d2[std::min<std::size_t>(got - 1, static_cast<std::size_t>(k))]);
}

}  // namespace cvt::analysis
