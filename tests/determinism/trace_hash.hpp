#pragma once
// Bit-exact trace fingerprints for the determinism checks
// (docs/architecture.md#determinism). Heap-free so the Cortex-M test image
// computes the very same hash as the host and aarch64 builds.
//
// The hash is FNV-1a (64 bit) over the bit patterns of every state component
// after every step, fed byte by byte in little-endian order so the result does
// not depend on the host's byte order.
#include <cstdint>
#include <cstring>

#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_runner.hpp"

namespace cvt::testing {

class TraceHash {
 public:
  void add_bytes(std::uint64_t bits, int n_bytes) {
    for (int i = 0; i < n_bytes; ++i) {
      h_ ^= (bits >> (8 * i)) & 0xffu;
      h_ *= 0x100000001b3ull;
    }
  }
  void add(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    add_bytes(b, 8);
  }
  void add(float v) {
    std::uint32_t b;
    std::memcpy(&b, &v, sizeof b);
    add_bytes(b, 4);
  }
  template <int F>
  void add(Fixed<F> v) {
    add_bytes(static_cast<std::uint32_t>(v.raw()), 4);
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

// The reference scenario: the seed's Stribeck oscillator from [0 3 0 6]
// (a stick-slip limit cycle, so it exercises stick, slip and every branch of
// the friction law) for `steps` steps of `h` seconds.
template <class T>
std::uint64_t oscillator_trace_hash(Method m, double h_s, long steps) {
  const auto p = OscillatorParams<double>::seed_section3(friction_presets::oscillator_stribeck<double>());
  const StickSlipOscillator<T> sys(p.template cast<T>());
  typename StickSlipOscillator<T>::State x;
  x << T(0.0), T(3.0), T(0.0), T(6.0);
  const T h(h_s);
  TraceHash hash;
  for (long i = 0; i < steps; ++i) {
    step(m, sys, x, h);
    for (int k = 0; k < 4; ++k) hash.add(x(k));
  }
  return hash.value();
}

// The reduced-order plant (docs/rom.md): a built-in scene at its real-time
// default (one ROS2 step per 1 ms frame, energy watchdog on) for
// `seconds`; every state after every frame, then the fault code. Fixed point
// hashes its internal units (RomUnits), which are part of what must agree.
template <class T, std::uint32_t F>
std::uint64_t rom_trace_hash(const char* scene_name, double seconds) {
  Scene s = *find_builtin_scene(scene_name);
  s.features = F;  // the scene's inputs and parameters on the plant of mask F
  s.t_end_s = seconds;
  TraceHash hash;
  const RomFault fault = run_scene<T, F>(s, sim_config_of(s), [&](long, double, const RomSimulator<T, F>& sim) {
    for (int k = 0; k < RomSimulator<T, F>::Plant::kStates; ++k) hash.add(sim.state()(k));
    return true;
  });
  hash.add_bytes(static_cast<std::uint64_t>(fault), 1);
  return hash.value();
}

// The ROM hash cases, shared by the host/aarch64 program and the Cortex-M
// image so both print the same labels: out(label, hash) for each.
// seed-case1 covers the start from rest and the grip with the axial feature
// (its inputs on the axial plant: tools/scenes/seed-case1-clamped.toml; the
// built-in itself runs the tension plant on fixed sheaves);
// clamp-step adds road load (tanh) and a flare in gross slip.
template <class T, class Out>
void rom_trace_hashes(Out&& out) {
  namespace f = rom_feature;
  out("rom/seed-case1/2s", rom_trace_hash<T, f::axial>("seed-case1", 2.0));
  out("rom/clamp-step/2.5s", rom_trace_hash<T, f::axial | f::road_load>("clamp-step", 2.5));
}

}  // namespace cvt::testing
