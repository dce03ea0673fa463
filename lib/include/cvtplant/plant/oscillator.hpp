#pragma once
// The seed's 2-DOF stick-slip oscillator, Eq. 9 (docs/physics.md#oscillator):
//
//   m1 x1'' + (c1+c2) x1' - c2 x2' + (k1+k2) x1 - k2 x2 = -phi(x1' - v) m1 g
//   m2 x2'' - c2 x1' + (c1+c2) x2' - k2 x1 + (k1+k2) x2 = -phi(x2' - v) m2 g
//
// with phi(v_rel) = mu(|v_rel|) s(v_rel) (friction_law.hpp) and a belt moving
// at v. State x = [x1 v1 x2 v2] (m, m/s). Heap-free; any scalar type.
#include <cstdint>

#include <Eigen/Core>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/integrate/system.hpp"
#include "cvtplant/physics/seed.hpp"

namespace cvt {

template <class T>
struct OscillatorParams {
  // Seed section 3 (physics/seed.hpp).
  T m1_kg = T(seed::kOscMass_kg), m2_kg = T(seed::kOscMass_kg);
  T k1_N_m = T(seed::kOscStiffness_N_m), k2_N_m = T(seed::kOscStiffness_N_m);
  T c1_Ns_m = T(seed::kOscDamping_Ns_m), c2_Ns_m = T(seed::kOscDamping_Ns_m);
  T belt_speed_m_s = T(seed::kOscBeltSpeed_m_s);
  T g_m_s2 = T(kGravity_m_s2);
  FrictionParams<T> friction = friction_presets::oscillator_coulomb<T>();

  // The seed's section-3 parameter set with the given friction law.
  static constexpr OscillatorParams seed_section3(const FrictionParams<T>& f) {
    OscillatorParams p;
    p.friction = f;
    return p;
  }

  template <class U>
  OscillatorParams<U> cast() const {
    OscillatorParams<U> p;
    p.m1_kg = U(static_cast<double>(m1_kg));
    p.m2_kg = U(static_cast<double>(m2_kg));
    p.k1_N_m = U(static_cast<double>(k1_N_m));
    p.k2_N_m = U(static_cast<double>(k2_N_m));
    p.c1_Ns_m = U(static_cast<double>(c1_Ns_m));
    p.c2_Ns_m = U(static_cast<double>(c2_Ns_m));
    p.belt_speed_m_s = U(static_cast<double>(belt_speed_m_s));
    p.g_m_s2 = U(static_cast<double>(g_m_s2));
    p.friction = friction.template cast<U>();
    return p;
  }
};

template <class T>
class StickSlipOscillator {
 public:
  using Scalar = T;
  static constexpr int kStates = 4;
  static constexpr std::uint32_t kPositionMask = 0b0101u;  // x1, x2
  using State = Eigen::Matrix<T, 4, 1>;
  using Jacobian = Eigen::Matrix<T, 4, 4>;

  explicit StickSlipOscillator(const OscillatorParams<T>& p)
      : p_(p),
        inv_m1_(T(1) / p.m1_kg),
        inv_m2_(T(1) / p.m2_kg),
        normal1_N_(p.m1_kg * p.g_m_s2),
        normal2_N_(p.m2_kg * p.g_m_s2) {}

  const OscillatorParams<T>& params() const { return p_; }

  // Friction force on mass i at slip velocity v_rel = v_i - v (Eq. 9 right-hand side).
  template <class S>
  S friction_force_N(const S& v_rel_m_s, const T& normal_N) const {
    return -friction_characteristic(p_.friction, v_rel_m_s) * S(normal_N);
  }

  template <class S>
  void derivative(const Eigen::Matrix<S, 4, 1>& x, Eigen::Matrix<S, 4, 1>& dxdt) const {
    const S x1 = x(0), v1 = x(1), x2 = x(2), v2 = x(3);
    const S v(p_.belt_speed_m_s);
    const S F1 = friction_force_N(v1 - v, normal1_N_);
    const S F2 = friction_force_N(v2 - v, normal2_N_);
    // Spring and damper forces of Eq. 8/9, grouped per element so that the
    // rounding is the same for the lumps of the drive-train plant.
    const S spring_mid = S(p_.k2_N_m) * (x1 - x2) + S(p_.c2_Ns_m) * (v1 - v2);
    const S ground1 = S(p_.k1_N_m) * x1 + S(p_.c1_Ns_m) * v1;
    const S ground2 = S(p_.k1_N_m) * x2 + S(p_.c1_Ns_m) * v2;
    dxdt(0) = v1;
    dxdt(1) = (F1 - ground1 - spring_mid) * S(inv_m1_);
    dxdt(2) = v2;
    dxdt(3) = (F2 - ground2 + spring_mid) * S(inv_m2_);
  }

  // Analytic Jacobian (docs/physics.md#oscillator-jacobian).
  void jacobian(const State& x, Jacobian& J) const {
    const T v = p_.belt_speed_m_s;
    const T dF1 = -friction_characteristic_slope(p_.friction, T(x(1) - v)) * normal1_N_;
    const T dF2 = -friction_characteristic_slope(p_.friction, T(x(3) - v)) * normal2_N_;
    const T k12 = p_.k1_N_m + p_.k2_N_m;
    const T c12 = p_.c1_Ns_m + p_.c2_Ns_m;
    J.setZero();
    J(0, 1) = T(1);
    J(1, 0) = -k12 * inv_m1_;
    J(1, 1) = (dF1 - c12) * inv_m1_;
    J(1, 2) = p_.k2_N_m * inv_m1_;
    J(1, 3) = p_.c2_Ns_m * inv_m1_;
    J(2, 3) = T(1);
    J(3, 0) = p_.k2_N_m * inv_m2_;
    J(3, 1) = p_.c2_Ns_m * inv_m2_;
    J(3, 2) = -k12 * inv_m2_;
    J(3, 3) = (dF2 - c12) * inv_m2_;
  }

  // The sliding equilibrium of Eq. 9 when both masses slide backwards against
  // the belt at rest (v_i = 0): for equal masses/springs x1 = x2 = x*, with
  // k1 x* = mu(v) s(v) m g (docs/physics.md#oscillator-equilibrium). Valid for
  // m1 = m2, k1, k2 arbitrary (the coupling spring carries no force).
  T sliding_equilibrium_m() const {
    const T v = p_.belt_speed_m_s;
    return friction_characteristic(p_.friction, v) * normal1_N_ / p_.k1_N_m;
  }

 private:
  OscillatorParams<T> p_;
  T inv_m1_, inv_m2_;
  T normal1_N_, normal2_N_;
};

}  // namespace cvt
