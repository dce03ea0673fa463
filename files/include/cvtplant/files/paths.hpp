#pragma once
// The paths a host program is given (docs/cli.md#files): one rule for what
// a path may be, and one check that no output of a command is one of its
// inputs or another of its outputs, by the file each resolves to, before
// anything is written.
#include <stdexcept>
#include <string>
#include <vector>

namespace cvt::files {

// A path or name refused before any work (the command line's bad input, exit 2).
struct PathError : std::invalid_argument {
  explicit PathError(const std::string& what) : std::invalid_argument(what) {}
};

// Why `path` cannot be used, or "" when it can: empty, or holding a control
// character (a newline would split a line of a generated file, a comment or
// a report).
std::string path_problem(const std::string& path);

// A path for a message: in quotes, cut to 200 characters with the full length
// said, control characters shown as '?'.
std::string shown_path(const std::string& path);

// Whether a and b name the same file: the same device and inode where both
// exist (so through symbolic and hard links); otherwise the same path once
// the symbolic links that exist are followed and "." and ".." removed, so
// two outputs not yet written are compared too.
bool same_file(const std::string& a, const std::string& b);

// Every file one command reads and writes, each with the option (or role)
// that named it. Each output is checked against every file added before it
// and each input against every output: an output that is an input (through
// a link too) or another output is refused with a PathError naming both
// options. "-" is stdin for an input (not compared) and stdout for an
// output (two outputs to stdout are refused). A path that breaks
// path_problem is refused as well.
class CommandFiles {
 public:
  void input(const std::string& role, const std::string& path);
  void output(const std::string& role, const std::string& path);

 private:
  struct Entry {
    std::string role, path;
    bool output;
  };
  void add(const std::string& role, const std::string& path, bool output);
  std::vector<Entry> files_;
};

}  // namespace cvt::files
