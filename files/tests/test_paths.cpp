// The rule for paths and the check of a command's inputs and outputs
// (docs/cli.md#files).
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <functional>

#include "cvtplant/files/paths.hpp"
#include "temp_dir.hpp"

using cvt::files::CommandFiles;
using cvt::files::PathError;
using cvt::files::path_problem;
using cvt::files::same_file;
using cvt::files::test::TempDir;

namespace {

void touch(const std::string& p) { std::ofstream(p) << "x\n"; }

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const PathError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_SUITE("paths") {
  TEST_CASE("a path is refused when empty or holding a control character") {
    CHECK(path_problem("") == "empty file name");
    CHECK(path_problem("a\nb").find("control character") != std::string::npos);
    CHECK(path_problem("a\nb").find("'a?b'") != std::string::npos);
    CHECK(path_problem(std::string("a\tb")) != "");
    CHECK(path_problem("dir/with space/é.csv") == "");
    CHECK(path_problem("-") == "");
  }

  TEST_CASE("same_file: through links, dot segments, and for files not yet written") {
    TempDir d;
    touch(d / "f.csv");
    REQUIRE(::mkdir((d / "sub").c_str(), 0755) == 0);
    CHECK(same_file(d / "f.csv", d / "f.csv"));
    CHECK(same_file(d / "f.csv", d / "sub/../f.csv"));
    CHECK(same_file(d / "f.csv", d / "./f.csv"));
    REQUIRE(::symlink((d / "f.csv").c_str(), (d / "link.csv").c_str()) == 0);
    CHECK(same_file(d / "link.csv", d / "f.csv"));
    REQUIRE(::link((d / "f.csv").c_str(), (d / "hard.csv").c_str()) == 0);
    CHECK(same_file(d / "hard.csv", d / "f.csv"));
    touch(d / "g.csv");
    CHECK_FALSE(same_file(d / "f.csv", d / "g.csv"));
    // Neither exists yet: the resolved paths decide.
    CHECK(same_file(d / "new.csv", d / "sub/../new.csv"));
    CHECK_FALSE(same_file(d / "new.csv", d / "other.csv"));
    REQUIRE(::symlink((d / "sub").c_str(), (d / "sublink").c_str()) == 0);
    CHECK(same_file(d / "sublink/x.csv", d / "sub/x.csv"));
    // A dangling link writes its target.
    REQUIRE(::symlink((d / "target.csv").c_str(), (d / "dangling.csv").c_str()) == 0);
    CHECK(same_file(d / "dangling.csv", d / "target.csv"));
    // One exists, the other does not: two files.
    CHECK_FALSE(same_file(d / "f.csv", d / "missing.csv"));
  }

  TEST_CASE("an output that is an input, through a link, is refused naming both options") {
    TempDir d;
    touch(d / "P.toml");
    REQUIRE(::symlink((d / "P.toml").c_str(), (d / "L.toml").c_str()) == 0);
    CommandFiles f;
    f.input("--start", d / "P.toml");
    const std::string msg = refusal([&] { f.output("--out", d / "L.toml"); });
    CHECK(msg.find("--out: '" + (d / "L.toml") + "' is the input of --start") == 0);
    CHECK(msg.find("destroy") != std::string::npos);
  }

  TEST_CASE("an input given after the output it would be is refused too") {
    TempDir d;
    touch(d / "s.toml");
    CommandFiles f;
    f.output("--csv", d / "s.toml");
    const std::string msg = refusal([&] { f.input("--scene", d / "s.toml"); });
    CHECK(msg.find("--csv: ") == 0);
    CHECK(msg.find("input of --scene") != std::string::npos);
  }

  TEST_CASE("two outputs to one file, or both to stdout, are refused") {
    TempDir d;
    CommandFiles f;
    f.output("--csv", d / "F.csv");
    const std::string msg = refusal([&] { f.output("--links-csv", d / "./F.csv"); });
    CHECK(msg.find("--links-csv: ") == 0);
    CHECK(msg.find("also the output of --csv") != std::string::npos);
    CommandFiles g;
    g.output("--csv", "-");
    CHECK(refusal([&] { g.output("--links-csv", "-"); }).find("stdout is already the output of --csv") !=
          std::string::npos);
  }

  TEST_CASE("what is allowed: two inputs of one file, stdin and stdout, distinct files") {
    TempDir d;
    touch(d / "a.csv");
    CommandFiles f;
    f.input("--csv", d / "a.csv");
    f.input("--scene", d / "a.csv");
    f.input("--csv", "-");
    f.output("--out", "-");
    f.output("--png", d / "b.png");
    CHECK(refusal([&] { f.output("--json-out", d / "c.json"); }).empty());
  }

  TEST_CASE("an empty path or one with a newline is refused with its option") {
    CommandFiles f;
    CHECK(refusal([&] { f.output("--csv", ""); }) == "--csv: empty file name");
    CHECK(refusal([&] { f.input("--start", "a\nk1_N_m = 5"); }).find("--start: 'a?k1_N_m = 5' holds a control") == 0);
  }
}
