#pragma once
// Self-registration of subcommands, so that adding a subcommand is adding one
// cmd_<name>.cpp file (no central list to edit). Usage, at namespace scope:
//   static const bool registered = cvtcli::add_registrar(&register_foo);
#include <vector>

#include "commands.hpp"

namespace cvtcli {

inline std::vector<Registrar>& registrars() {
  static std::vector<Registrar> table;
  return table;
}

inline bool add_registrar(Registrar r) {
  registrars().push_back(r);
  return true;
}

}  // namespace cvtcli
