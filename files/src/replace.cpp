// Files written whole or not at all (docs/cli.md#files).
#include "cvtplant/files/replace.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "cvtplant/files/paths.hpp"

namespace cvt::files {

namespace {

std::atomic<unsigned> g_temp_counter{0};

// The file a write to `path` changes: a symbolic link's target (followed
// while links exist), else the path itself.
std::string write_target(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(p, ec)) return p.string();
    const fs::path t = fs::read_symlink(p, ec);
    if (ec) return p.string();
    p = t.is_absolute() ? t : p.parent_path() / t;
  }
  return p.string();
}

}  // namespace

ReplacingFile::ReplacingFile(const std::string& path) : target_(write_target(path)) {
  if (const std::string why = path_problem(path); !why.empty()) throw PathError(why);
  struct stat st {};
  const bool exists = ::stat(target_.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw PathError(shown_path(path) + " is a directory");
  const std::filesystem::path t(target_);
  const std::string dir = t.has_parent_path() ? t.parent_path().string() : ".";
  // Hidden, and unique per process and call: two runs never share one.
  temp_ = dir + "/." + t.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
          std::to_string(g_temp_counter.fetch_add(1));
  const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw PathError("cannot write " + shown_path(path) + ": " + std::strerror(errno));
  // A file replaced keeps its permissions, as one rewritten in place would.
  if (exists) (void)::fchmod(fd, st.st_mode & 07777);
  f_ = ::fdopen(fd, "w");
  if (f_ == nullptr) {
    const int err = errno;
    ::close(fd);
    ::unlink(temp_.c_str());
    throw PathError("cannot write " + shown_path(path) + ": " + std::strerror(err));
  }
}

ReplacingFile::~ReplacingFile() {
  if (f_ != nullptr) std::fclose(f_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void ReplacingFile::commit() {
  errno = 0;
  const bool write_failed = std::fflush(f_) != 0 || std::ferror(f_) != 0;
  int err = errno;
  const bool close_failed = std::fclose(f_) != 0;
  if (err == 0) err = errno;
  f_ = nullptr;
  if (write_failed || close_failed) {
    ::unlink(temp_.c_str());
    temp_.clear();
    throw WriteError("writing " + shown_path(target_) + " failed: " + (err != 0 ? std::strerror(err) : "write error"));
  }
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    err = errno;
    ::unlink(temp_.c_str());
    temp_.clear();
    throw WriteError("replacing " + shown_path(target_) + " failed: " + std::strerror(err));
  }
  temp_.clear();
}

void replace_file(const std::string& path, const std::string& content) {
  ReplacingFile f(path);
  std::fwrite(content.data(), 1, content.size(), f.stream());
  f.commit();
}

void make_directories(const std::string& dir, const std::string& role) {
  if (const std::string why = path_problem(dir); !why.empty()) throw PathError(role + ": " + why);
  // Each missing level from the top: EEXIST is fine (another process may
  // make the same directory at the same moment), as long as it is one.
  std::string prefix;
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = dir.find('/', pos + 1);
    prefix = dir.substr(0, pos);
    if (prefix.empty() || prefix == "/" ) continue;
    if (::mkdir(prefix.c_str(), 0777) == 0) continue;
    const int err = errno;
    struct stat st {};
    if (::stat(prefix.c_str(), &st) == 0) {
      if (S_ISDIR(st.st_mode)) continue;
      throw PathError(role + ": " + shown_path(prefix) + " exists and is not a directory");
    }
    throw PathError(role + ": cannot create directory " + shown_path(prefix) + ": " + std::strerror(err));
  }
}

}  // namespace cvt::files
