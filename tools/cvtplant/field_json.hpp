#pragma once
// A parameter struct as JSON rows, by walking its field list
// (physics/param_field.hpp): one row per field, {"name": "group.name",
// "value": ..., "unit": ...}, the value a number, a flag, an enumerator's name
// or a profile's [t_s, value] points (docs/cli.md#json-output: the unit
// stands beside the value).
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <type_traits>

#include "cvtplant/friction/friction_fields.hpp"
#include "cvtplant/mbd/params_fields.hpp"

namespace cvtcli {

struct FieldRows {
  nlohmann::json rows = nlohmann::json::array();

  template <class X>
  void operator()(const cvt::ParamField& f, const X& x) {
    nlohmann::json value;
    if constexpr (std::is_enum_v<X>) {
      value = cvt::value_name(value_names(x), x);
    } else if constexpr (std::is_same_v<X, cvt::mbd::TimeProfile>) {
      value = nlohmann::json::array();
      for (const auto& pt : x.points) value.push_back({pt.first, pt.second});
    } else if constexpr (std::is_floating_point_v<X>) {
      value = std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
    } else {
      value = x;
    }
    const std::string name = f.group[0] != '\0' ? std::string(f.group) + "." + f.name : std::string(f.name);
    rows.push_back({{"name", name}, {"value", value}, {"unit", f.unit}});
  }
};

// visit(p, v) is the struct's field list (cvt::mbd::visit_mbd_params, ...).
template <class P, class Visit>
nlohmann::json field_rows(const P& p, Visit&& visit) {
  FieldRows w;
  visit(p, w);
  return w.rows;
}

}  // namespace cvtcli
