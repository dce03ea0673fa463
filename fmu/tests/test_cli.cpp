// `cvtplant fmu` as a user drives it (docs/cli.md#fmu): bad input is one
// line on stderr and exit 2, a failed write exit 1 and no file, the same
// scene gives the same bytes.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "importer.hpp"

using namespace fmutest;

namespace {

struct Result {
  int rc;
  std::string out, err;
};

Result cli(const std::string& args, const std::string& dir) {
  const std::string o = dir + "/stdout.txt", e = dir + "/stderr.txt";
  Result r;
  r.rc = run(cvtplant() + " fmu " + args + " > " + o + " 2> " + e);
  std::ifstream fo(o), fe(e);
  std::stringstream so, se;
  so << fo.rdbuf();
  se << fe.rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

std::string bytes_of(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void bad_input(const Result& r, const std::string& part) {
  INFO("stderr: " << r.err);
  CHECK(r.rc == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("cvtplant fmu: error: ", 0) == 0);
  CHECK(r.err.find(part) != std::string::npos);
  CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
}

}  // namespace

TEST_SUITE("cli") {
  TEST_CASE("bad input: exit 2 and one line naming it") {
    const std::string dir = temp_dir("fmu-cli");
    bad_input(cli("--scene no-such-scene --out " + dir + "/x.fmu", dir), "no-such-scene");
    bad_input(cli("--scene ratio-control --fmi 4 --out " + dir + "/x.fmu", dir), "--fmi");
    bad_input(cli("--scene ratio-control --out -", dir), "--out");
    bad_input(cli("--scene ratio-control --out " + dir, dir), "is a directory");
    bad_input(cli("--scene ratio-control", dir), "--out");
    const std::string scene = dir + "/fixed.toml";
    std::ofstream(scene) << "base = \"ratio-control\"\nscalar = \"fixed\"\n";
    bad_input(cli("--scene " + scene + " --out " + dir + "/x.fmu", dir), "wedging runs in double or float only");
    const std::string good = dir + "/good.toml";
    std::ofstream(good) << "base = \"tip-in\"\n";
    const std::string before = bytes_of(good);
    bad_input(cli("--scene " + good + " --out " + good, dir), "is the scene file");
    CHECK(bytes_of(good) == before);
    CHECK(!std::filesystem::exists(dir + "/x.fmu"));
  }

  TEST_CASE("a failed write: exit 1, no file; a good one replaces the old file whole, the same bytes each time") {
    const std::string dir = temp_dir("fmu-cli-write");
    const Result r = cli("--scene tip-in --out " + dir + "/missing/x.fmu", dir);
    CHECK(r.rc == 1);
    CHECK(r.err.rfind("cvtplant fmu: failed: ", 0) == 0);
    CHECK(!std::filesystem::exists(dir + "/missing"));
    const std::string out = dir + "/plant.fmu";
    std::ofstream(out) << "an old file";
    REQUIRE(cli("--scene tip-in --out " + out, dir).rc == 0);
    const std::string first = bytes_of(out);
    CHECK(first.size() > 1000000);
    REQUIRE(cli("--scene tip-in --out " + out + " --json", dir).rc == 0);
    CHECK(bytes_of(out) == first);
    for (const char* key : {"\"subcommand\": \"fmu\"", "\"model_identifier\": \"cvtplant_tip_in\"", "\"fmi_version\": \"3.0\"",
                            "\"input_count\": 3", "\"frame_s\": 0.001"}) {
      INFO(key);
      CHECK(cli("--scene tip-in --out " + out + " --json", dir).out.find(key) != std::string::npos);
    }
  }
}
