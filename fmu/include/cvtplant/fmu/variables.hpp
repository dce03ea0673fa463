#pragma once
// The FMU's variables for a scene (docs/fmu.md#variables): the model
// description lists them and the FMU's functions serve them, both from this
// one function, so the two cannot disagree. Heap-free.
//
// Value references are fixed whatever the scene: the independent time, the
// inputs from 1, the fault code at 10, the plant's signals from 100 in the
// order of plant/rom_signals.hpp, the scene's parameters from 1000 in the
// order of scene/scene_params.hpp. A scene without a feature leaves its
// references out.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "cvtplant/plant/rom_signals.hpp"
#include "cvtplant/plant/rom_watchdog.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/scene/scene_params.hpp"

namespace cvt::fmu {

enum class VarType : std::uint8_t { float64, boolean, enumeration };
enum class Causality : std::uint8_t { independent, input, output, parameter };
enum class Variability : std::uint8_t { fixed, discrete, continuous };
// Where a variable's value lives.
enum class VarSource : std::uint8_t { time, input, fault, signal, param };

// The plant's inputs, in value-reference order.
enum FmuInput : int { input_tau_in, input_tau_load, input_clamp, input_clamp_driven, input_count };

inline constexpr std::uint32_t kVrTime = 0;
inline constexpr std::uint32_t kVrInput0 = 1;
inline constexpr std::uint32_t kVrFault = 10;
inline constexpr std::uint32_t kVrSignal0 = 100;
inline constexpr std::uint32_t kVrParam0 = 1000;
inline constexpr std::uint32_t kVrEnd = kVrParam0 + static_cast<std::uint32_t>(kSceneParamCount);
inline constexpr int kMaxVariables = 2 + input_count + kRomSignalCount + kSceneParamCount;
inline constexpr double kNoBound = std::numeric_limits<double>::infinity();
// q16.16 scenes: an input must stay off the rail of the Q range, where the
// watchdog would fault input-saturated (docs/rom.md#watchdog).
inline constexpr double kFixedInputBound = 32767.0;

struct Variable {
  std::uint32_t vr = 0;
  const char* name = "";
  const char* unit = nullptr;  // nullptr: the enumeration (its type says what it is)
  const char* description = "";
  VarType type = VarType::float64;
  Causality causality = Causality::output;
  Variability variability = Variability::continuous;
  VarSource source = VarSource::signal;
  int index = 0;  // FmuInput, RomSignal or kSceneParams row
  bool has_start = false;
  double start = 0;
  double min = -kNoBound, max = kNoBound;
};

inline const char* input_name(int i) {
  switch (i) {
    case input_tau_in: return "inputs.tau_in";
    case input_tau_load: return "inputs.tau_load";
    case input_clamp: return "inputs.clamp";
    default: return "inputs.clamp_driven";
  }
}

// The inputs a scene's plant reads: the driven clamping with wedging only;
// the clamping input unless the tension plant's sheaves are fixed (then the
// plant does not read it, docs/rom.md#tension).
inline bool input_applies(int i, const Scene& s) {
  if (i == input_clamp_driven) return (s.features & rom_feature::wedging) != 0u;
  if (i == input_clamp) return !((s.features & rom_feature::tension) != 0u && s.params.fixed_sheaves);
  return true;
}

inline const char* input_description(int i, const Scene& s) {
  switch (i) {
    case input_tau_in: return "input torque on the driver pulley";
    case input_tau_load: return "load torque at the driven shaft (the road load adds to it)";
    case input_clamp:
      if ((s.features & rom_feature::axial) != 0u)
        return "driver clamping command F_cmd: the actuator follows it with actuator_tau_s, saturated at clamp_max_N";
      return "driver axial force F_ax on the wrap";
    default:
      return "driven clamping command F_ax2: the driven actuator follows it with actuator_tau_s, saturated at "
             "clamp_max_N";
  }
}

// The start values of the inputs: the scene's profiles at t = 0, the driven
// clamping's set-up value.
inline double input_start(int i, const Scene& s) {
  switch (i) {
    case input_tau_in: return s.tau_in.at(0.0);
    case input_tau_load: return s.tau_load.at(0.0);
    case input_clamp: return s.clamp.at(0.0);
    default: return s.params.driven_clamp_N;
  }
}

// Whether a signal of plant/rom_signals.hpp is an output of the scene's FMU:
// the energy group with the ledger, the tension group with the tension
// feature, the radial group with wedging, the others always.
inline bool signal_applies(const RomSignalInfo& g, const Scene& s) {
  if (g.log == rom_log::energy) return s.energy_ledger;
  if (g.log == rom_log::tension) return (s.features & rom_feature::tension) != 0u;
  if (g.log == rom_log::radial) return (s.features & rom_feature::wedging) != 0u;
  return true;
}

// The variables of the FMU of scene s, in value-reference order; returns
// their count (at most kMaxVariables). Start values are the scene's.
inline int fmu_variables(const Scene& s, Variable* out) {
  int n = 0;
  const bool fixed_point = s.scalar == ScalarKind::q16_16;
  {
    Variable& v = out[n++] = Variable{};
    v.vr = kVrTime;
    v.name = "time";
    v.unit = "s";
    v.description = "simulation time";
    v.causality = Causality::independent;
    v.source = VarSource::time;
  }
  for (int i = 0; i < input_count; ++i) {
    if (!input_applies(i, s)) continue;
    Variable& v = out[n++] = Variable{};
    v.vr = kVrInput0 + static_cast<std::uint32_t>(i);
    v.name = input_name(i);
    v.unit = (i == input_tau_in || i == input_tau_load) ? "N.m" : "N";
    v.description = input_description(i, s);
    v.causality = Causality::input;
    v.source = VarSource::input;
    v.index = i;
    v.has_start = true;
    v.start = input_start(i, s);
    if (i == input_clamp || i == input_clamp_driven) v.min = 0.0;
    if (fixed_point) {
      if (v.min < 0) v.min = -kFixedInputBound;
      v.max = kFixedInputBound;
    }
  }
  {
    Variable& v = out[n++] = Variable{};
    v.vr = kVrFault;
    v.name = "fault";
    v.description = "the plant's watchdog: none, or the latched fault (docs/rom.md#watchdog)";
    v.type = VarType::enumeration;
    v.variability = Variability::discrete;
    v.source = VarSource::fault;
  }
  for (const RomSignalInfo& g : kRomSignals) {
    if (!signal_applies(g, s)) continue;
    Variable& v = out[n++] = Variable{};
    v.vr = kVrSignal0 + static_cast<std::uint32_t>(g.id);
    v.name = g.name;
    v.unit = g.unit;
    v.description = g.description;
    v.source = VarSource::signal;
    v.index = static_cast<int>(g.id);
    if (g.kind == RomSignalKind::flag) {
      v.type = VarType::boolean;
      v.variability = Variability::discrete;
    }
  }
  for (int i = 0; i < kSceneParamCount; ++i) {
    const SceneParamInfo& p = kSceneParams[i];
    if (!scene_param_applies(p, s)) continue;
    Variable& v = out[n++] = Variable{};
    v.vr = kVrParam0 + static_cast<std::uint32_t>(i);
    v.name = p.name;
    v.unit = p.unit;
    v.description = p.description;
    v.causality = Causality::parameter;
    v.variability = Variability::fixed;
    v.source = VarSource::param;
    v.index = i;
    v.has_start = true;
    v.start = p.get(s);
    if (p.kind == SceneParamKind::flag) {
      v.type = VarType::boolean;
    } else {
      v.min = p.min;
      v.max = p.max;
    }
  }
  return n;
}

// FNV-1a over bytes: the instantiation token is computed from the scene's
// resource text (scene_text.hpp), by the packager and again by the FMU.
inline std::uint64_t fnv1a(const char* data, std::size_t n, std::uint64_t h = 14695981039346656037ull) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

// "{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}" from the resource text; out has
// room for 39 bytes.
inline void instantiation_token(const char* text, std::size_t n, char* out) {
  const std::uint64_t a = fnv1a(text, n), b = fnv1a(text, n, a ^ 0x9e3779b97f4a7c15ull);
  constexpr const char* hex = "0123456789abcdef";
  const char* layout = "{........-....-....-....-............}";
  int bit = 0;
  for (int i = 0; layout[i] != '\0'; ++i) {
    char c = layout[i];
    if (c == '.') {
      const std::uint64_t word = bit < 64 ? a : b;
      c = hex[(word >> (60 - bit % 64)) & 0xFu];
      bit += 4;
    }
    out[i] = c;
  }
  out[38] = '\0';
}

}  // namespace cvt::fmu
