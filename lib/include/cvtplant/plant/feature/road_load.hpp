#pragma once
// Feature `road_load` (docs/rom.md#road-load): the driven shaft's load grows
// with its speed,
//   tau_load_total = tau_load + T0 tanh(w2 / w_eps) + c_v w2 + c_a w2 |w2|.
// No state; the load torque and its slope d tau / d w2 for the Jacobian.
// A plant type carries it compiled in, switched at set-up (the host
// dispatch, docs/rom.md#build-time), or not at all (then the load is the
// input alone and none of this code exists).
#include <cstdint>

#include "cvtplant/plant/rom_config.hpp"
#include "cvtplant/plant/rom_formulas.hpp"
#include "cvtplant/plant/rom_params.hpp"

namespace cvt {

// What a state's contact keeps of the road load: tanh(w2 / w_eps), which
// the right-hand side, the Jacobian and the ledger's load power at that
// state all read (docs/rom.md#cost); nothing without the feature.
template <class T, bool kCarried>
struct RomRoadLoadCache {};
template <class T>
struct RomRoadLoadCache<T, true> {
  T tanh_w{};
};

template <class Cfg, bool kCarried = Cfg::carried(rom_feature::road_load)>
class RomRoadLoad {
  using T = typename Cfg::Scalar;

 public:
  using Cache = RomRoadLoadCache<T, false>;
  RomRoadLoad(const RomParams&, std::uint32_t) {}
  template <class S>
  S load_torque(const S& tau_load, const S&) const {
    return tau_load;
  }
  void cache(const T&, Cache&) const {}
  T load_torque(const T& tau_load, const T&, const Cache&) const { return tau_load; }
  T load_torque_slope(const T&, const Cache&) const { return T(0); }
};

template <class Cfg>
class RomRoadLoad<Cfg, true> {
  using T = typename Cfg::Scalar;

 public:
  using Cache = RomRoadLoadCache<T, true>;
  RomRoadLoad(const RomParams& p, std::uint32_t features)
      : T0_(T(p.road_T0_Nm)),
        cv_(T(p.road_cv_Nms_rad)),
        ca_(T(p.road_ca_Nms2_rad2)),
        inv_w_eps_(T(1.0 / p.road_w_eps_rad_s)),
        on_(rom_feature_on<Cfg>(features, rom_feature::road_load)) {}

  // Load torque at the driven shaft [N m] (road_load_torque, rom_formulas.hpp).
  template <class S>
  S load_torque(const S& tau_load, const S& w2) const {
    if (!active()) return tau_load;
    return road_load_torque(tau_load, S(T0_), S(inv_w_eps_), S(cv_), S(ca_), w2);
  }

  // tanh(w2 / w_eps) at the state's w2, kept with its contact.
  void cache(const T& w2, Cache& c) const {
    if (active()) c.tanh_w = tanh(w2 * inv_w_eps_);
  }
  // The load torque at w2 from its cache c (bit for bit load_torque(tau_load, w2)).
  T load_torque(const T& tau_load, const T& w2, const Cache& c) const {
    if (!active()) return tau_load;
    return road_load_torque_at(tau_load, T0_, c.tanh_w, cv_, ca_, w2);
  }
  // d tau_load / d w2 [N m s/rad] at w2 from its cache c.
  T load_torque_slope(const T& w2, const Cache& c) const {
    if (!active()) return T(0);
    const T th = c.tanh_w;
    return T0_ * (T(1) - th * th) * inv_w_eps_ + cv_ + (ca_ + ca_) * abs(w2);
  }

 private:
  bool active() const {
    if constexpr (Cfg::on(rom_feature::road_load)) return true;
    return on_;
  }

  T T0_, cv_, ca_, inv_w_eps_;
  bool on_;
};

}  // namespace cvt
