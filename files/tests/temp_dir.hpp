#pragma once
// A fresh directory under the system's temporary folder, removed with its
// content at the end of a test.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace cvt::files::test {

struct TempDir {
  std::string path;
  TempDir() {
    char tmpl[] = "/tmp/cvt-files-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return path + "/" + name; }
};

}  // namespace cvt::files::test
