// The FMU through the project's importer (importer.hpp): a run gives the same
// bits as `cvtplant run`, FMU states restore bit-identically (in the same
// process and in another), faults and bad calls return an error with a
// logged reason, instances are independent (docs/fmu.md#tests).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cvtplant/plant/rom_watchdog.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "importer.hpp"

using namespace fmutest;

namespace {

std::string make_fmu(const std::string& scene, int version, const std::string& dir, const std::string& name) {
  const std::string out = dir + "/" + name + ".fmu";
  const int rc = run(cvtplant() + " fmu --scene " + scene + " --fmi " + std::to_string(version) + " --out " + out +
                     " > " + dir + "/" + name + ".txt 2>&1");
  REQUIRE_MESSAGE(rc == 0, "cvtplant fmu --scene " << scene << " exited " << rc);
  return out;
}

CsvRun run_csv(const std::string& scene, double t_end, const std::string& dir, const std::string& name,
               int expect_rc = 0) {
  const std::string csv = dir + "/" + name + ".csv";
  char t[32];
  std::snprintf(t, sizeof t, "%.17g", t_end);
  const int rc = run(cvtplant() + " run --scene " + scene + " --t-end " + t + " --csv " + csv + " > /dev/null 2>&1");
  REQUIRE_MESSAGE(rc == expect_rc, "cvtplant run --scene " << scene << " exited " << rc);
  return read_csv(csv);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every FMU output that `cvtplant run` also writes, against row `row`:
// identical bits. Returns how many were compared.
template <class Get>
int compare_row(const Unpacked& fmu, const CsvRun& csv, std::size_t row, Get&& get) {
  int n = 0;
  for (const VarInfo& v : fmu.vars) {
    if (v.causality != "output" && v.causality != "independent") continue;
    if (v.name == "fault") continue;  // compared by name below
    const int col = csv.column(v.causality == "independent" ? "t" : v.name);
    if (col < 0) continue;
    const double want = csv.rows.at(row).at(static_cast<std::size_t>(col));
    const double got = get(v);
    INFO("row " << row << ", " << v.name << ": FMU " << got << ", cvtplant run " << want);
    CHECK(same_bits(got, want));
    ++n;
  }
  const auto fault = static_cast<cvt::RomFault>(static_cast<int>(get(fmu.var("fault"))));
  CHECK(std::string(cvt::rom_fault_name(fault)) == csv.faults.at(row));
  return n;
}

// The scene's inputs at t through the FMU's input variables.
template <class Set>
void set_inputs(const cvt::Scene& s, double t, const Unpacked& fmu, Set&& set) {
  if (fmu.by_name.count("inputs.tau_in")) set("inputs.tau_in", s.tau_in.at(t));
  if (fmu.by_name.count("inputs.tau_load")) set("inputs.tau_load", s.tau_load.at(t));
  if (fmu.by_name.count("inputs.clamp")) set("inputs.clamp", s.clamp.at(t));
}

double value3(Instance3& inst, const VarInfo& v) {
  if (v.type == "Boolean") return inst.boolean(v.name) ? 1.0 : 0.0;
  if (v.type == "Enumeration") return static_cast<double>(inst.enumeration(v.name));
  return inst.real(v.name);
}

// Drives an FMI 3.0 FMU of `scene` (a built-in or a file based on `base`)
// for `frames` frames in communication steps of k frames and compares every
// step's end with `cvtplant run`.
void compare_fmi3(const std::string& scene, const char* base, long frames, int k, const std::string& tag) {
  const std::string dir = temp_dir("fmu-" + tag);
  const cvt::Scene* s = cvt::find_builtin_scene(base);
  REQUIRE(s != nullptr);
  const Unpacked fmu(make_fmu(scene, 3, dir, "plant"), dir + "/unpacked");
  const CsvRun csv = run_csv(scene, static_cast<double>(frames) * fmu.frame_s, dir, "run");
  REQUIRE(csv.rows.size() == static_cast<std::size_t>(frames + 1));
  const Api3 api(fmu.binary());
  Instance3 inst(api, fmu);
  REQUIRE_MESSAGE(inst.ok(), inst.log.all());
  set_inputs(*s, 0.0, fmu, [&](const std::string& n, double v) { REQUIRE(inst.set(n, v) == fmi3OK); });
  REQUIRE_MESSAGE(inst.init() == fmi3OK, inst.log.all());
  int compared = compare_row(fmu, csv, 0, [&](const VarInfo& v) { return value3(inst, v); });
  CHECK(compared >= 10);
  for (long i = 0; i < frames; i += k) {
    const double t = static_cast<double>(i) * fmu.frame_s;
    set_inputs(*s, t, fmu, [&](const std::string& n, double v) { REQUIRE(inst.set(n, v) == fmi3OK); });
    REQUIRE_MESSAGE(inst.step(t, k * fmu.frame_s) == fmi3OK, inst.log.all());
    compared += compare_row(fmu, csv, static_cast<std::size_t>(i + k), [&](const VarInfo& v) { return value3(inst, v); });
  }
  MESSAGE(scene << ": " << frames << " frames in steps of " << k << ", " << compared << " values identical");
}

}  // namespace

TEST_SUITE("importer") {
  TEST_CASE("ratio-control through FMI 3.0 gives the bits of cvtplant run, one frame per step") {
    compare_fmi3("ratio-control", "ratio-control", 1500, 1, "rc1");
  }

  TEST_CASE("several frames per communication step: the same bits (inputs constant over each step)") {
    // clamp-step's clamping steps at 2 s, a multiple of both step lengths.
    compare_fmi3("clamp-step", "clamp-step", 2500, 4, "cs4");
    compare_fmi3("ratio-control", "ratio-control", 1000, 10, "rc10");
  }

  TEST_CASE("a ramped input (tip-in), float and q16.16 plants: the same bits") {
    compare_fmi3("tip-in", "tip-in", 1300, 1, "tip");
    const std::string dir = temp_dir("fmu-scalars");
    for (const char* scalar : {"float", "fixed"}) {
      const std::string file = dir + "/clamp-step-" + scalar + ".toml";
      std::ofstream(file) << "base = \"clamp-step\"\nname = \"clamp-step-" << scalar << "\"\nscalar = \"" << scalar
                          << "\"\n";
      compare_fmi3(file, "clamp-step", 2200, 5, std::string("cs-") + scalar);
    }
  }

  TEST_CASE("FMI 2.0: the same bits as cvtplant run") {
    const std::string dir = temp_dir("fmu-fmi2");
    const cvt::Scene* s = cvt::find_builtin_scene("ratio-control");
    const Unpacked fmu(make_fmu("ratio-control", 2, dir, "plant"), dir + "/unpacked");
    CHECK(fmu.version == 2);
    const CsvRun csv = run_csv("ratio-control", 500 * fmu.frame_s, dir, "run");
    const Api2 api(fmu.binary());
    Instance2 inst(api, fmu);
    REQUIRE_MESSAGE(inst.ok(), inst.log.all());
    set_inputs(*s, 0.0, fmu, [&](const std::string& n, double v) { REQUIRE(inst.set(n, v) == fmi2OK); });
    REQUIRE(inst.init() == fmi2OK);
    int compared = 0;
    for (long i = 0; i < 500; i += 2) {
      const double t = static_cast<double>(i) * fmu.frame_s;
      REQUIRE_MESSAGE(inst.step(t, 2 * fmu.frame_s) == fmi2OK, inst.log.all());
      compared += compare_row(fmu, csv, static_cast<std::size_t>(i + 2), [&](const VarInfo& v) {
        if (v.type == "Boolean") {
          fmi2Boolean b = 0;
          api.fmi2GetBoolean(inst.get(), &v.vr, 1, &b);
          return b ? 1.0 : 0.0;
        }
        if (v.type == "Enumeration") {
          fmi2Integer e = -1;
          api.fmi2GetInteger(inst.get(), &v.vr, 1, &e);
          return static_cast<double>(e);
        }
        return inst.real(v.name);
      });
    }
    CHECK(compared > 1000);
  }
}
