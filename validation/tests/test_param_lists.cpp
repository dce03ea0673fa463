// Every field of the parameter structs is in its list: the reference's
// field list (mbd/params_fields.hpp) for MbdParams and RunOptions, the
// scene's parameter rows (scene/scene_params.hpp) for RomParams and
// RomInitial. The lists are what the reference cache's key, the scene-file
// reader, the FMU's parameters and calibrate walk, so a field missing from
// one would be silently left out (a stale cache hit, a key a file cannot
// set).
//
// The structured bindings below decompose each struct into exactly as many
// names as it has fields: a field added to a struct fails to compile here
// ("decomposes into N elements") until a name is added, and the test then
// fails until the field is in its list too.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "cvtplant/mbd/params_fields.hpp"
#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/scene/scene_params.hpp"
#include "cvtplant/validation/cache.hpp"
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

// Another valid value of a field's type.
template <class X>
void perturb(X& x) {
  if constexpr (std::is_same_v<X, bool>)
    x = !x;
  else if constexpr (std::is_enum_v<X>)
    x = static_cast<X>(static_cast<int>(x) == 0 ? 1 : 0);
  else if constexpr (std::is_arithmetic_v<X>)
    x = x * 1.5 + 1.0;
  // a nested struct is checked field by field
}

// The rows of the scene's parameter list whose value differs between a and b.
int rows_that_differ(const cvt::Scene& a, const cvt::Scene& b) {
  int n = 0;
  for (const cvt::SceneParamInfo& r : cvt::kSceneParams) n += r.get(a) != r.get(b) ? 1 : 0;
  return n;
}

// For the k-th field (of n) that fields(scene) binds: changed alone in a
// copy of base, does a row see it? Counts the fields none sees.
template <class Fields>
int fields_no_row_sees(const cvt::Scene& base, int n, Fields&& fields) {
  int unseen = 0;
  for (int k = 0; k < n; ++k) {
    cvt::Scene s = base;
    fields(s, k);
    if (rows_that_differ(base, s) != 1) {
      MESSAGE("field " << k << " is seen by " << rows_that_differ(base, s) << " rows");
      ++unseen;
    }
  }
  return unseen;
}

// Perturbs the k-th of the bound fields.
template <class... B>
void perturb_kth(int k, B&... fields) {
  int i = 0;
  ((i++ == k ? perturb(fields) : void()), ...);
}

}  // namespace

TEST_SUITE("param_lists") {
  TEST_CASE("MbdParams: every field, nested ones included, is in visit_mbd_params once") {
    cvt::mbd::MbdParams p;
    Visited v;
    cvt::mbd::visit_mbd_params(p, v);
    CHECK(v.duplicates == 0);
    auto& [a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34] = p;
    // The friction coefficients are visited as copies (their names are the
    // scene's rows): friction's fields are checked by the key below.
    CHECK(unvisited(v, a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34) == 0);
    CHECK(unvisited(v, p.friction.law, p.friction.sign) == 0);
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

  TEST_CASE("every FrictionParams field moves the reference's cache key") {
    const cvt::mbd::MbdParams base = cvt::mbd::seed_case(2);
    const cvt::mbd::RunOptions run;
    const std::string key = cvt::validation::reference_key(base, run);
    for (int k = 0; k < 9; ++k) {
      cvt::mbd::MbdParams p = base;
      auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8] = p.friction;
      perturb_kth(k, f0, f1, f2, f3, f4, f5, f6, f7, f8);
      INFO("friction field " << k);
      CHECK(cvt::validation::reference_key(p, run) != key);
    }
  }

  TEST_CASE("RunOptions: every field is in visit_run_options") {
    cvt::mbd::RunOptions r;
    Visited v;
    cvt::mbd::visit_run_options(r, v);
    auto& [o0, o1, o2, o3, o4, o5, o6, o7, o8] = r;
    CHECK(unvisited(v, o0, o1, o2, o3, o4, o5, o6, o7, o8) == 0);
    CHECK(v.count == 9);
  }

  TEST_CASE("RomParams and RomInitial: every number and flag is one row of the scene's parameter list") {
    const cvt::Scene base = *cvt::find_builtin_scene("ratio-control");
    // RomParams' fields but friction (the struct of field 13), each alone.
    CHECK(fields_no_row_sees(base, 45, [](cvt::Scene& s, int k) {
      auto& [a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34, a35, a36, a37, a38, a39, a40, a41, a42, a43, a44] = s.params;
      if (k != 13) perturb_kth(k, a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, a17, a18, a19, a20, a21, a22, a23, a24, a25, a26, a27, a28, a29, a30, a31, a32, a33, a34, a35, a36, a37, a38, a39, a40, a41, a42, a43, a44);
    }) == 1);  // the friction struct itself
    // Friction: the seven coefficients are rows; law and sign are chosen by
    // name (friction/friction_fields.hpp), not numbers.
    CHECK(fields_no_row_sees(base, 9, [](cvt::Scene& s, int k) {
      auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8] = s.params.friction;
      perturb_kth(k, f0, f1, f2, f3, f4, f5, f6, f7, f8);
    }) == 2);
    CHECK(fields_no_row_sees(base, 8, [](cvt::Scene& s, int k) {
      auto& [i0, i1, i2, i3, i4, i5, i6, i7] = s.initial;
      perturb_kth(k, i0, i1, i2, i3, i4, i5, i6, i7);
    }) == 0);
    // And no row without a field: 45 - 1 + 7 + 8 rows.
    CHECK(cvt::kSceneParamCount == 45 - 1 + 7 + 8);
  }

  TEST_CASE("calibrate fits the lumped parameters: the seventeen docs/cli.md#calibrate names, each a [params] row") {
    const std::set<std::string> documented = {
        "k1_N_m", "c1_Ns_m", "k2_N_m", "c2_Ns_m", "lump_mass_kg", "r1_m", "r2_m", "normal_load_factor",
        "entry_load_share", "wrap_tension_share", "chain_mass_kg_m", "chain_stiffness_N", "creep_gain",
        "centrifugal_gain", "stop_tension_N", "stop_tension_share", "wrap_excess_share"};
    const std::vector<std::string> names = cvt::validation::fittable_names();  // throws for a name without a row
    CHECK(std::set<std::string>(names.begin(), names.end()) == documented);
    CHECK(names.size() == documented.size());
  }
}
