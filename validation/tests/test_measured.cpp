// A test rig's measured log as a calibration case (docs/validation.md#measured-csv):
// the reader refuses every kind of bad log, the plant driven by a log
// reproduces the plant run by the same inputs, and a fit on a noisy log
// made by the plant with known parameters finds them again within the
// uncertainty it states.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "cvtplant/friction/friction_law.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/calibration.hpp"
#include "cvtplant/validation/errors.hpp"
#include "cvtplant/validation/measured.hpp"
#include "cvtplant/validation/plant.hpp"

using namespace cvt::validation;

namespace {

// A variable-ratio plant (wedging) with a road load, built here so the test
// does not move with a built-in scene's values. Its inputs: the clamping
// stepped 3.3 -> 3.4 kN at 0.3 s and the input torque 60 -> 70 N m at 0.6 s,
// so the ratio shifts and the speeds answer to the chain's lumps.
cvt::Scene rig_scene() {
  cvt::Scene s;
  s.name = "rig";
  s.features = cvt::rom_feature::axial | cvt::rom_feature::road_load | cvt::rom_feature::wedging;
  s.params.friction = cvt::friction_presets::table2_case1<double>();
  s.params.road_T0_Nm = 10.0;
  s.params.road_cv_Nms_rad = 0.05;
  s.params.road_ca_Nms2_rad2 = 0.002;
  s.initial.omega1_rad_s = 150.0;
  s.initial.omega2_rad_s = 100.0;
  s.tau_in = cvt::step_profile(60.0, 70.0, 0.6);
  s.clamp = cvt::step_profile(3300.0, 3400.0, 0.3);
  s.t_end_s = 1.5;
  return s;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cvt_measured_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// The plant's run of s as a rig's log, every `every`-th frame, with
// Gaussian noise of sd_rad_s on the speeds (fixed seed).
MeasuredLog log_of(const cvt::Scene& s, int every, double sd_rad_s, unsigned seed) {
  const Series r = plant_run(s, s.frame_s * every);
  MeasuredLog log;
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> noise(0.0, sd_rad_s);
  for (std::size_t i = 0; i < r.size(); ++i) {
    log.t_s.push_back(r.t_s[i]);
    log.tau_in_Nm.push_back(s.tau_in.at(r.t_s[i]));
    log.tau_load_Nm.push_back(s.tau_load.at(r.t_s[i]));
    log.clamp1_N.push_back(s.clamp.at(r.t_s[i]));
    log.omega1_rad_s.push_back(r.omega1_rad_s[i] + (sd_rad_s > 0 ? noise(gen) : 0.0));
    log.omega2_rad_s.push_back(r.omega2_rad_s[i] + (sd_rad_s > 0 ? noise(gen) : 0.0));
  }
  return log;
}

// A log file with the given text; removed when the test ends.
struct TempFile {
  std::string path;
  TempFile(const std::string& name, const std::string& text) : path(temp_path(name)) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

// The message read_measured_csv refuses a log with ("" if it reads it).
std::string refusal(const std::string& text) {
  const TempFile f("bad.csv", text);
  try {
    read_measured_csv(f.path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A well-formed log's header and rows, to be spoiled one way at a time.
const std::string kHeader = "time_s,tau_in_Nm,tau_load_Nm,clamp1_N,omega1_rad_s,omega2_rad_s\n";
const std::string kRows = "0,60,0,3300,150,100\n0.001,60,0,3300,150.1,100\n0.002,60,0,3300,150.2,100\n";

}  // namespace

TEST_SUITE("measured") {
  TEST_CASE("a log's columns are read in their units, pressures times the piston area") {
    const TempFile f("units.csv",
                     "# a rig's log\n# piston_area1_m2 = 0.01\n"
                     "time_ms,tau_in_Nm,p1_bar,omega1_rpm,omega2_rad_s,ratio\n"
                     "0,60,33,1500,100,1.5\n10,61,34,1510,101,1.49\n20,62,35,1520,102,1.48\n");
    const MeasuredLog log = read_measured_csv(f.path);
    REQUIRE(log.size() == 3u);
    CHECK(log.t_s[1] == doctest::Approx(0.01));
    CHECK(log.clamp1_N[0] == doctest::Approx(33e5 * 0.01));  // 33 bar on 100 cm^2 = 33 kN
    CHECK(log.omega1_rad_s[0] == doctest::Approx(1500 * 2 * 3.14159265358979 / 60));
    CHECK(log.tau_load_Nm == std::vector<double>(3, 0.0));  // no load column: none (the road load still acts)
    CHECK(log.has_ratio());
    CHECK(!log.has_clamp2());
    // An area the caller gives wins over the file's.
    CHECK(read_measured_csv(f.path, {0.02, 0}).clamp1_N[0] == doctest::Approx(33e5 * 0.02));
  }

  TEST_CASE("every kind of bad log is refused with the file and the reason") {
    CHECK(refusal(kHeader + kRows) == "");
    // A missing column.
    CHECK(refusal("time_s,tau_in_Nm,clamp1_N,omega1_rad_s\n0,1,2,3\n1,1,2,3\n2,1,2,3\n").find("secondary speed") !=
          std::string::npos);
    CHECK(refusal("time_s,tau_in_Nm,omega1_rad_s,omega2_rad_s\n0,1,3,3\n1,1,3,3\n2,1,3,3\n")
              .find("driver clamping") != std::string::npos);
    // Time not strictly increasing.
    CHECK(refusal(kHeader + kRows + "0.002,60,0,3300,150,100\n").find("time must increase") != std::string::npos);
    CHECK(refusal(kHeader + "0,60,0,3300,150,100\n0.002,60,0,3300,150,100\n0.001,60,0,3300,150,100\n")
              .find("data row 3") != std::string::npos);
    // NaN, and a cell that is not a number.
    CHECK(refusal(kHeader + kRows + "0.003,nan,0,3300,150,100\n").find("NaN") != std::string::npos);
    CHECK(refusal(kHeader + kRows + "0.003,60,0,3300,fast,100\n").find("not a number") != std::string::npos);
    // Too few rows.
    CHECK(refusal(kHeader + "0,60,0,3300,150,100\n0.001,60,0,3300,150,100\n").find("at least 3") !=
          std::string::npos);
    CHECK(refusal(kHeader).find("no data rows") != std::string::npos);
    // Unknown units (or quantity), and one quantity twice.
    const std::string rpm_s = "time_s,tau_in_Nm,clamp1_N,omega1_rps,omega2_rad_s\n0,1,2,3,4\n1,1,2,3,4\n2,1,2,3,4\n";
    CHECK(refusal(rpm_s).find("unknown column 'omega1_rps'") != std::string::npos);
    CHECK(refusal("time_s,tau_in_Nm,clamp1_N,p1_bar,omega1_rad_s,omega2_rad_s\n0,1,2,3,4,5\n1,1,2,3,4,5\n2,1,2,3,4,"
                  "5\n")
              .find("both a force") != std::string::npos);
    CHECK(refusal("time_s,time_ms,tau_in_Nm,clamp1_N,omega1_rad_s,omega2_rad_s\n0,0,1,2,3,4\n1,1,1,2,3,4\n2,2,1,2,"
                  "3,4\n")
              .find("given twice") != std::string::npos);
    // A row of another width; a pressure without its area, a bad area; a negative clamping.
    CHECK(refusal(kHeader + kRows + "0.003,60,0,3300,150\n").find("5 cells") != std::string::npos);
    CHECK(refusal("time_s,tau_in_Nm,p1_bar,omega1_rad_s,omega2_rad_s\n0,1,2,3,4\n1,1,2,3,4\n2,1,2,3,4\n")
              .find("piston area") != std::string::npos);
    CHECK(refusal("# piston_area1_m2 = -1\n" + kHeader + kRows).find("positive area") != std::string::npos);
    CHECK(refusal(kHeader + kRows + "0.003,60,0,-5,150,100\n").find("clamping must be >= 0") != std::string::npos);
    // Not a file.
    CHECK_THROWS_AS(read_measured_csv(temp_path("missing.csv")), InputError);
    CHECK_THROWS_AS(read_measured_csv(std::filesystem::temp_directory_path().string()), InputError);
  }

  TEST_CASE("a driven clamping log needs a plant with driven clamping") {
    const TempFile f("clamp2.csv", "time_s,tau_in_Nm,clamp1_N,clamp2_N,omega1_rad_s,omega2_rad_s\n"
                                   "0,60,3300,3600,150,100\n0.001,60,3300,3600,150,100\n0.002,60,3300,3600,150,100\n");
    const MeasuredLog log = read_measured_csv(f.path);
    cvt::Scene fixed_ratio = rig_scene();
    fixed_ratio.features = cvt::rom_feature::axial | cvt::rom_feature::road_load;
    Calibration cal({"k1_N_m"}, fixed_ratio.params);
    CHECK_THROWS_AS(cal.add_measured_case("clamp2", fixed_ratio, log, 1), InputError);
    Calibration wedging({"k1_N_m"}, rig_scene().params);
    CHECK_NOTHROW(wedging.add_measured_case("clamp2", rig_scene(), log, 1));
  }

  TEST_CASE("the plant driven by a log of its own inputs runs as the scene does") {
    // Rows every 5 ms; inputs constant over the row steps, so the driven
    // plant sees the scene's inputs frame by frame.
    cvt::Scene s = rig_scene();
    s.tau_in = cvt::constant_profile(60.0);
    s.clamp = cvt::constant_profile(3350.0);
    s.t_end_s = 0.5;
    const MeasuredLog log = log_of(s, 5, 0.0, 1);
    const Series scene_run = plant_run(s, 5 * s.frame_s);
    cvt::Scene driven = s;
    measured_start(log, driven.initial);
    CHECK(driven.initial.omega1_rad_s == doctest::Approx(s.initial.omega1_rad_s).epsilon(1e-3));
    driven.initial = s.initial;
    const Series d = measured_plant_run(driven, log, 1);
    REQUIRE(d.size() == scene_run.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      CHECK(d.t_s[i] == doctest::Approx(scene_run.t_s[i]).epsilon(1e-12));
      CHECK(d.omega1_rad_s[i] == doctest::Approx(scene_run.omega1_rad_s[i]).epsilon(1e-12));
      CHECK(d.omega2_rad_s[i] == doctest::Approx(scene_run.omega2_rad_s[i]).epsilon(1e-12));
      CHECK(d.ratio_geom[i] == doctest::Approx(scene_run.ratio_geom[i]).epsilon(1e-12));
    }
  }

  // Cost: about 0.1 s (host release), a 1.5 s log of 1 ms rows and about
  // 45 plant runs of it.
  TEST_CASE("a fit on a noisy log recovers the parameters within three stated standard deviations") {
    const cvt::Scene truth = rig_scene();
    // Noise of 0.2 rad/s (about 0.15 %) on both speeds, written and read back as a rig's CSV.
    const TempFile f("noisy.csv", "");
    write_measured_csv(f.path, log_of(truth, 1, 0.2, 7));
    const MeasuredLog log = read_measured_csv(f.path);
    REQUIRE(log.size() == 1501u);
    // A start 15-25 % off; creep_gain belongs to the tension feature, which
    // this plant has not: the log cannot see it.
    cvt::Scene start = truth;
    start.params.normal_load_factor *= 1.15;
    start.params.k1_N_m *= 0.8;
    start.params.c1_Ns_m *= 1.2;
    const std::vector<std::string> names = {"normal_load_factor", "k1_N_m", "c1_Ns_m", "creep_gain"};
    const double truths[] = {truth.params.normal_load_factor, truth.params.k1_N_m, truth.params.c1_Ns_m};
    Calibration cal(names, start.params);
    cal.add_measured_case("noisy", start, log, 1);
    CHECK(cal.min_evaluations() == 4 + 2 + 2);  // four parameters and the two start speeds
    const CalibrationResult r = cal.run(200);
    REQUIRE(r.params.size() == 4u);
    CHECK(r.faults == 0);
    CHECK(r.residuals == 2 * 1501);
    for (int i = 0; i < 3; ++i) {
      const FittedParam& p = r.params[static_cast<std::size_t>(i)];
      INFO(p.name << ": truth " << truths[i] << ", start " << p.start << ", fitted " << p.value << " +- " << p.sigma);
      CHECK(p.identifiable);
      CHECK(std::fabs(p.value - truths[i]) < 3.0 * p.sigma);
      // Honest: small against the value, yet not below what the noise allows.
      CHECK(p.sigma_rel < 0.1);
      CHECK(p.sigma_rel > 1e-5);
      // The start was outside the uncertainty: the fit moved the value.
      CHECK(std::fabs(p.start - truths[i]) > 10.0 * p.sigma);
    }
    CHECK_FALSE(r.params[3].identifiable);
    CHECK(r.params[3].value == truth.params.creep_gain);
    // What is left is the noise: rms of 0.2 rad/s over the speeds' rms, per quantity.
    const double rel_noise_1 = 0.2 / 157.0, rel_noise_2 = 0.2 / 108.0;
    REQUIRE(r.cases.size() == 1u);
    CHECK(r.cases[0].measured);
    // The start speeds, fitted with the parameters, are the truth's.
    const auto& v = r.cases[0].start_speeds;
    CHECK(std::fabs(v.omega1_rad_s - truth.initial.omega1_rad_s) < 3.0 * v.sigma1_rad_s);
    CHECK(std::fabs(v.omega2_rad_s - truth.initial.omega2_rad_s) < 3.0 * v.sigma2_rad_s);
    CHECK(v.sigma1_rad_s < 0.2);  // below one sample's noise
    CHECK(v.sigma2_rad_s < 0.2);
    CHECK(r.cases[0].rel_rms_end[0] == doctest::Approx(rel_noise_1).epsilon(0.1));
    CHECK(r.cases[0].rel_rms_end[1] == doctest::Approx(rel_noise_2).epsilon(0.1));
  }

  TEST_CASE("without noise the fit finds the parameters to the last digits") {
    const cvt::Scene truth = rig_scene();
    const MeasuredLog log = log_of(truth, 1, 0.0, 1);
    cvt::Scene start = truth;
    start.params.k1_N_m *= 0.8;
    start.params.c1_Ns_m *= 1.2;
    Calibration cal({"k1_N_m", "c1_Ns_m"}, start.params);
    cal.add_measured_case("exact", start, log, 1);
    const CalibrationResult r = cal.run(200);
    CHECK(r.params[0].value == doctest::Approx(truth.params.k1_N_m).epsilon(1e-8));
    CHECK(r.params[1].value == doctest::Approx(truth.params.c1_Ns_m).epsilon(1e-8));
    CHECK(r.cost_end < 1e-20);
  }
}
