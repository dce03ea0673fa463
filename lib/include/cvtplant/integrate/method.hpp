#pragma once
// Run-time choice of a fixed-step method (docs/numerics.md#integrators).
// A scene picks one; the switch costs nothing next to a right-hand side.
#include <cstdint>
#include <cstring>

#include "cvtplant/integrate/explicit_rk.hpp"
#include "cvtplant/integrate/rosenbrock.hpp"
#include "cvtplant/integrate/semi_implicit_euler.hpp"

namespace cvt {

enum class Method : std::uint8_t {
  explicit_euler,
  semi_implicit_euler,
  heun,
  rk4,
  linear_implicit_euler,
  ros2,
};

inline constexpr Method kAllMethods[] = {Method::explicit_euler, Method::semi_implicit_euler,
                                         Method::heun,           Method::rk4,
                                         Method::linear_implicit_euler, Method::ros2};

inline constexpr const char* method_name(Method m) {
  switch (m) {
    case Method::explicit_euler: return "euler";
    case Method::semi_implicit_euler: return "semi-implicit-euler";
    case Method::heun: return "heun";
    case Method::rk4: return "rk4";
    case Method::linear_implicit_euler: return "linear-implicit-euler";
    case Method::ros2: return "ros2";
  }
  return "?";
}

// Parses a method name; returns false (and leaves `out` alone) if unknown.
inline bool parse_method(const char* name, Method& out) {
  for (const Method m : kAllMethods) {
    if (std::strcmp(name, method_name(m)) == 0) {
      out = m;
      return true;
    }
  }
  return false;
}

// Order of accuracy, for convergence tests and documentation.
inline constexpr int method_order(Method m) {
  switch (m) {
    case Method::explicit_euler:
    case Method::semi_implicit_euler:
    case Method::linear_implicit_euler: return 1;
    case Method::heun:
    case Method::ros2: return 2;
    case Method::rk4: return 4;
  }
  return 0;
}

template <class Sys>
void step(Method m, const Sys& sys, StateOf<Sys>& x, typename Sys::Scalar h) {
  switch (m) {
    case Method::explicit_euler: step_explicit_euler(sys, x, h); break;
    case Method::semi_implicit_euler: step_semi_implicit_euler(sys, x, h); break;
    case Method::heun: step_heun(sys, x, h); break;
    case Method::rk4: step_rk4(sys, x, h); break;
    case Method::linear_implicit_euler: step_linear_implicit_euler(sys, x, h); break;
    case Method::ros2: step_ros2(sys, x, h); break;
  }
}

}  // namespace cvt
