// Static description of one DBC signal, for loggers and tools that walk a
// message generically (Msg::visit in messages.hpp). Plain constants: no heap.
#pragma once

#include <cstdint>

namespace cvt::can {

enum class SignalKind : uint8_t { Float, Integer, Enum, Bool };

struct SignalInfo {
  const char* name;  // DBC name = C++ member name (unit in the name)
  const char* unit;  // DBC unit string
  SignalKind kind;
  double min;        // DBC [min|max], physical
  double max;
  double lsb;        // DBC factor (1 for Integer, Enum, Bool)
};

}  // namespace cvt::can
