// The chain's Newton systems by block elimination (docs/mbd.md#linear-algebra).
#include "chain_solver.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace cvt::mbd::detail {

namespace {

[[noreturn]] void not_chain(int r, int c) {
  throw std::logic_error("chain solver: entry (" + std::to_string(r) + ", " + std::to_string(c) +
                         ") outside the chain's structure");
}

}  // namespace

ChainSolver::ChainSolver(const ChainModel& m) {
  N_ = m.links();
  n_ = m.size();
  const SparsePattern& p = m.pattern();
  // Unknowns: link states (6 per link: x, y, theta, vx, vy, omega), the
  // border (pulley speeds; clamped: sheave openings and rates), the pulley
  // angles and the ledger integrals.
  for (int j = 0; j < 2; ++j) border_.push_back(m.pulley_speed(j));
  if (m.clamped())
    for (int j = 0; j < 2; ++j) {
      border_.push_back(m.sheave_opening(j));
      border_.push_back(m.sheave_rate(j));
    }
  nb_ = static_cast<int>(border_.size());
  w_ = 3 + nb_;
  if (w_ > 16) throw std::logic_error("chain solver: border too wide");
  for (int j = 0; j < 2; ++j) angle_[j] = m.pulley_angle(j);
  for (int k = 0; k < 5; ++k) ledger_[k] = m.ledger(k);
  // What each state index is: 0..6N-1 links; -1 - b border b; angles and
  // ledger marked apart.
  enum Kind { link, border, angle, ledger };
  std::vector<Kind> kind(static_cast<std::size_t>(n_), link);
  std::vector<int> slot(static_cast<std::size_t>(n_), 0);
  for (int b = 0; b < nb_; ++b) kind[static_cast<std::size_t>(border_[b])] = border, slot[border_[b]] = b;
  for (int j = 0; j < 2; ++j) kind[static_cast<std::size_t>(angle_[j])] = angle, slot[angle_[j]] = j;
  for (int k = 0; k < 5; ++k) kind[static_cast<std::size_t>(ledger_[k])] = ledger, slot[ledger_[k]] = k;
  for (int i = 0; i < n_; ++i)
    if (kind[static_cast<std::size_t>(i)] == link && i >= 6 * N_) throw std::logic_error("chain solver: layout");

  const std::size_t N3 = 3 * static_cast<std::size_t>(N_), nb = static_cast<std::size_t>(nb_);
  std::size_t off = 0;
  auto take = [&off](std::size_t count) {
    const std::size_t o = off;
    off += count;
    return o;
  };
  off_qq_ = take(N3);
  off_qv_ = take(N3);
  off_vq_ = take(N3 * 9);  // per link, per neighbour slot, 3x3 row-major
  off_vv_ = take(N3 * 9);
  off_vb_ = take(N3 * nb);
  off_bq_ = take(nb * N3);
  off_bv_ = take(nb * N3);
  off_bb_ = take(nb * nb);
  off_pb_ = take(2 * nb);
  off_pp_ = take(2);
  off_ll_ = take(5);
  off_lrow_ = take(5 * static_cast<std::size_t>(n_));  // dense, their diagonals apart
  jac_.assign(off, 0.0);

  dest_.resize(static_cast<std::size_t>(p.nnz()));
  auto neighbour_slot = [this](int i, int mlink) {
    if (mlink == (i + N_ - 1) % N_) return 0;
    if (mlink == i) return 1;
    if (mlink == (i + 1) % N_) return 2;
    return -1;
  };
  for (int c = 0; c < n_; ++c) {
    for (std::int64_t k = p.col_start[static_cast<std::size_t>(c)]; k < p.col_start[static_cast<std::size_t>(c) + 1];
         ++k) {
      const int r = static_cast<int>(p.row[static_cast<std::size_t>(k)]);
      const Kind kr = kind[static_cast<std::size_t>(r)], kc = kind[static_cast<std::size_t>(c)];
      std::size_t d = 0;
      if (kr == link && r % 6 < 3) {
        // Position row: dq/dt = v, so only its own diagonal and velocity.
        const std::size_t row = static_cast<std::size_t>(3 * (r / 6) + r % 6);
        if (c == r) d = off_qq_ + row;
        else if (c == r + 3) d = off_qv_ + row;
        else not_chain(r, c);
      } else if (kr == link) {
        const int i = r / 6, kk = r % 6 - 3;
        if (kc == link) {
          const int s = neighbour_slot(i, c / 6);
          if (s < 0) not_chain(r, c);
          const std::size_t blk = (3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(s)) * 9 +
                                  3 * static_cast<std::size_t>(kk) + static_cast<std::size_t>(c % 6 % 3);
          d = (c % 6 < 3 ? off_vq_ : off_vv_) + blk;
        } else if (kc == border) {
          d = off_vb_ + (3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(kk)) * nb +
              static_cast<std::size_t>(slot[c]);
        } else {
          not_chain(r, c);
        }
      } else if (kr == border) {
        const std::size_t b = static_cast<std::size_t>(slot[r]);
        if (kc == link) {
          const std::size_t col = static_cast<std::size_t>(3 * (c / 6) + c % 6 % 3);
          d = (c % 6 < 3 ? off_bq_ : off_bv_) + b * N3 + col;
        } else if (kc == border) {
          d = off_bb_ + b * nb + static_cast<std::size_t>(slot[c]);
        } else {
          not_chain(r, c);
        }
      } else if (kr == angle) {
        if (c == r) d = off_pp_ + static_cast<std::size_t>(slot[r]);
        else if (kc == border) d = off_pb_ + static_cast<std::size_t>(slot[r]) * nb + static_cast<std::size_t>(slot[c]);
        else not_chain(r, c);
      } else {  // ledger row
        if (c == r) {
          d = off_ll_ + static_cast<std::size_t>(slot[r]);
        } else if (kc == ledger) {
          not_chain(r, c);
        } else {
          d = off_lrow_ + static_cast<std::size_t>(slot[r]) * static_cast<std::size_t>(n_) + static_cast<std::size_t>(c);
        }
      }
      dest_[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(d);
    }
  }
  // Nothing may depend on an angle or a ledger integral: their columns hold
  // only their diagonal.
  for (int c = 0; c < n_; ++c) {
    const Kind kc = kind[static_cast<std::size_t>(c)];
    if (kc != angle && kc != ledger) continue;
    for (std::int64_t k = p.col_start[static_cast<std::size_t>(c)]; k < p.col_start[static_cast<std::size_t>(c) + 1];
         ++k)
      if (p.row[static_cast<std::size_t>(k)] != c) not_chain(static_cast<int>(p.row[static_cast<std::size_t>(k)]), c);
  }

  const int Nt = N_ - 1;  // links in the tridiagonal part
  nbr_.resize(N3);
  for (int i = 0; i < N_; ++i)
    for (int s = 0; s < 3; ++s) nbr_[3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(s)] = (i + N_ - 1 + s) % N_;
  aqq_.assign(N3, 1.0);
  ratio_.assign(N3, 0.0);
  K_.assign(N3 * 9, 0.0);
  Kb_.assign(N3 * nb, 0.0);
  Bv_.assign(nb * N3, 0.0);
  M_.assign(static_cast<std::size_t>(Nt) * 9, 0.0);
  Ginv_.assign(static_cast<std::size_t>(Nt) * 9, 0.0);
  P_.assign(static_cast<std::size_t>(Nt) * 9, 0.0);
  X_.assign(3 * static_cast<std::size_t>(Nt) * static_cast<std::size_t>(w_), 0.0);
  Bt_.assign(18, 0.0);
  S_.assign(static_cast<std::size_t>(w_ * w_), 0.0);
  piv_.assign(static_cast<std::size_t>(w_), 0);
  tq_.assign(N3, 0.0);
  r_.assign(N3 + nb, 0.0);
  e_.assign(static_cast<std::size_t>(w_), 0.0);
}

namespace {

// 3x3 row-major helpers.
void mul3(const double* a, const double* b, double* c) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}
// c -= a b
void mul3_sub(const double* a, const double* b, double* c) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[3 * i + j] -= a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}
// Dot product in a fixed order: two running sums, of the even and of the odd
// terms, added at the end (one SSE2 register where there is one; the same
// arithmetic without).
double dot(const double* a, const double* b, std::size_t n) {
  std::size_t i = 0;
#if defined(__SSE2__)
  __m128d acc = _mm_setzero_pd();
  for (; i + 1 < n; i += 2) acc = _mm_add_pd(acc, _mm_mul_pd(_mm_loadu_pd(a + i), _mm_loadu_pd(b + i)));
  double s[2];
  _mm_storeu_pd(s, acc);
  double s0 = s[0], s1 = s[1];
#else
  double s0 = 0, s1 = 0;
  for (; i + 1 < n; i += 2) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
  }
#endif
  if (i < n) s0 += a[i] * b[i];
  return s0 + s1;
}
// inverse by Gauss-Jordan with partial pivoting; false if a pivot is zero or not finite
bool inv3(const double* g, double* out) {
  double a[3][6];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      a[i][j] = g[3 * i + j];
      a[i][3 + j] = i == j ? 1.0 : 0.0;
    }
  for (int c = 0; c < 3; ++c) {
    int p = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (!(std::isfinite(a[p][c]) && a[p][c] != 0.0)) return false;
    if (p != c)
      for (int j = 0; j < 6; ++j) std::swap(a[p][j], a[c][j]);
    const double inv = 1.0 / a[c][c];
    for (int j = 0; j < 6; ++j) a[c][j] *= inv;
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      for (int j = 0; j < 6; ++j) a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[3 * i + j] = a[i][3 + j];
  return true;
}

}  // namespace

void ChainSolver::set_jacobian(const double* values) {
  for (std::size_t k = 0; k < dest_.size(); ++k) jac_[static_cast<std::size_t>(dest_[k])] = values[k];
}

bool ChainSolver::factor(double gamma) {
  gamma_ = gamma;
  const double g = gamma;
  const std::size_t N3 = 3 * static_cast<std::size_t>(N_), nb = static_cast<std::size_t>(nb_),
                    w = static_cast<std::size_t>(w_);
  // A = I - gamma J. Position rows: a_qq q + a_qv v = b_q.
  for (std::size_t r = 0; r < N3; ++r) {
    aqq_[r] = 1.0 - g * jac_[off_qq_ + r];
    ratio_[r] = -g * jac_[off_qv_ + r] / aqq_[r];
  }
  // Positions eliminated: the velocity rows' position columns fold into their
  // velocity columns, K = A_vv - A_vq diag(a_qv / a_qq).
  for (std::size_t blk = 0; blk < N3; ++blk) {
    const double* vq = &jac_[off_vq_ + blk * 9];
    const double* vv = &jac_[off_vv_ + blk * 9];
    const double* rm = &ratio_[3 * static_cast<std::size_t>(nbr_[blk])];
    double* K = &K_[blk * 9];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) K[3 * a + b] = g * (vq[3 * a + b] * rm[b] - vv[3 * a + b]);
    if (blk % 3 == 1)
      for (int a = 0; a < 3; ++a) K[4 * a] += 1.0;
  }
  for (std::size_t k = 0; k < N3 * nb; ++k) Kb_[k] = -g * jac_[off_vb_ + k];
  for (std::size_t b = 0; b < nb; ++b)
    for (std::size_t c = 0; c < N3; ++c)
      Bv_[b * N3 + c] = g * (jac_[off_bq_ + b * N3 + c] * ratio_[c] - jac_[off_bv_ + b * N3 + c]);

  // Thomas on links 0..N-2.
  const int Nt = N_ - 1;
  auto D = [this](int i) { return &K_[(3 * static_cast<std::size_t>(i) + 1) * 9]; };
  auto Lo = [this](int i) { return &K_[(3 * static_cast<std::size_t>(i)) * 9]; };
  auto Up = [this](int i) { return &K_[(3 * static_cast<std::size_t>(i) + 2) * 9]; };
  for (int i = 0; i < Nt; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i) * 9;
    double G[9];
    std::copy(D(i), D(i) + 9, G);
    if (i > 0) {
      mul3(Lo(i), &Ginv_[ii - 9], &M_[ii]);
      mul3_sub(&M_[ii], Up(i - 1), G);
    }
    if (!inv3(G, &Ginv_[ii])) return false;
    if (i < Nt - 1) mul3(&Ginv_[ii], Up(i), &P_[ii]);
  }
  // X = T^-1 R, R: links 0..N-2 against the last link and the border.
  const int last = N_ - 1;
  // Column-major: column c holds 3 (N - 1) rows.
  const std::size_t n3t = 3 * static_cast<std::size_t>(Nt);
  std::fill(X_.begin(), X_.end(), 0.0);
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = 0; b < 3; ++b) {
      X_[b * n3t + a] += Lo(0)[3 * a + b];
      X_[b * n3t + n3t - 3 + a] += Up(Nt - 1)[3 * a + b];
    }
  for (std::size_t r = 0; r < n3t; ++r)
    for (std::size_t b = 0; b < nb; ++b) X_[(3 + b) * n3t + r] = Kb_[r * nb + b];
  for (std::size_t c = 0; c < w; ++c) thomas_solve(&X_[c * n3t]);
  // Bt: the last link's rows against links 0 and N-2 (its other columns are zero).
  std::copy(Up(last), Up(last) + 9, Bt_.begin());
  std::copy(Lo(last), Lo(last) + 9, Bt_.begin() + 9);
  // C, then S = C - Bt X.
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) S_[static_cast<std::size_t>(a) * w + static_cast<std::size_t>(b)] = D(last)[3 * a + b];
    for (std::size_t b = 0; b < nb; ++b)
      S_[static_cast<std::size_t>(a) * w + 3 + b] = Kb_[(3 * static_cast<std::size_t>(last) + static_cast<std::size_t>(a)) * nb + b];
  }
  for (std::size_t bb = 0; bb < nb; ++bb) {
    for (int b = 0; b < 3; ++b)
      S_[(3 + bb) * w + static_cast<std::size_t>(b)] = Bv_[bb * N3 + 3 * static_cast<std::size_t>(last) + static_cast<std::size_t>(b)];
    for (std::size_t b = 0; b < nb; ++b) S_[(3 + bb) * w + 3 + b] = (bb == b ? 1.0 : 0.0) - g * jac_[off_bb_ + bb * nb + b];
  }
  for (std::size_t c = 0; c < w; ++c) {
    const double* xc = &X_[c * n3t];
    for (std::size_t a = 0; a < 3; ++a) {
      double s = 0;
      for (std::size_t b = 0; b < 3; ++b) s += Bt_[3 * a + b] * xc[b] + Bt_[9 + 3 * a + b] * xc[n3t - 3 + b];
      S_[a * w + c] -= s;
    }
    for (std::size_t bb = 0; bb < nb; ++bb) S_[(3 + bb) * w + c] -= dot(&Bv_[bb * N3], xc, n3t);
  }
  // LU of S with partial pivoting.
  for (std::size_t c = 0; c < w; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < w; ++r)
      if (std::fabs(S_[r * w + c]) > std::fabs(S_[p * w + c])) p = r;
    piv_[c] = static_cast<int>(p);
    if (!(std::isfinite(S_[p * w + c]) && S_[p * w + c] != 0.0)) return false;
    if (p != c)
      for (std::size_t j = 0; j < w; ++j) std::swap(S_[p * w + j], S_[c * w + j]);
    for (std::size_t r = c + 1; r < w; ++r) {
      const double f = S_[r * w + c] / S_[c * w + c];
      S_[r * w + c] = f;
      for (std::size_t j = c + 1; j < w; ++j) S_[r * w + j] -= f * S_[c * w + j];
    }
  }
  return true;
}

// Solves T y = v in place over links 0..N-2 (3 (N - 1) entries).
void ChainSolver::thomas_solve(double* v) const {
  const int Nt = N_ - 1;
  for (int i = 1; i < Nt; ++i) {
    const double* M = &M_[static_cast<std::size_t>(i) * 9];
    const double* y0 = v + 3 * (i - 1);
    double* y = v + 3 * i;
    const double a0 = y0[0], a1 = y0[1], a2 = y0[2];
    y[0] -= M[0] * a0 + M[1] * a1 + M[2] * a2;
    y[1] -= M[3] * a0 + M[4] * a1 + M[5] * a2;
    y[2] -= M[6] * a0 + M[7] * a1 + M[8] * a2;
  }
  double x1[3] = {0, 0, 0};
  for (int i = Nt - 1; i >= 0; --i) {
    const double* G = &Ginv_[static_cast<std::size_t>(i) * 9];
    double* y = v + 3 * i;
    double t[3];
    for (int a = 0; a < 3; ++a) t[a] = G[3 * a] * y[0] + G[3 * a + 1] * y[1] + G[3 * a + 2] * y[2];
    if (i < Nt - 1) {
      const double* P = &P_[static_cast<std::size_t>(i) * 9];
      for (int a = 0; a < 3; ++a) t[a] -= P[3 * a] * x1[0] + P[3 * a + 1] * x1[1] + P[3 * a + 2] * x1[2];
    }
    for (int a = 0; a < 3; ++a) y[a] = x1[a] = t[a];
  }
}

void ChainSolver::solve(const double* b, double* x) const {
  const std::size_t N3 = 3 * static_cast<std::size_t>(N_), nb = static_cast<std::size_t>(nb_),
                    w = static_cast<std::size_t>(w_);
  const double g = gamma_;
  // Positions: q = (b_q - a_qv v) / a_qq; first the b_q / a_qq part.
  for (std::size_t i = 0; i < static_cast<std::size_t>(N_); ++i)
    for (std::size_t k = 0; k < 3; ++k) tq_[3 * i + k] = b[6 * i + k] / aqq_[3 * i + k];
  // Reduced right-hand sides of the velocity rows and the border rows.
  for (std::size_t i = 0; i < static_cast<std::size_t>(N_); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      double s = 0;  // (J_vq t_q) over the three neighbours; A_vq = -gamma J_vq
      for (std::size_t sl = 0; sl < 3; ++sl) {
        const double* vq = &jac_[off_vq_ + (3 * i + sl) * 9 + 3 * k];
        const double* t = &tq_[3 * static_cast<std::size_t>(nbr_[3 * i + sl])];
        s += vq[0] * t[0] + vq[1] * t[1] + vq[2] * t[2];
      }
      r_[3 * i + k] = b[6 * i + 3 + k] + g * s;
    }
  for (std::size_t bb = 0; bb < nb; ++bb) r_[N3 + bb] = b[border_[bb]] + g * dot(&jac_[off_bq_ + bb * N3], tq_.data(), N3);
  // T z = r over links 0..N-2 (in place in r_), S e = r_E - Bt z, v = z - X e.
  const int Nt = N_ - 1;
  const std::size_t n3t = 3 * static_cast<std::size_t>(Nt);
  thomas_solve(r_.data());
  for (std::size_t k = 0; k < w; ++k) e_[k] = r_[n3t + k];
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b2 = 0; b2 < 3; ++b2) e_[a] -= Bt_[3 * a + b2] * r_[b2] + Bt_[9 + 3 * a + b2] * r_[n3t - 3 + b2];
  for (std::size_t bb = 0; bb < nb; ++bb) e_[3 + bb] -= dot(&Bv_[bb * N3], r_.data(), n3t);
  // The factorisation swapped whole rows: all interchanges first, then L.
  for (std::size_t c = 0; c < w; ++c) std::swap(e_[static_cast<std::size_t>(piv_[c])], e_[c]);
  for (std::size_t c = 0; c < w; ++c)
    for (std::size_t r = c + 1; r < w; ++r) e_[r] -= S_[r * w + c] * e_[c];
  for (std::size_t c = w; c-- > 0;) {
    double s = e_[c];
    for (std::size_t j = c + 1; j < w; ++j) s -= S_[c * w + j] * e_[j];
    e_[c] = s / S_[c * w + c];
  }
  for (std::size_t c = 0; c < w; ++c) {
    const double* xc = &X_[c * n3t];
    const double f = e_[c];
    for (std::size_t r = 0; r < n3t; ++r) r_[r] -= xc[r] * f;
  }
  for (std::size_t k = 0; k < 3; ++k) r_[n3t + k] = e_[k];
  for (std::size_t i = 0; i < static_cast<std::size_t>(N_); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const double v = r_[3 * i + k];
      x[6 * i + 3 + k] = v;
      x[6 * i + k] = tq_[3 * i + k] - ratio_[3 * i + k] * v;
    }
  for (std::size_t bb = 0; bb < nb; ++bb) x[border_[bb]] = e_[3 + bb];
  for (std::size_t j = 0; j < 2; ++j) {
    double s = 0;
    for (std::size_t bb = 0; bb < nb; ++bb) s += jac_[off_pb_ + j * nb + bb] * x[border_[bb]];
    x[angle_[j]] = (b[angle_[j]] + g * s) / (1.0 - g * jac_[off_pp_ + j]);
  }
  // Ledger: their own entries of x are zero until set (the rows' diagonals
  // are stored apart), and the rows are in ledger order.
  for (int k = 0; k < 5; ++k) x[ledger_[k]] = 0.0;
  for (std::size_t k = 0; k < 5; ++k)
    x[ledger_[k]] = (b[ledger_[k]] + g * dot(&jac_[off_lrow_ + k * static_cast<std::size_t>(n_)], x, static_cast<std::size_t>(n_))) /
                    (1.0 - g * jac_[off_ll_ + k]);
}

namespace {

struct Content {
  std::unique_ptr<ChainSolver> solver;
  std::vector<double> jac;  // the model's Jacobian in pattern order
  double gamma = 0;         // of the linear system chain_linear_system() set up
  long last_flag = 0;
};

Content* content(SUNLinearSolver S) { return static_cast<Content*>(S->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }

int setup(SUNLinearSolver S, SUNMatrix) {
  Content* c = content(S);
  // A singular pivot is recoverable: CVODE retries with a smaller step.
  c->last_flag = c->solver->factor(c->gamma) ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
  return static_cast<int>(c->last_flag);
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  content(S)->solver->solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
  return static_cast<int>(content(S)->last_flag = SUNLS_SUCCESS);
}

sunindextype last_flag(SUNLinearSolver S) { return content(S)->last_flag; }

int free_solver(SUNLinearSolver S) {
  if (S == nullptr) return SUNLS_SUCCESS;
  delete content(S);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

SUNMatrix_ID placeholder_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
void placeholder_destroy(SUNMatrix A) { SUNMatFreeEmpty(A); }

}  // namespace

SUNLinearSolver make_chain_linear_solver(const ChainModel& m, SUNContext ctx) {
  auto c = std::make_unique<Content>();
  c->solver = std::make_unique<ChainSolver>(m);  // std::logic_error if the pattern is not the chain's
  c->jac.assign(static_cast<std::size_t>(m.pattern().nnz()), 0.0);
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (S == nullptr) return nullptr;
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = last_flag;
  S->ops->free = free_solver;
  S->content = c.release();
  return S;
}

SUNMatrix make_chain_placeholder_matrix(SUNContext ctx) {
  SUNMatrix A = SUNMatNewEmpty(ctx);
  if (A == nullptr) return nullptr;
  A->ops->getid = placeholder_id;
  A->ops->destroy = placeholder_destroy;
  return A;
}

int chain_linear_system(SUNLinearSolver S, const ChainModel& m, double t, const double* y, bool jok, int* jcur,
                        double gamma) {
  Content* c = content(S);
  if (!jok) {
    m.jacobian(t, y, c->jac.data());
    c->solver->set_jacobian(c->jac.data());
  }
  *jcur = jok ? 0 : 1;
  c->gamma = gamma;
  return 0;
}

}  // namespace cvt::mbd::detail
