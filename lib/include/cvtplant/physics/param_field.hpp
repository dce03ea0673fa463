#pragma once
// What a field list says about one parameter (friction/friction_fields.hpp's
// names, the multibody reference's mbd/params_fields.hpp). A list is a
// function template that calls a visitor once per field of a parameter
// struct, in declaration order, with this description and the field, so
// every reader, writer and key of those parameters walks the same list and a
// new field is added in one line. The plant's own parameters are the rows of
// scene/scene_params.hpp.
namespace cvt {

struct ParamField {
  const char* name;          // the key in files, JSON, cache keys and messages
  const char* unit;          // SI unit ("1": dimensionless; "": a flag, a choice, a profile)
  const char* group = "";    // the nested struct or table it sits in ("friction", "road"); "": the top
  bool cap = false;          // a cap on work, not an input of the result (left out of cache keys)
};

}  // namespace cvt
