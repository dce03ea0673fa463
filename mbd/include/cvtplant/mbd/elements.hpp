#pragma once
// The force elements of the chain model, written once for double (right-hand
// side) and for forward-mode dual numbers (exact element Jacobians):
//   joint:   zero-length bushing between consecutive links' pins, spring k and
//            a frame-invariant damper p      (docs/mbd.md#joint)
//   contact: bolt of a link in a pulley groove: bolt spring (seed Eq. 5) on a
//            deformed groove (Eq. 3-4), normal force with the slip angle
//            (Eq. 7), friction (Eq. 6) along the slip direction
//                                             (docs/mbd.md#contact)
// Link state order: x, y, theta, vx, vy, omega (centre of mass, SI units).
//
// Elementary functions are the core's, called unqualified
// (docs/architecture.md#scalar-math): cvt::dm's deterministic math for
// double, the chain rule next to the dual type for Dual<double, N>.
#include "cvtplant/autodiff/dual.hpp"
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/math/detmath.hpp"

namespace cvt::mbd::detail {

// The value of either scalar kind, for branches (contact or not).
inline double value(double x) { return x; }
template <int N>
double value(const Dual<double, N>& x) {
  return x.v;
}

// |(x, y)| for a vector that may vanish: a slip velocity is exactly zero
// while a pulley is held and the chain rests, where sqrt's slope 1/(2 sqrt)
// would make the derivative 0 x inf. There the slope is taken as 0 (the
// norm's subgradient at its kink).
inline double norm(double x, double y) { return sqrt(x * x + y * y); }
template <int N>
Dual<double, N> norm(const Dual<double, N>& x, const Dual<double, N>& y) {
  const Dual<double, N> sq = x * x + y * y;
  if (sq.v > 0) return sqrt(sq);
  return Dual<double, N>(0.0);
}

// Friction per unit slip speed, k(s) = mu(s) sgn(s) / s for s = |g| >= 0, with
// the core's law and sign smoothing (seed Eq. 6 and 2/pi atan(lambda s)); the
// friction force is then -N k(|g|) g, along the slip. At s = 0 the limit
// mu(0) * 2 lambda / pi. docs/mbd.md#contact
inline double friction_per_speed(const FrictionParams<double>& fp, double s) {
  if (s > 0) return friction_characteristic(fp, s) / s;
  return friction_characteristic_and_slope(fp, 0.0).slope;
}
template <int N>
Dual<double, N> friction_per_speed(const FrictionParams<double>& fp, const Dual<double, N>& s) {
  // dk/ds = (phi'(s) s - phi(s)) / s^2; below the smoothing layer's scale the
  // quotient loses digits, so it is taken at the layer's edge / 1e6 there
  // (the Jacobian only steers Newton's iteration).
  const double s_min = 1e-6 / fp.lambda_s_m;
  const double se = s.v > s_min ? s.v : s_min;
  const FrictionEval<double> e = friction_characteristic_and_slope(fp, se);
  const double k = friction_per_speed(fp, s.v);
  const double dk = (e.slope * se - e.phi) / (se * se);
  Dual<double, N> r(k);
  for (int i = 0; i < N; ++i) r.d[i] = dk * s.d[i];
  return r;
}

// Link constants shared by the elements.
struct ChainConst {
  double half_length_m;  // L/2: pins at +-L/2 along the link axis
  double k_N_m, p_Ns_m;  // joint spring and damper
  double c_rot_Nms = 0;  // articulation damper on the two links' relative rotation rate (0: none)
  double Kb_N_m;         // bolt spring
  FrictionParams<double> friction;
};

template <class S>
struct JointForces {
  S fa[3], fb[3];     // (fx, fy, torque) on the leading link a and the trailing link b
  S tension_N;        // force along the joint axis (positive pulls the pins together)
  S stretch_m;        // |Delta|
  S potential_J;      // k |Delta|^2 / 2
  S dissipation_W;    // p |d|^2
};

// Link a's front pin joined to link b's rear pin; (ca, sa), (cb, sb) are the
// cosine and sine of the links' angles (computed once per link by the caller).
// kOutputs false: the forces and the dissipation only (the right-hand side);
// tension, stretch and potential are left zero. docs/mbd.md#joint
template <class S, bool kOutputs = true>
JointForces<S> joint_forces(const ChainConst& c, const S* a, const S& ca, const S& sa, const S* b, const S& cb,
                            const S& sb) {
  const double h = c.half_length_m;
  // Stretch Delta = rear pin of b - front pin of a, and its rate.
  const S dx = (b[0] - h * cb) - (a[0] + h * ca);
  const S dy = (b[1] - h * sb) - (a[1] + h * sa);
  // d Delta / d theta for each link (pin offsets rotate with the link).
  const S gax = h * sa, gay = -h * ca;  // from a's front pin: -(d/dtheta)(h ca, h sa)
  const S gbx = h * sb, gby = -h * cb;  // from b's rear pin:   (d/dtheta)(-h cb, -h sb)
  const S ddx = (b[3] - a[3]) + gbx * b[5] + gax * a[5];
  const S ddy = (b[4] - a[4]) + gby * b[5] + gay * a[5];
  // Objective stretch rate: the change of Delta seen from the joint's frame,
  // which turns at the mean rate of the two links.
  const S wm = 0.5 * (a[5] + b[5]);
  const S rx = ddx + wm * dy;  // d = dDelta/dt - wm (z x Delta), z x Delta = (-dy, dx)
  const S ry = ddy - wm * dx;
  // Generalised forces -dV/dq - dR/dqdot, V = k|Delta|^2/2, R = p|d|^2/2.
  const S Fx = c.k_N_m * dx + c.p_Ns_m * rx;
  const S Fy = c.k_N_m * dy + c.p_Ns_m * ry;
  JointForces<S> f;
  f.fa[0] = Fx;
  f.fa[1] = Fy;
  f.fb[0] = -Fx;
  f.fb[1] = -Fy;
  // d d / d omega = g - (z x Delta)/2 for each link.
  const S hx = -0.5 * (-dy), hy = -0.5 * dx;
  // Articulation damper (docs/mbd.md#joint): a moment c_rot (omega_b - omega_a)
  // on a and its opposite on b, R_rot = c_rot (omega_a - omega_b)^2 / 2.
  const S wrel = a[5] - b[5];
  f.fa[2] = -(c.k_N_m * (dx * gax + dy * gay)) - c.p_Ns_m * (rx * (gax + hx) + ry * (gay + hy)) - c.c_rot_Nms * wrel;
  f.fb[2] = -(c.k_N_m * (dx * gbx + dy * gby)) - c.p_Ns_m * (rx * (gbx + hx) + ry * (gby + hy)) + c.c_rot_Nms * wrel;
  if constexpr (kOutputs) {
    f.stretch_m = norm(dx, dy);
    f.tension_N = value(f.stretch_m) > 0 ? (Fx * dx + Fy * dy) / f.stretch_m : S(0.0);
    f.potential_J = 0.5 * c.k_N_m * (dx * dx + dy * dy);
  } else {
    f.stretch_m = f.tension_N = f.potential_J = S(0.0);
  }
  f.dissipation_W = c.p_Ns_m * (rx * rx + ry * ry) + c.c_rot_Nms * wrel * wrel;
  return f;
}

// A pulley as the contact sees it.
struct PulleyConst {
  double ox_m, oy_m;         // centre
  double width_at_axis_m;    // 2 r_p tan(beta0): the bolt is unloaded at the pitch radius
  double beta0_rad;
  double cos_beta0, sin_beta0;  // of beta0, the core's cos and sin
  double half_amp_rad;       // Delta/2 of Eq. 3 (0: no deformation); at most 0.01 rad (flank_cos_sin)
  double wx, wy;             // unit vector towards the wrap angle of maximum deformation
  double reject_radius_m;    // beyond this radius no bolt can be compressed
};

// cos(beta) and sin(beta) of the flank angle beta = beta0 + d of Eq. 3, d the
// deformation's share (|d| <= Delta/2, 2.8e-4 rad for the seed's radii):
// the angle-sum formula with cos d to d^6 and sin d to d^7, whose next terms
// (d^8/8!, d^9/9!) are below 1e-20 relative for |d| <= 0.01 rad (the model
// requires it): correct to the rounding of double (within an ulp or two of
// cos(beta), sin(beta)), without two sine/cosine evaluations per contact.
template <class S>
void flank_cos_sin(const PulleyConst& pc, const S& d, S& cb, S& sb) {
  const S d2 = d * d;
  const S cd = 1.0 - d2 * (1.0 / 2.0 - d2 * (1.0 / 24.0 - d2 * (1.0 / 720.0)));
  const S sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0 - d2 * (1.0 / 5040.0))));
  cb = pc.cos_beta0 * cd - pc.sin_beta0 * sd;
  sb = pc.sin_beta0 * cd + pc.cos_beta0 * sd;
}

template <class S>
struct ContactForces {
  bool active = false;
  S f[3];               // (fx, fy, torque) on the link
  S pulley_moment_Nm;   // on the pulley, about its axis
  S bolt_force_N;       // F_b, pushes the sheaves apart (axial force)
  S dissipation_W;      // friction power lost, >= 0
  S potential_J;        // K_b c^2 / 2
  S normal_N;           // N on each flank (Eq. 7)
  S slip_t_m_s;         // tangential slip, bolt minus sheave
  S radius_m;           // bolt radius
};

// Bolt at the front pin of link q (angle cosine cq, sine sq) against pulley
// pc turning at omega, the movable sheave opened by s_open. docs/mbd.md#contact
template <class S>
ContactForces<S> contact_forces(const ChainConst& c, const PulleyConst& pc, const S* q, const S& cq, const S& sq,
                                const S& omega, const S& s_open) {
  ContactForces<S> out;
  const double h = c.half_length_m;
  const S rx = q[0] + h * cq - pc.ox_m;
  const S ry = q[1] + h * sq - pc.oy_m;
  const double rxv = value(rx), ryv = value(ry);
  if (rxv * rxv + ryv * ryv >= pc.reject_radius_m * pc.reject_radius_m) return out;
  const S rho = norm(rx, ry);
  const S ex = rx / rho, ey = ry / rho;  // radial unit vector
  const S tx = -ey, ty = ex;             // tangential (running direction)
  // Eq. 3: beta = beta0 + Delta/2 cos(zeta - theta_c), zeta measured from the
  // wrap entry; cos(zeta - theta_c) = e_rho . w.
  S cb, sb;
  flank_cos_sin(pc, pc.half_amp_rad * (ex * pc.wx + ey * pc.wy), cb, sb);
  const S tanb = sb / cb;
  // Eq. 5 with the local groove width z + u = l_b + 2 rho tan(beta) - 2 r_p tan(beta0) + s:
  // compression l_b - z - u = 2 r_p tan(beta0) - 2 rho tan(beta) - s.
  const S comp = pc.width_at_axis_m - 2.0 * rho * tanb - s_open;
  if (!(value(comp) > 0)) return out;
  out.active = true;
  const S Fb = c.Kb_N_m * comp;
  // -grad V of V = K_b c^2/2: radial 2 F_b tan(beta) and, from the deformation's
  // variation round the wrap, a tangential 2 F_b rho sec^2(beta) dbeta/ds.
  const S wt = tx * pc.wx + ty * pc.wy;
  const S Fcr = 2.0 * Fb * tanb;
  const S Fct = 2.0 * Fb * pc.half_amp_rad * wt / (cb * cb);
  // Slip of the bolt against the sheave, in the sheave plane (Fig. 5-6).
  const S vx = q[3] - h * sq * q[5];
  const S vy = q[4] + h * cq * q[5];
  const S gx = vx + omega * ry;  // v - omega z x r
  const S gy = vy - omega * rx;
  const S gr = gx * ex + gy * ey;
  const S gt = gx * tx + gy * ty;
  const S gs = norm(gr, gt);
  const S kf = friction_per_speed(c.friction, gs);
  // Eq. 7: N = F_r tan(beta) + F_b / cos(beta), F_r = -mu N sgn sin(gamma) = -k N g_r.
  const S N = Fb / (cb * (1.0 + kf * gr * tanb));
  const S fr = -kf * N * gr;  // per flank, along the flank's meridian (outwards)
  const S ft = -kf * N * gt;  // per flank, tangential
  // In-plane resultant on the link: both flanks, the meridian component
  // projected into the plane with the normal's radial part: 2 f_r / cos(beta).
  const S Fr = Fcr + 2.0 * fr / cb;
  const S Ft = Fct + 2.0 * ft;
  out.f[0] = Fr * ex + Ft * tx;
  out.f[1] = Fr * ey + Ft * ty;
  out.f[2] = h * (cq * out.f[1] - sq * out.f[0]);
  // The sheaves carry the friction reaction; the deformation's tangential
  // term is held by the frame that fixes the deformation pattern.
  out.pulley_moment_Nm = -2.0 * rho * ft;
  out.bolt_force_N = Fb;
  out.dissipation_W = 2.0 * kf * N * (gr * gr / cb + gt * gt);
  out.potential_J = 0.5 * c.Kb_N_m * comp * comp;
  out.normal_N = N;
  out.slip_t_m_s = gt;
  out.radius_m = rho;
  return out;
}

}  // namespace cvt::mbd::detail
