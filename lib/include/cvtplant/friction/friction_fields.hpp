#pragma once
// The friction parameters' field list (physics/param_field.hpp), and the
// names of the laws and sign functions as scene files and keys write them
// (docs/rom.md#scene-files, docs/physics.md#friction).
#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/physics/param_field.hpp"

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

// The name of an enumerator in such a table ("?" if it has none).
template <class E, int N>
constexpr const char* value_name(const NamedValue<E> (&table)[N], E value) {
  for (const auto& e : table)
    if (e.value == value) return e.name;
  return "?";
}

// v(const ParamField&, field&) for every field of FrictionParams<T>, in
// declaration order; P is FrictionParams<T> or its const.
template <class P, class V>
constexpr void visit_friction_fields(P& f, V&& v) {
  v(ParamField{"law", ""}, f.law);
  v(ParamField{"mu0", "1"}, f.mu0);
  v(ParamField{"a", "1"}, f.a);
  v(ParamField{"b_m_s", "m/s"}, f.b_m_s);
  v(ParamField{"sigma", "1"}, f.sigma);
  v(ParamField{"kappa_s_m", "s/m"}, f.kappa_s_m);
  v(ParamField{"chi_s_m", "s/m"}, f.chi_s_m);
  v(ParamField{"sign", ""}, f.sign);
  v(ParamField{"lambda_s_m", "s/m"}, f.lambda_s_m);
}

}  // namespace cvt
