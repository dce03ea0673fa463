// Files written whole or not at all, and directories made concurrently
// (docs/cli.md#files).
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "cvtplant/files/paths.hpp"
#include "cvtplant/files/replace.hpp"
#include "temp_dir.hpp"

using cvt::files::make_directories;
using cvt::files::PathError;
using cvt::files::replace_file;
using cvt::files::ReplacingFile;
using cvt::files::test::TempDir;

namespace {

std::string read(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The directory's entries (hidden ones too).
std::vector<std::string> entries(const std::string& d) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(d)) out.push_back(e.path().filename().string());
  return out;
}

}  // namespace

TEST_SUITE("replace") {
  TEST_CASE("a file is created and replaced whole, with no temporary left") {
    TempDir d;
    replace_file(d / "a.toml", "first\n");
    CHECK(read(d / "a.toml") == "first\n");
    replace_file(d / "a.toml", "second, longer\n");
    CHECK(read(d / "a.toml") == "second, longer\n");
    CHECK(entries(d.path) == std::vector<std::string>{"a.toml"});
  }

  TEST_CASE("a write that is not committed leaves the old file and no temporary") {
    TempDir d;
    replace_file(d / "a.csv", "old\n");
    {
      ReplacingFile f(d / "a.csv");
      std::fputs("half a ro", f.stream());
      // While it is written, the target still holds the old content.
      CHECK(read(d / "a.csv") == "old\n");
    }
    CHECK(read(d / "a.csv") == "old\n");
    CHECK(entries(d.path) == std::vector<std::string>{"a.csv"});
  }

  TEST_CASE("through a symbolic link the link's target is replaced and the link stays") {
    TempDir d;
    replace_file(d / "target.h", "old\n");
    REQUIRE(::symlink((d / "target.h").c_str(), (d / "link.h").c_str()) == 0);
    replace_file(d / "link.h", "new\n");
    CHECK(std::filesystem::is_symlink(d / "link.h"));
    CHECK(read(d / "target.h") == "new\n");
  }

  TEST_CASE("a replaced file keeps its permissions") {
    TempDir d;
    replace_file(d / "p.toml", "a\n");
    REQUIRE(::chmod((d / "p.toml").c_str(), 0600) == 0);
    replace_file(d / "p.toml", "b\n");
    struct stat st {};
    REQUIRE(::stat((d / "p.toml").c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0600);
  }

  TEST_CASE("a missing directory or a directory as the target is a PathError") {
    TempDir d;
    CHECK_THROWS_AS(replace_file(d / "no/such/dir/a.csv", "x"), PathError);
    REQUIRE(::mkdir((d / "dir").c_str(), 0755) == 0);
    CHECK_THROWS_AS(replace_file(d / "dir", "x"), PathError);
  }

  TEST_CASE("make_directories: parents, existing ones, a file in the way") {
    TempDir d;
    make_directories(d / "a/b/c", "--out-dir");
    CHECK(std::filesystem::is_directory(d / "a/b/c"));
    make_directories(d / "a/b/c/", "--out-dir");
    replace_file(d / "file", "x");
    try {
      make_directories(d / "file/sub", "--out-dir");
      FAIL("no error");
    } catch (const PathError& e) {
      CHECK(std::string(e.what()).find("--out-dir: '" + (d / "file") + "' exists and is not a directory") == 0);
    }
  }

  TEST_CASE("several threads creating the same new directory tree all succeed") {
    TempDir d;
    for (int round = 0; round < 20; ++round) {
      const std::string dir = d / ("r" + std::to_string(round) + "/x/y/z");
      std::vector<std::thread> threads;
      std::vector<std::string> errors(8);
      for (int i = 0; i < 8; ++i)
        threads.emplace_back([&, i] {
          try {
            make_directories(dir, "--out-dir");
          } catch (const PathError& e) {
            errors[static_cast<std::size_t>(i)] = e.what();
          }
        });
      for (auto& t : threads) t.join();
      for (const auto& e : errors) CHECK(e == "");
      CHECK(std::filesystem::is_directory(dir));
    }
  }
}
