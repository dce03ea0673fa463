#pragma once
// The names of the friction laws, the sign functions and the parameter
// presets as scene files, cache keys and JSON write them
// (docs/rom.md#scene-files, docs/physics.md#friction). The coefficients'
// names are the friction.* rows of scene/scene_params.hpp.
#include <cstddef>

#include "cvtplant/friction/friction_law.hpp"

namespace cvt {

template <class E>
struct NamedValue {
  const char* name;
  E value;
};

inline constexpr NamedValue<FrictionLaw> kFrictionLawNames[] = {
    {"constant", FrictionLaw::constant}, {"case1", FrictionLaw::case1}, {"case2", FrictionLaw::case2}};
inline constexpr NamedValue<SignFunction> kSignFunctionNames[] = {
    {"atan", SignFunction::atan}, {"tanh", SignFunction::tanh}, {"exact", SignFunction::exact}};
// The names of an enumeration's values, found by its type (argument-
// dependent lookup), for generic readers and writers of field lists.
constexpr const auto& value_names(FrictionLaw) { return kFrictionLawNames; }
constexpr const auto& value_names(SignFunction) { return kSignFunctionNames; }

// The named parameter sets (docs/physics.md#friction-presets), as a scene
// file's [friction] preset names them.
inline constexpr NamedValue<FrictionParams<double>> kFrictionPresetNames[] = {
    {"oscillator_coulomb", friction_presets::oscillator_coulomb<double>()},
    {"oscillator_stribeck", friction_presets::oscillator_stribeck<double>()},
    {"table2_case1", friction_presets::table2_case1<double>()},
    {"table2_case2", friction_presets::table2_case2<double>()}};

// The name of an enumerator in such a table ("?" if it has none).
template <class E, std::size_t N>
constexpr const char* value_name(const NamedValue<E> (&table)[N], E value) {
  for (const auto& e : table)
    if (e.value == value) return e.name;
  return "?";
}

}  // namespace cvt
