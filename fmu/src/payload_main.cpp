// Build step: the FMU payload, a zip of the runtime's shared object and the
// FMU's sources/ (docs/fmu.md#files), which `cvtplant fmu` carries inside it
// and copies into every FMU it writes (packager.cpp).
//
//   cvtplant_fmu_payload OUT.zip NAME=FILE... PREFIX/=DIR...
//
// NAME=FILE adds a file as NAME; PREFIX/=DIR adds every regular file under
// DIR as PREFIX/<relative path>, in sorted order. Entries carry a fixed
// time, so the same inputs give the same zip.
#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

int fail(const std::string& why) {
  std::fprintf(stderr, "cvtplant_fmu_payload: error: %s\n", why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return fail("usage: cvtplant_fmu_payload OUT.zip NAME=FILE... PREFIX/=DIR...");
  std::vector<std::pair<std::string, fs::path>> entries;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos || eq == 0) return fail("expected NAME=FILE or PREFIX/=DIR: " + arg);
    const std::string name = arg.substr(0, eq);
    const fs::path path = arg.substr(eq + 1);
    if (name.back() == '/') {
      if (!fs::is_directory(path)) return fail("not a directory: " + path.string());
      std::vector<std::pair<std::string, fs::path>> found;
      for (const auto& e : fs::recursive_directory_iterator(path))
        if (e.is_regular_file()) found.emplace_back(name + fs::relative(e.path(), path).generic_string(), e.path());
      std::sort(found.begin(), found.end());
      entries.insert(entries.end(), found.begin(), found.end());
    } else {
      if (!fs::is_regular_file(path)) return fail("not a file: " + path.string());
      entries.emplace_back(name, path);
    }
  }
  const std::string out = argv[1];
  const std::string tmp = out + ".tmp";
  std::remove(tmp.c_str());
  int err = 0;
  zip_t* z = zip_open(tmp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (z == nullptr) return fail("cannot create " + tmp);
  for (const auto& [name, path] : entries) {
    zip_source_t* src = zip_source_file(z, path.c_str(), 0, -1);
    if (src == nullptr) return fail("cannot read " + path.string());
    const zip_int64_t idx = zip_file_add(z, name.c_str(), src, ZIP_FL_ENC_UTF_8);
    if (idx < 0) {
      zip_source_free(src);
      return fail("cannot add " + name + ": " + zip_strerror(z));
    }
    // 1980-01-02: a day after the earliest time a zip entry holds, in any time zone.
    zip_file_set_mtime(z, static_cast<zip_uint64_t>(idx), 315619200, 0);
  }
  if (zip_close(z) != 0) return fail("cannot write " + out + ": " + zip_strerror(z));
  std::error_code ec;
  fs::rename(tmp, out, ec);
  if (ec) return fail("cannot rename " + tmp + ": " + ec.message());
  return 0;
}
