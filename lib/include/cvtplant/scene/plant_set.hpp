#pragma once
// Scene dispatch (docs/architecture.md#scene-dispatch): the one place where a
// scene's run-time feature mask becomes a compiled plant.
//
// RomPlantSet<T, Masks...> is the set of plants a program compiles in: the
// caller lists the feature masks it needs, so firmware carries only the
// physics it ships (e.g. RomPlantSet<float, rom_feature::axial>), and the
// host tools use AllRomPlants<T> (scene/all_plants.hpp), whose code is
// compiled once in lib/src. SceneSimulator<Set> owns suitably aligned storage
// for the largest plant of the set and builds the scene's plant in it:
// placement new, no heap, and a clear refusal when the scene needs a plant
// the set does not have.
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>

#include "cvtplant/plant/rom_simulator_interface.hpp"
#include "cvtplant/plant/rom_units.hpp"
#include "cvtplant/scalar/fixed.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt {

namespace plant_set_detail {
constexpr std::size_t max_of(std::size_t a) { return a; }
template <class... R>
constexpr std::size_t max_of(std::size_t a, std::size_t b, R... rest) {
  return max_of(a > b ? a : b, rest...);
}
}  // namespace plant_set_detail

// Why a feature mask has no plant in a set of scalar T, or nullptr if it has
// one (`found`). Wedging has no fixed-point scaling (docs/rom.md#wedging).
template <class T>
constexpr const char* missing_plant_reason(std::uint32_t features, bool found) {
  if (found) return nullptr;
  if (const char* why = rom_feature_conflict(features)) return why;
  if ((features & rom_feature::wedging) != 0u && !std::is_floating_point<T>::value)
    return "wedging runs in double or float only: there is no fixed-point plant with it";
  return "this program has no plant compiled for this feature set";
}

// The plants of the feature masks `Masks`, each also carrying the stateless
// features `Runtime` switched at set-up (CvtRom's run-time bits; 0 for
// firmware, which names every bit it ships at compile time): a scene runs on
// the plant whose mask is its own without the Runtime bits.
template <class T, std::uint32_t Runtime, std::uint32_t... Masks>
struct RomPlantSetRt {
  static_assert(sizeof...(Masks) > 0, "a plant set needs at least one feature mask");
  static_assert((((Masks & Runtime) == 0u) && ...), "a mask names no run-time bit");
  using Scalar = T;
  static constexpr std::uint32_t kRuntime = Runtime;
  static constexpr std::size_t kSize = plant_set_detail::max_of(sizeof(ErasedRomSimulator<T, Masks, Runtime>)...);
  static constexpr std::size_t kAlign = plant_set_detail::max_of(alignof(ErasedRomSimulator<T, Masks, Runtime>)...);

  // Replacing a plant in its storage needs no destructor call.
  static_assert((std::is_trivially_destructible<ErasedRomSimulator<T, Masks, Runtime>>::value && ...),
                "plants are built in place and never destroyed");

  static constexpr bool contains(std::uint32_t features) { return (((features & ~Runtime) == Masks) || ...); }

  // Constructs the plant of `features` in `storage` (kSize bytes aligned to
  // kAlign); nullptr if the set has none.
  static IRomSimulator<T>* build(std::uint32_t features, const RomParams& p, const RomSimConfig& c, void* storage) {
    IRomSimulator<T>* sim = nullptr;
    const std::uint32_t compiled = features & ~Runtime;
    (void)((compiled == Masks ? (sim = ::new (storage) ErasedRomSimulator<T, Masks, Runtime>(p, c, features), true)
                              : false) ||
           ...);
    return sim;
  }

  // Calls f(plant) with `sim`, a plant build() made, as its concrete
  // ErasedRomSimulator<T, F, Runtime> (F = sim.features() without the
  // run-time bits): what copies a whole
  // simulator, its state, cached contact, ledger, actuators, fault and frame
  // count, for a rollback that continues bit-identically (the FMU's state,
  // fmu/). False, without calling f, if the set has no plant of its features.
  template <class Sim, class Fn>
  static bool visit(Sim& sim, Fn&& f) {
    static_assert(std::is_same<std::remove_const_t<Sim>, IRomSimulator<T>>::value, "a plant of this set");
    const std::uint32_t compiled = sim.features() & ~Runtime;
    return ((compiled == Masks ? (f(concrete<Masks>(sim)), true) : false) || ...);
  }

 private:
  template <std::uint32_t F>
  static ErasedRomSimulator<T, F, Runtime>& concrete(IRomSimulator<T>& sim) {
    return static_cast<ErasedRomSimulator<T, F, Runtime>&>(sim);
  }
  template <std::uint32_t F>
  static const ErasedRomSimulator<T, F, Runtime>& concrete(const IRomSimulator<T>& sim) {
    return static_cast<const ErasedRomSimulator<T, F, Runtime>&>(sim);
  }
};

// A set of plants whose every feature is compiled in, as firmware ships them
// (RomPlantSet<float, rom_feature::axial>).
template <class T, std::uint32_t... Masks>
using RomPlantSet = RomPlantSetRt<T, 0u, Masks...>;

// Whether a fixed-point plant can take the scene's declared values: every
// input profile's declared range (profile_bound) and every initial value must
// fit the Q range in the plant's units (RomUnits), or it would be clipped when
// converted (docs/rom.md#fixed-point). Floating point takes any finite value.
template <class T>
SceneIssue check_scalar_range(const Scene& s) {
  if constexpr (is_fixed_point_v<T>) {
    const double lim = T::max().to_double();
    auto fits = [lim](double v) { return v < lim && v > -lim; };
    const char* why =
        "the profile goes beyond the fixed-point range (|value| < 32768 in q16.16): it would be clipped; run it in "
        "double or float";
    if (!fits(profile_bound(s.tau_in))) return SceneIssue{false, "tau_in", why};
    if (!fits(profile_bound(s.tau_load))) return SceneIssue{false, "tau_load", why};
    if (!fits(profile_bound(s.clamp))) return SceneIssue{false, "clamp", why};
    using U = RomUnits<T>;
    const RomInitial& x = s.initial;
    if (!(fits(x.omega1_rad_s) && fits(x.omega2_rad_s) && fits(x.x1_m / U::length_m) && fits(x.x2_m / U::length_m) &&
          fits(x.xd1_m_s) && fits(x.xd2_m_s)))
      return SceneIssue{false, "initial",
                        "beyond the fixed-point range (speeds |v| < 32768, displacements |x| < 32 m): it would be "
                        "clipped"};
    if ((s.features & rom_feature::tension) != 0u) {
      // docs/rom.md#tension: T_max in N, kL in RomUnits::tension_N.
      const char* tw = "beyond the fixed-point range: it would be clipped; run it in double or float";
      if (!fits(s.params.stop_tension_N)) return SceneIssue{false, "stop_tension_N", tw};
      if (!fits(s.params.chain_stiffness_N / U::tension_N)) return SceneIssue{false, "chain_stiffness_N", tw};
    }
  } else {
    (void)s;
  }
  return SceneIssue{};
}

// validate_scene, then whether the set has the scene's plant and its scalar
// can take the scene's values.
template <class Set>
SceneIssue check_scene_plant(const Scene& s) {
  const SceneIssue issue = validate_scene(s);
  if (!issue.ok) return issue;
  if (const char* why = missing_plant_reason<typename Set::Scalar>(s.features, Set::contains(s.features)))
    return SceneIssue{false, "features", why};
  return check_scalar_range<typename Set::Scalar>(s);
}

// A scene's simulator, built from a plant set into storage it owns.
// Neither copyable nor movable: the interface points into the storage.
template <class Set>
class SceneSimulator {
 public:
  using T = typename Set::Scalar;

  SceneSimulator() = default;
  SceneSimulator(const SceneSimulator&) = delete;
  SceneSimulator& operator=(const SceneSimulator&) = delete;

  // Checks the scene (check_scene_plant), then
  // builds the plant with `cfg` and resets it to the scene's start. On a
  // problem nothing is loaded and the issue says why.
  SceneIssue load(const Scene& s, const RomSimConfig& cfg) {
    sim_ = nullptr;
    const SceneIssue issue = check_scene_plant<Set>(s);
    if (!issue.ok) return issue;
    sim_ = Set::build(s.features, s.params, cfg, storage_);
    sim_->reset(s.initial, scene_inputs_at<T>(s, 0.0));
    return SceneIssue{};
  }
  SceneIssue load(const Scene& s) { return load(s, sim_config_of(s)); }

  bool loaded() const { return sim_ != nullptr; }
  IRomSimulator<T>& sim() { return *sim_; }
  const IRomSimulator<T>& sim() const { return *sim_; }

 private:
  alignas(Set::kAlign) unsigned char storage_[Set::kSize];
  IRomSimulator<T>* sim_ = nullptr;
};

}  // namespace cvt
