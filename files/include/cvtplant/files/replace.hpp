#pragma once
// Files written whole or not at all (docs/cli.md#files): caches and
// generated files are written to a temporary file beside the target and
// renamed over it once complete, so a reader (another run, a second
// process) sees the old file or the whole new one, and a run killed in the
// middle leaves no half file under the target's name.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace cvt::files {

// A write that failed after the file was opened (a full disk): the run
// could not complete its output (the command line's exit 1).
struct WriteError : std::runtime_error {
  explicit WriteError(const std::string& what) : std::runtime_error(what) {}
};

class ReplacingFile {
 public:
  // Opens a temporary file in the target's directory (a symbolic link is
  // followed: its target is replaced). Throws PathError when it cannot be
  // created (no such directory, no permission) or the target is a directory.
  explicit ReplacingFile(const std::string& path);
  // Without commit(): the temporary is removed, the target is untouched.
  ~ReplacingFile();
  ReplacingFile(const ReplacingFile&) = delete;
  ReplacingFile& operator=(const ReplacingFile&) = delete;

  std::FILE* stream() const { return f_; }
  // Flushes, closes and renames the temporary over the target; throws
  // WriteError if a write failed or the rename did.
  void commit();

 private:
  std::string target_, temp_;
  std::FILE* f_ = nullptr;
};

// The whole of `content` as the file `path`, by a ReplacingFile.
void replace_file(const std::string& path, const std::string& content);

// Creates `dir` and its missing parents. A directory that exists, also one
// that another process creates at the same moment, is success; a path that
// exists and is not a directory, or one that cannot be created, is a
// PathError naming `role` (the option that gave it).
void make_directories(const std::string& dir, const std::string& role);

}  // namespace cvt::files
