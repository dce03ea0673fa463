// The one rule for names that become file names (docs/cli.md#names).
#include "cvtplant/files/names.hpp"

namespace cvt::files {

namespace {

bool alnum(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); }

}  // namespace

std::string name_problem(const std::string& name) {
  const std::string rule = "a name has 1 to 64 characters: letters, digits, '-', '_' and '.', the first a letter or digit";
  if (name.empty()) return "empty name (" + rule + ")";
  if (name.size() > kMaxNameChars) return "longer than 64 characters (" + rule + ")";
  if (!alnum(name[0])) return "starts with a character other than a letter or digit (" + rule + ")";
  for (const char c : name)
    if (!alnum(c) && c != '-' && c != '_' && c != '.') {
      const unsigned char u = static_cast<unsigned char>(c);
      const std::string what = u < 0x20 || u == 0x7f ? "a control character"
                               : u >= 0x80          ? "a non-ASCII byte"
                               : c == ' '           ? "a space"
                                                    : std::string("'") + c + "'";
      return "holds " + what + " (" + rule + ")";
    }
  return {};
}

}  // namespace cvt::files
