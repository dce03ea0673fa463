#pragma once
// The plant behind one FMU instance: a scene's simulator of one scalar type,
// built through the scene dispatch (docs/architecture.md#scene-dispatch)
// into storage the engine owns. No heap, no exceptions.
//
// The prebuilt binary carries every plant (AllRomPlants of the three
// scalars, lib/src); a build from the FMU's sources/ defines
// CVT_FMU_FEATURES and CVT_FMU_SCALAR and compiles the scene's plant only.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <type_traits>

#include "cvtplant/fmu/variables.hpp"
#include "cvtplant/plant/rom_signals.hpp"
#include "cvtplant/scene/plant_set.hpp"
#include "cvtplant/scene/scene_runner.hpp"
#ifndef CVT_FMU_FEATURES
#include "cvtplant/scene/all_plants.hpp"
#endif

namespace cvt::fmu {

class Engine {
 public:
  // Checks the scene (validate_scene and the set's plant and range), builds
  // the plant and resets it to the scene's initial values under the inputs
  // `in` (input_count values, SI).
  virtual SceneIssue load(const Scene& s, const double* in) = 0;
  // One frame with the inputs held; the latched fault.
  virtual RomFault step(const double* in) = 0;
  virtual double signal(RomSignal id) const = 0;
  virtual RomFault fault() const = 0;
  virtual long frames() const = 0;
  virtual bool loaded() const = 0;
  // Constructs a copy of this engine, plant and all, in `storage`
  // (kEngineSize bytes aligned to kEngineAlign).
  virtual Engine* copy_into(void* storage) const = 0;
  // The plant's bytes (the FMU's serialised state, docs/fmu.md#state) and
  // their reading back into a plant loaded with the same scene.
  virtual std::size_t image_size() const = 0;
  virtual void image(unsigned char* out) const = 0;
  virtual bool restore_image(const unsigned char* in, std::size_t n) = 0;

 protected:
  Engine() = default;
  Engine(const Engine&) = default;
  ~Engine() = default;
};

template <class Set>
class EngineOf final : public Engine {
 public:
  using T = typename Set::Scalar;

  EngineOf() = default;
  // The copy builds its plant through the scene dispatch and assigns it the
  // other's simulator: a plant is only ever constructed by Set::build, so
  // this translation unit instantiates no plant's step (lib/src does).
  EngineOf(const EngineOf& o) : Engine(o), params_(o.params_), cfg_(o.cfg_), wedging_(o.wedging_) {
    if (o.sim_ == nullptr) return;
    sim_ = Set::build(o.sim_->features(), params_, cfg_, storage_);
    const IRomSimulator<T>& from = *o.sim_;
    Set::visit(*sim_, [&from](auto& plant) {
      using P = std::decay_t<decltype(plant)>;
      plant.concrete() = static_cast<const P&>(from).concrete();
    });
  }
  EngineOf& operator=(const EngineOf&) = delete;

  SceneIssue load(const Scene& s, const double* in) override {
    sim_ = nullptr;
    const SceneIssue issue = check_scene_plant<Set>(s);
    if (!issue.ok) return issue;
    params_ = s.params;
    cfg_ = sim_config_of(s);
    sim_ = Set::build(s.features, params_, cfg_, storage_);
    wedging_ = (s.features & rom_feature::wedging) != 0u;
    // The driven command before the reset: the driven actuator starts at it
    // (docs/rom.md#driven-clamping), as a run of the scene starts at its
    // set-up value.
    if (wedging_) sim_->set_driven_clamp_command(in[input_clamp_driven]);
    sim_->reset(s.initial, inputs(in));
    return SceneIssue{};
  }
  RomFault step(const double* in) override {
    if (wedging_) sim_->set_driven_clamp_command(in[input_clamp_driven]);
    return sim_->step_frame(inputs(in));
  }
  double signal(RomSignal id) const override { return rom_signal(sim_->outputs(), sim_->energy(), id); }
  RomFault fault() const override { return sim_ == nullptr ? RomFault::none : sim_->fault(); }
  long frames() const override { return sim_ == nullptr ? 0 : sim_->frames(); }
  bool loaded() const override { return sim_ != nullptr; }
  Engine* copy_into(void* storage) const override { return ::new (storage) EngineOf(*this); }

  // The simulator RomSimulator<T, F> holds values only (states, cached
  // contact, ledger, actuator forces, carries, counters; Eigen's fixed-size
  // arrays, no pointer, no reference, no virtual function), so its bytes are
  // its value in any instance of the same binary.
  std::size_t image_size() const override {
    std::size_t n = 0;
    if (sim_ != nullptr) Set::visit(*sim_, [&n](const auto& plant) { n = sizeof(plant.concrete()); });
    return n;
  }
  void image(unsigned char* out) const override {
    if (sim_ == nullptr) return;
    Set::visit(*sim_, [out](const auto& plant) {
      std::memcpy(out, static_cast<const void*>(&plant.concrete()), sizeof(plant.concrete()));
    });
  }
  bool restore_image(const unsigned char* in, std::size_t n) override {
    if (sim_ == nullptr || n != image_size()) return false;
    Set::visit(*sim_, [in](auto& plant) {
      std::memcpy(static_cast<void*>(&plant.concrete()), in, sizeof(plant.concrete()));
    });
    return true;
  }

 private:
  static RomInputs<T> inputs(const double* in) {
    RomInputs<T> u;
    u.tau_in_Nm = T(in[input_tau_in]);
    u.tau_load_Nm = T(in[input_tau_load]);
    u.clamp_N = T(in[input_clamp]);
    return u;
  }

  RomParams params_{};
  RomSimConfig cfg_{};
  alignas(Set::kAlign) unsigned char storage_[Set::kSize];
  IRomSimulator<T>* sim_ = nullptr;
  bool wedging_ = false;
};

// The plant sets of this build, per scalar.
#ifdef CVT_FMU_FEATURES
#ifndef CVT_FMU_SCALAR
#error "CVT_FMU_FEATURES needs CVT_FMU_SCALAR (0 double, 1 float, 2 q16.16)"
#endif
#if CVT_FMU_SCALAR == 0
using FmuEngine = EngineOf<RomPlantSet<double, CVT_FMU_FEATURES>>;
#elif CVT_FMU_SCALAR == 1
using FmuEngine = EngineOf<RomPlantSet<float, CVT_FMU_FEATURES>>;
#else
using FmuEngine = EngineOf<RomPlantSet<q16_16, CVT_FMU_FEATURES>>;
#endif
inline constexpr std::size_t kEngineSize = sizeof(FmuEngine);
inline constexpr std::size_t kEngineAlign = alignof(FmuEngine);
inline constexpr ScalarKind kBuiltScalar = CVT_FMU_SCALAR == 0   ? ScalarKind::f64
                                           : CVT_FMU_SCALAR == 1 ? ScalarKind::f32
                                                                 : ScalarKind::q16_16;
// Constructs the engine of a scene's scalar in storage, or nullptr (with why)
// when this build has none.
inline Engine* make_engine(const Scene& s, void* storage, const char** why) {
  if (s.scalar != kBuiltScalar || s.features != static_cast<std::uint32_t>(CVT_FMU_FEATURES)) {
    *why = "this build of the FMU's sources has another scene's scalar or features (CVT_FMU_SCALAR, CVT_FMU_FEATURES)";
    return nullptr;
  }
  return ::new (storage) FmuEngine();
}
#else
constexpr std::size_t larger_of(std::size_t a, std::size_t b) { return a > b ? a : b; }
inline constexpr std::size_t kEngineSize = larger_of(
    sizeof(EngineOf<AllRomPlants<double>>),
    larger_of(sizeof(EngineOf<AllRomPlants<float>>), sizeof(EngineOf<AllRomPlants<q16_16>>)));
inline constexpr std::size_t kEngineAlign = larger_of(
    alignof(EngineOf<AllRomPlants<double>>),
    larger_of(alignof(EngineOf<AllRomPlants<float>>), alignof(EngineOf<AllRomPlants<q16_16>>)));
inline Engine* make_engine(const Scene& s, void* storage, const char** why) {
  (void)why;
  switch (s.scalar) {
    case ScalarKind::f64: return ::new (storage) EngineOf<AllRomPlants<double>>();
    case ScalarKind::f32: return ::new (storage) EngineOf<AllRomPlants<float>>();
    case ScalarKind::q16_16: return ::new (storage) EngineOf<AllRomPlants<q16_16>>();
  }
  return nullptr;
}
#endif

}  // namespace cvt::fmu
