// The paths a host program is given (docs/cli.md#files).
#include "cvtplant/files/paths.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <system_error>

namespace cvt::files {

namespace {

bool control_char(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

// The path with the symbolic links that exist followed and "." and ".."
// removed; a last component that is a dangling link is followed to the file
// it would create (a write through it creates the link's target).
std::string resolved(const std::string& p) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path q = fs::absolute(p, ec);
  if (ec) return p;
  for (int hops = 0; hops < 40; ++hops) {
    const fs::path c = fs::weakly_canonical(q, ec);
    if (ec) return q.lexically_normal().string();
    std::error_code link_ec;
    if (!fs::is_symlink(c, link_ec)) return c.string();
    const fs::path target = fs::read_symlink(c, link_ec);
    if (link_ec) return c.string();
    q = target.is_absolute() ? target : c.parent_path() / target;
  }
  return q.lexically_normal().string();
}

}  // namespace

std::string path_problem(const std::string& path) {
  if (path.empty()) return "empty file name";
  for (const char c : path)
    if (control_char(c)) return shown_path(path) + " holds a control character (shown as '?')";
  return {};
}

std::string shown_path(const std::string& path) {
  constexpr std::size_t kMax = 200;
  std::string s = path.substr(0, kMax);
  for (char& c : s)
    if (control_char(c)) c = '?';
  if (path.size() <= kMax) return "'" + s + "'";
  return "'" + s + "...' (" + std::to_string(path.size()) + " characters)";
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  const bool has_a = ::stat(a.c_str(), &sa) == 0, has_b = ::stat(b.c_str(), &sb) == 0;
  if (has_a && has_b) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (has_a != has_b) return false;
  return resolved(a) == resolved(b);
}

void CommandFiles::input(const std::string& role, const std::string& path) { add(role, path, false); }
void CommandFiles::output(const std::string& role, const std::string& path) { add(role, path, true); }

void CommandFiles::add(const std::string& role, const std::string& path, bool output) {
  if (const std::string why = path_problem(path); !why.empty()) throw PathError(role + ": " + why);
  const bool stdio = path == "-";
  for (const Entry& e : files_) {
    if (!output && !e.output) continue;  // two inputs may be one file
    if (stdio || e.path == "-") {
      // stdout twice; stdin is no file of the tree.
      if (stdio && e.path == "-" && output && e.output)
        throw PathError(role + ": stdout is already the output of " + e.role + "; give one of them a file");
      continue;
    }
    if (!same_file(path, e.path)) continue;
    if (output && e.output)
      throw PathError(role + ": " + shown_path(path) + " is also the output of " + e.role + " (" + shown_path(e.path) +
                      "); one would overwrite the other");
    const Entry& in = output ? e : Entry{role, path, false};
    const Entry& out = output ? Entry{role, path, true} : e;
    throw PathError(out.role + ": " + shown_path(out.path) + " is the input of " + in.role + " (" +
                    shown_path(in.path) + "); writing it would destroy that input");
  }
  files_.push_back({role, path, output});
}

}  // namespace cvt::files
