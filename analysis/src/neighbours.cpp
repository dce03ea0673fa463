#include "cvtplant/analysis/neighbours.hpp"

#include <algorithm>
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

// Single nearest neighbour outside the Theiler band around `centre`; of
// equally near points the lowest index, whatever order the tree offers them
// in (worstDist lets an equal distance through nanoflann's `dist < worst`).
// A start with a known candidate (best, idx, found) bounds the search.
struct NearestExcluding {
  long centre;
  long w;
  const std::uint32_t* index_of = nullptr;  // a tree's labels -> row indices (nullptr: the same)
  double best = std::numeric_limits<double>::max();
  double worst = std::numeric_limits<double>::infinity();  // the next double above best
  std::uint32_t idx = 0;
  bool found = false;
  void init() {}
  void start(double d2, std::uint32_t j) {
    best = d2;
    worst = std::nextafter(d2, std::numeric_limits<double>::infinity());
    idx = j;
    found = true;
  }
  std::size_t size() const { return found ? 1 : 0; }
  bool full() const { return true; }
  bool addPoint(double d2, std::uint32_t label) {
    const std::uint32_t j = index_of != nullptr ? index_of[label] : label;
    if (w >= 0 && std::labs(static_cast<long>(j) - centre) <= w) return true;
    if (d2 < best || (d2 == best && (j < idx || !found))) start(d2, j);
    return true;
  }
  double worstDist() const { return worst; }
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

// --- DelayNeighbours ---------------------------------------------------------

namespace {

// The tree of dimension m is built from the delay vectors read in place
// (coordinate d of row i is x[i + d tau]) and then relabelled: label p is the
// p-th row in the tree's leaf order, its m coordinates copied to
// pts[p m, p m + m), so a leaf is one contiguous block rather than m
// scattered reads per row.
struct DelayCloud {
  const double* x = nullptr;
  std::size_t tau = 1;
  std::size_t n = 0;                 // rows
  std::size_t m = 1;                 // dimension
  std::vector<double> pts;           // rows by label
  std::vector<std::uint32_t> index;  // label -> row
  std::size_t kdtree_get_point_count() const { return n; }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return x[i + d * tau]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};

// L2_Simple_Adaptor over the relabelled rows: the same terms in the same
// order as over an Embedding's rows, so distances agree to the bit.
struct DelayL2 {
  using ElementType = double;
  using DistanceType = double;
  const DelayCloud& c;
  explicit DelayL2(const DelayCloud& cloud) : c(cloud) {}
  double evalMetric(const double* q, std::uint32_t label, std::size_t m) const {
    const double* p = c.pts.data() + static_cast<std::size_t>(label) * m;
    double d2 = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const double diff = q[k] - p[k];
      d2 += diff * diff;
    }
    return d2;
  }
  double accum_dist(double a, double b, std::size_t) const { return (a - b) * (a - b); }
};

using DelayTree = nanoflann::KDTreeSingleIndexAdaptor<DelayL2, DelayCloud, -1, std::uint32_t>;

}  // namespace

struct DelayNeighbours::Impl {
  DelayCloud cloud;
  std::unique_ptr<DelayTree> tree;
};

DelayNeighbours::DelayNeighbours(const std::vector<double>& x, int tau) : impl_(std::make_unique<Impl>()) {
  impl_->cloud.x = x.data();
  impl_->cloud.tau = static_cast<std::size_t>(tau);
}
DelayNeighbours::~DelayNeighbours() = default;

void DelayNeighbours::set_dimension(int m, std::size_t rows) {
  Impl& s = *impl_;
  DelayCloud& c = s.cloud;
  c.n = rows;
  c.m = static_cast<std::size_t>(m);
  // The previous dimension's tree and rows go first: the peak memory is one
  // dimension's, not two.
  s.tree.reset();
  std::vector<double>().swap(c.pts);
  s.tree = std::make_unique<DelayTree>(m, c, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  s.tree->buildIndex();
  c.index.assign(s.tree->vAcc.begin(), s.tree->vAcc.end());
  for (std::size_t p = 0; p < c.n; ++p) s.tree->vAcc[p] = static_cast<std::uint32_t>(p);
  c.pts.resize(c.n * c.m);
  for (std::size_t p = 0; p < c.n; ++p)
    for (std::size_t k = 0; k < c.m; ++k) c.pts[p * c.m + k] = c.x[c.index[p] + k * c.tau];
}

std::size_t DelayNeighbours::size() const { return impl_->cloud.n; }
std::size_t DelayNeighbours::row_of(std::size_t label) const { return impl_->cloud.index[label]; }

bool DelayNeighbours::nearest(std::size_t label, int w, std::size_t& j, double& dist, std::size_t hint) const {
  const DelayCloud& c = impl_->cloud;
  const std::size_t i = c.index[label];
  const double* q = c.pts.data() + label * c.m;
  NearestExcluding rs{static_cast<long>(i), w, c.index.data()};
  if (hint < c.n && std::labs(static_cast<long>(hint) - static_cast<long>(i)) > w) {
    double d2 = 0;
    for (std::size_t k = 0; k < c.m; ++k) {
      const double diff = q[k] - c.x[hint + k * c.tau];
      d2 += diff * diff;
    }
    rs.start(d2, static_cast<std::uint32_t>(hint));
  }
  impl_->tree->findNeighbors(rs, q, nanoflann::SearchParams());
  if (!rs.found) return false;
  j = rs.idx;
  dist = std::sqrt(rs.best);
  return true;
}

}  // namespace cvt::analysis
