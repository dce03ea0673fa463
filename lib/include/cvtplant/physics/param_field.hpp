#pragma once
// What a field list says about one parameter (the lists: friction/
// friction_fields.hpp, plant/rom_param_fields.hpp, and the multibody
// reference's mbd/params_fields.hpp). A list is a function template that
// calls a visitor once per field of a parameter struct, in declaration
// order, with this description and a reference to the field, so every
// reader, writer and key of those parameters walks the same list and a new
// field is added in one line.
#include <cstdint>

namespace cvt {

// How `cvtplant calibrate` may fit a field (docs/validation.md#calibration):
// not at all (a physical value the multibody reference shares, or not a
// number), as a positive value (fitted on a log scale) or as a share in
// (0, 1) (fitted on a logit scale).
enum class ParamFit : std::uint8_t { none, positive, share };

struct ParamField {
  const char* name;          // the key in files, JSON, cache keys and messages
  const char* unit;          // the key's unit ("1": dimensionless; "": a flag, a choice, a profile)
  ParamFit fit = ParamFit::none;
  double to_si = 1.0;        // the key's value times to_si is the field's SI value (beta0_deg: pi/180)
  const char* group = "";    // the nested struct or table it sits in ("friction", "road"); "": the top
  bool cap = false;          // a cap on work, not an input of the result (left out of cache keys)
};

// Whether two names are equal (constexpr, heap-free).
constexpr bool param_names_equal(const char* a, const char* b) {
  while (*a != '\0' && *a == *b) {
    ++a;
    ++b;
  }
  return *a == *b;
}

}  // namespace cvt
