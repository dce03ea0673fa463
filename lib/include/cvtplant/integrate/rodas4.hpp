#pragma once
// RODAS4: the adaptive, L-stable, stiffly accurate Rosenbrock method of
// order 4 with an embedded order-3 solution and a continuous (dense) output
// of order 3 (Hairer & Wanner, Solving ODEs II, sec. IV.7; coefficients as
// published there). For inputs known in advance (docs/numerics.md#adaptive).
//
// One step of h from x, for an autonomous system x' = f(x) with Jacobian J
// at x and W = I - gamma h J (the W solver of integrate/rosenbrock.hpp, so
// the plant's block-eliminated solve serves it unchanged):
//
//   W g_i = gamma (h f(x + sum_{j<i} a_ij g_j) + sum_{j<i} c_ij g_j),   i = 1..6
//   (stages 5 and 6 are evaluated at x + sum a_5j g_j and at that + g_5)
//   x_new = x + sum a_5j g_j + g_5 + g_6;     error estimate e = g_6
//   x(t + s h) = (1 - s) x + s (x_new + (1 - s)(q3 + s q4)),
//     q3 = sum d_2j g_j,  q4 = sum d_3j g_j
//
// Cost per step: one Jacobian, one factorisation, six right-hand sides and
// six solves; a rejected step repeats the factorisation with the new h and
// everything after it. Heap-free, fixed-size Eigen; the same operations in
// the same order on every run, so results are bit-for-bit repeatable.
#include <Eigen/Core>

#include "cvtplant/integrate/system.hpp"
#include "cvtplant/math/detmath.hpp"

namespace cvt {

// The published coefficients (transformed form, autonomous system).
struct Rodas4Coefficients {
  static constexpr double gamma = 0.25;
  static constexpr double a21 = 0.1544000000000000e+01;
  static constexpr double a31 = 0.9466785280815826e+00, a32 = 0.2557011698983284e+00;
  static constexpr double a41 = 0.3314825187068521e+01, a42 = 0.2896124015972201e+01,
                          a43 = 0.9986419139977817e+00;
  static constexpr double a51 = 0.1221224509226641e+01, a52 = 0.6019134481288629e+01,
                          a53 = 0.1253708332932087e+02, a54 = -0.6878860361058950e+00;
  static constexpr double c21 = -0.5668800000000000e+01;
  static constexpr double c31 = -0.2430093356833875e+01, c32 = -0.2063599157091915e+00;
  static constexpr double c41 = -0.1073529058151375e+00, c42 = -0.9594562251023355e+01,
                          c43 = -0.2047028614809616e+02;
  static constexpr double c51 = 0.7496443313967647e+01, c52 = -0.1024680431464352e+02,
                          c53 = -0.3399990352819905e+02, c54 = 0.1170890893206160e+02;
  static constexpr double c61 = 0.8083246795921522e+01, c62 = -0.7981132988064893e+01,
                          c63 = -0.3152159432874371e+02, c64 = 0.1631930543123136e+02,
                          c65 = -0.6058818238834054e+01;
  static constexpr double d21 = 0.1012623508344586e+02, d22 = -0.7487995877610167e+01,
                          d23 = -0.3480091861555747e+02, d24 = -0.7992771707568823e+01,
                          d25 = 0.1025137723295662e+01;
  static constexpr double d31 = -0.6762803392801253e+00, d32 = 0.6087714651680015e+01,
                          d33 = 0.1643084320892478e+02, d34 = 0.2476722511418386e+02,
                          d35 = -0.6594389125716872e+01;
};

// Work done, for benchmarks and the CLI's summary.
struct Rodas4Work {
  long accepted = 0, rejected = 0;
  long rhs = 0, jacobians = 0, factorizations = 0, solves = 0;
};

// What a step leaves for the dense output of [t, t + h].
template <class Sys>
struct Rodas4Dense {
  StateOf<Sys> x0, x1, q3, q4;
  // x at t + s h, 0 <= s <= 1.
  StateOf<Sys> at(double s) const {
    const double s1 = 1.0 - s;
    return x0 * s1 + s * (x1 + s1 * (q3 + s * q4));
  }
};

namespace rodas4_detail {
template <class T>
struct same {
  using type = T;
};
}  // namespace rodas4_detail

// One RODAS4 step of h from x, whose f(x) is `f0` and Jacobian `J`. Writes
// the new state to `x_new` and returns the error norm
//   sqrt(mean_i (e_i / (atol_i + rtol max(|x_i|, |x_new_i|)))^2)
// (accept the step if it is <= 1). `w` is factorised for this h. With
// `dense`, the dense output of the step is stored there.
template <class Sys, class WSolver>
double rodas4_step(const Sys& sys, const StateOf<Sys>& x, const StateOf<Sys>& f0, const JacobianOf<Sys>& J,
                   double h, WSolver& w, const StateOf<Sys>& atol, double rtol, StateOf<Sys>& x_new,
                   typename rodas4_detail::same<Rodas4Dense<Sys>>::type* dense, Rodas4Work& work) {
  using C = Rodas4Coefficients;
  using V = StateOf<Sys>;
  constexpr double g = C::gamma;
  w.factor(J, g * h);
  ++work.factorizations;
  V f;
  const V g1 = w.solve(V((g * h) * f0));
  V xs = x + C::a21 * g1;
  sys.derivative(xs, f);
  const V g2 = w.solve(V(g * (h * f + C::c21 * g1)));
  xs = x + C::a31 * g1 + C::a32 * g2;
  sys.derivative(xs, f);
  const V g3 = w.solve(V(g * (h * f + C::c31 * g1 + C::c32 * g2)));
  xs = x + C::a41 * g1 + C::a42 * g2 + C::a43 * g3;
  sys.derivative(xs, f);
  const V g4 = w.solve(V(g * (h * f + C::c41 * g1 + C::c42 * g2 + C::c43 * g3)));
  xs = x + C::a51 * g1 + C::a52 * g2 + C::a53 * g3 + C::a54 * g4;
  sys.derivative(xs, f);
  const V g5 = w.solve(V(g * (h * f + C::c51 * g1 + C::c52 * g2 + C::c53 * g3 + C::c54 * g4)));
  xs += g5;
  sys.derivative(xs, f);
  const V g6 = w.solve(V(g * (h * f + C::c61 * g1 + C::c62 * g2 + C::c63 * g3 + C::c64 * g4 + C::c65 * g5)));
  x_new = xs + g6;
  work.rhs += 5;
  work.solves += 6;
  if (dense != nullptr) {
    dense->x0 = x;
    dense->x1 = x_new;
    dense->q3 = C::d21 * g1 + C::d22 * g2 + C::d23 * g3 + C::d24 * g4 + C::d25 * g5;
    dense->q4 = C::d31 * g1 + C::d32 * g2 + C::d33 * g3 + C::d34 * g4 + C::d35 * g5;
  }
  double sum = 0.0;
  for (int i = 0; i < x.size(); ++i) {
    const double ax = x(i) < 0 ? -x(i) : x(i);
    const double an = x_new(i) < 0 ? -x_new(i) : x_new(i);
    const double sc = atol(i) + rtol * (ax > an ? ax : an);
    const double e = g6(i) / sc;
    sum += e * e;
  }
  const double err = dm::sqrt(sum / static_cast<double>(x.size()));
  // NaN anywhere fails the step (the caller shrinks h).
  return err == err ? err : 1e300;
}

// The step-size factor after a step with error norm err (order 4: exponent
// 1/4), bounded to [0.2, 6], with a safety factor 0.9; after a rejection the
// next step may not grow (Hairer & Wanner IV.8).
inline double rodas4_step_factor(double err, bool after_reject) {
  double fac = err > 0.0 ? 0.9 / dm::sqrt(dm::sqrt(err)) : 6.0;
  if (fac > 6.0) fac = 6.0;
  if (fac < 0.2) fac = 0.2;
  if (after_reject && fac > 1.0) fac = 1.0;
  return fac;
}

}  // namespace cvt
