// A plant scene as the reference's inputs (docs/validation.md#method): what
// is copied, what each profile becomes, and what is refused with a reason.
#include <doctest/doctest.h>

#include <string>

#include "cvtplant/scene/builtin_scenes.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/reference.hpp"
#include "cvtplant/validation/scene_check.hpp"

using namespace cvt::validation;
using cvt::mbd::SheaveMode;

namespace {

cvt::Scene builtin(const char* name) {
  const cvt::Scene* s = cvt::find_builtin_scene(name);
  REQUIRE(s != nullptr);
  return *s;
}

}  // namespace

TEST_SUITE("reference") {
  TEST_CASE("seed-case1 runs on the reference's fixed sheaves with the scene's torques and friction") {
    const cvt::Scene s = builtin("seed-case1");
    std::string why;
    const auto p = reference_params(s, SheaveChoice::scene, why);
    REQUIRE(p);
    CHECK(why.empty());
    CHECK(p->sheaves == SheaveMode::fixed);
    CHECK(p->clamp1_N.empty());
    CHECK(p->tau_in_Nm.points == std::vector<std::pair<double, double>>{{0.0, 100.0}});
    CHECK(p->tau_load_Nm.points == std::vector<std::pair<double, double>>{{0.0, 50.0}});
    CHECK(p->friction.law == s.params.friction.law);
    CHECK(p->friction.mu0 == s.params.friction.mu0);
    CHECK(p->J1_kgm2 == s.params.J1_kgm2);
    CHECK_FALSE(p->start.active);
    // The chain stays the seed's: the plant's effective radii are not copied.
    CHECK(p->r1_m == cvt::mbd::seed_case(1).r1_m);
  }

  TEST_CASE("clamped sheaves follow the scene's clamping; a step becomes a 1 ms ramp; a start at speed") {
    const cvt::Scene s = builtin("clamp-step");
    std::string why;
    const auto p = reference_params(s, SheaveChoice::scene, why);
    REQUIRE(p);
    CHECK(p->sheaves == SheaveMode::clamped);
    REQUIRE(p->clamp1_N.points.size() == 2u);
    CHECK(p->clamp1_N.points[0] == std::pair<double, double>{2.0, 1200.0});
    CHECK(p->clamp1_N.points[1].first == doctest::Approx(2.001));
    CHECK(p->clamp1_N.points[1].second == 3000.0);
    CHECK(p->clamp2_N.empty());  // no wedging: the static thrust ratio
    CHECK(p->start.active);
    CHECK(p->start.omega1_rad_s == 150.0);
    CHECK(p->start.omega2_rad_s == 100.0);
    CHECK(p->road.T0_Nm == s.params.road_T0_Nm);
    CHECK(p->road.cv_Nms_rad == s.params.road_cv_Nms_rad);
  }

  TEST_CASE("wedging holds the driven clamping; --sheaves fixed overrides the scene") {
    std::string why;
    const auto w = reference_params(builtin("ratio-control"), SheaveChoice::scene, why);
    REQUIRE(w);
    CHECK(w->clamp2_N.points == std::vector<std::pair<double, double>>{{0.0, builtin("ratio-control").params.driven_clamp_N}});
    const auto f = reference_params(builtin("gross-slip"), SheaveChoice::fixed, why);
    REQUIRE(f);
    CHECK(f->sheaves == SheaveMode::fixed);
    CHECK(f->clamp1_N.empty());
    CHECK(reference_sheaves(builtin("seed-case1"), SheaveChoice::clamped) == SheaveMode::clamped);
  }

  TEST_CASE("refused with the reason: held pulleys, lump states, a pulley at rest, sines, light clamping") {
    std::string why;
    CHECK_FALSE(reference_params(builtin("oscillator-coulomb"), SheaveChoice::scene, why));
    CHECK(why.find("held pulleys") != std::string::npos);

    cvt::Scene s = builtin("gross-slip");
    s.initial.x1_m = 1e-4;
    CHECK_FALSE(reference_params(s, SheaveChoice::scene, why));
    CHECK(why.find("initial lump") != std::string::npos);

    s = builtin("gross-slip");
    s.initial.omega1_rad_s = 10.0;
    CHECK_FALSE(reference_params(s, SheaveChoice::scene, why));
    CHECK(why.find("at rest") != std::string::npos);

    s = builtin("gross-slip");
    s.tau_in = cvt::sine_profile(100.0, 10.0, 5.0, 0.0);
    CHECK_FALSE(reference_params(s, SheaveChoice::scene, why));
    CHECK(why.find("a sine torque profile") != std::string::npos);

    s = builtin("gross-slip");
    s.clamp = cvt::constant_profile(50.0);
    CHECK_FALSE(reference_params(s, SheaveChoice::scene, why));
    CHECK(why.find("below 100 N") != std::string::npos);
    // On fixed sheaves the clamping is no input: the same scene runs.
    CHECK(reference_params(s, SheaveChoice::fixed, why));
  }

  TEST_CASE("the settings: run length, sample interval, and the sheave choice by name") {
    RunSettings st;
    st.t_end_s = 0.5;
    st.rtol = 1e-6;
    const cvt::Scene s = builtin("tip-in");
    CHECK(run_length_s(s, st) == 0.5);
    std::string why;
    const auto setup = reference_setup(s, st, why);
    REQUIRE(setup);
    CHECK(setup->run.t_end_s == 0.5);
    CHECK(setup->run.rtol == 1e-6);
    CHECK(setup->run.sample_s == s.frame_s);
    st.t_end_s = 0;
    CHECK(run_length_s(s, st) == s.t_end_s);
    CHECK(sheave_choice("fixed") == SheaveChoice::fixed);
    CHECK(sheave_choice("scene") == SheaveChoice::scene);
    CHECK_THROWS_AS(sheave_choice("loose"), InputError);
    CHECK(std::string(sheave_mode_name(SheaveMode::clamped)) == "clamped");
  }
}
