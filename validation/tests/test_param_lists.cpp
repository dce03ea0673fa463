// Every field of the parameter structs is in its field list
// (physics/param_field.hpp): the lists are what the reference cache's key,
// the scene-file reader and calibrate walk, so a field missing from one would
// be silently left out (a stale cache hit, a key a file cannot set).
//
// The structured bindings below decompose each struct into exactly as many
// names as it has fields: a field added to a struct fails to compile here
// ("decomposes into N elements") until a name is added, and the test then
// fails until the field is in the list too.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/plant/rom_param_fields.hpp"
#include "cvtplant/validation/calibration.hpp"

namespace {

struct Visited {
  std::set<const void*> where;
  std::set<std::string> names;
  int count = 0, duplicates = 0;
  template <class X>
  void operator()(const cvt::ParamField& f, X& x) {
    where.insert(static_cast<const void*>(&x));
    const std::string key = std::string(f.group) + "." + f.name;
    if (!names.insert(key).second) ++duplicates;
    ++count;
  }
};

// The fields (by address) that the list does not visit.
template <class... B>
int unvisited(const Visited& v, const B&... fields) {
  int missing = 0;
  ((missing += v.where.count(static_cast<const void*>(&fields)) == 0 ? 1 : 0), ...);
  return missing;
}

}  // namespace

TEST_SUITE("param_lists") {
  TEST_CASE("MbdParams: every field, nested ones included, is in visit_mbd_params once") {
    cvt::mbd::MbdParams p;
    Visited v;
    cvt::mbd::visit_mbd_params(p, v);
    CHECK(v.duplicates == 0);
    auto& [a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34] = p;
    CHECK(unvisited(v, a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34) == 0);
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8] = p.friction;
    CHECK(unvisited(v, f0, f1, f2, f3, f4, f5, f6, f7, f8) == 0);
    auto& [r0, r1, r2, r3] = p.road;
    CHECK(unvisited(v, r0, r1, r2, r3) == 0);
    for (cvt::mbd::SpeedHold* h : {&p.hold1, &p.hold2}) {
      auto& [h0, h1] = *h;
      CHECK(unvisited(v, h0, h1) == 0);
    }
    auto& [s0, s1, s2, s3, s4] = p.start;
    CHECK(unvisited(v, s0, s1, s2, s3, s4) == 0);
    // The leaves: the top level without its five nested structs, and theirs.
    CHECK(v.count == 35 - 5 + 9 + 4 + 2 + 2 + 5);
  }

  TEST_CASE("RunOptions: every field is in visit_run_options") {
    cvt::mbd::RunOptions r;
    Visited v;
    cvt::mbd::visit_run_options(r, v);
    auto& [o0, o1, o2, o3, o4, o5, o6, o7] = r;
    CHECK(unvisited(v, o0, o1, o2, o3, o4, o5, o6, o7) == 0);
    CHECK(v.count == 8);
  }

  TEST_CASE("RomParams: every field is in visit_rom_params once, friction in its group") {
    cvt::RomParams p;
    Visited v;
    cvt::visit_rom_params(p, v);
    CHECK(v.duplicates == 0);
    auto& [a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34, a35, a36, a37, a38, a39, a40, a41, a42, a43, a44] = p;
    CHECK(unvisited(v, a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34, a35, a36, a37, a38, a39, a40, a41, a42, a43, a44) == 0);
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8] = p.friction;
    CHECK(unvisited(v, f0, f1, f2, f3, f4, f5, f6, f7, f8) == 0);
    CHECK(v.count == 45 - 1 + 9);
    CHECK(v.names.count("friction.mu0") == 1);
    CHECK(v.names.count(".beta0_deg") == 1);
  }

  TEST_CASE("calibrate fits the lumped parameters: the seventeen docs/cli.md#calibrate names") {
    const std::set<std::string> documented = {
        "k1_N_m", "c1_Ns_m", "k2_N_m", "c2_Ns_m", "lump_mass_kg", "r1_m", "r2_m", "normal_load_factor",
        "entry_load_share", "wrap_tension_share", "chain_mass_kg_m", "chain_stiffness_N", "creep_gain",
        "centrifugal_gain", "stop_tension_N", "stop_tension_share", "wrap_excess_share"};
    const std::vector<std::string> names = cvt::validation::fittable_names();
    CHECK(std::set<std::string>(names.begin(), names.end()) == documented);
    CHECK(names.size() == documented.size());
  }

  TEST_CASE("rom_param_number finds a [params] number by its key and nothing else") {
    cvt::RomParams p;
    CHECK(cvt::rom_param_number(p, "k1_N_m") == &p.k1_N_m);
    cvt::ParamField f{};
    CHECK(cvt::rom_param_number(p, "beta0_deg", &f) == &p.beta0_rad);
    CHECK(f.to_si == cvt::kDegToRad);
    CHECK(cvt::rom_param_number(p, "mu0") == nullptr);  // [friction], not [params]
    CHECK(cvt::rom_param_number(p, "fixed_sheaves") == nullptr);  // a flag
    CHECK(cvt::rom_param_number(p, "no_such_key") == nullptr);
  }
}
