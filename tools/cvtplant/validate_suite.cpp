// `cvtplant validate --suite` (docs/validation.md#suite): the validation
// module's suite check, its options checked and its results printed.
#include "validate_suite.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "progress.hpp"
#include "scene_file.hpp"
#include "cvtplant/validation/reference.hpp"
#include "cvtplant/validation/report.hpp"
#include "cvtplant/validation/suite_check.hpp"

namespace cvtcli {

namespace {

namespace val = cvt::validation;

nlohmann::json jnum(double v) { return json_number(v); }
std::string pct(double v) { return pct_text(v); }
std::string num(double v) { return num_text(v); }

// An uncertainty: small, so two significant digits.
std::string upct(double v) {
  if (!std::isfinite(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.2g %%", 100.0 * v);
  return b;
}


// A goal's error in the table: bold where it misses its limit.
std::string cell(const val::GoalRow& r) {
  const std::string e = pct(r.error);
  return std::isfinite(r.error) && !r.met() ? "**" + e + "**" : e;
}

// The reference's uncertainty beside an error: u_val (u_num, u_input).
std::string u_text(const val::GoalRow& r) {
  if (!r.has_u) return "";
  return upct(r.u.u_val()) + " (" + upct(r.u.u_num()) + ", " + upct(r.u.u_input) + ")";
}

nlohmann::json to_json(const val::Uncertainty& u) {
  nlohmann::json j{{"u_num_rtol10", jnum(u.u_num10)},
                   {"u_num_rtol100", jnum(u.u_num100)},
                   {"u_input", jnum(u.u_input)},
                   {"u_val", jnum(u.u_val())}};
  j["inputs"] = nlohmann::json::object();
  for (const auto& [name, share] : u.inputs) j["inputs"][name] = jnum(share);
  return j;
}

nlohmann::json to_json(const val::GoalRow& r) {
  nlohmann::json j{{"goal", r.goal},   {"where", r.where},        {"held_out", r.held_out},
                   {"error", jnum(r.error)}, {"limit", r.limit}, {"met", std::isfinite(r.error) && r.met()}};
  j["uncertainty"] = r.has_u ? to_json(r.u) : nlohmann::json(nullptr);
  j["uncertainty_from"] = r.has_u ? nlohmann::json(r.u_from) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json to_json(const val::ManoeuvreCheck& k, const std::string& csv, const std::string& png) {
  nlohmann::json j{{"name", k.m.name}, {"kind", k.m.kind}, {"held_out", k.held_out}, {"t_end_s", k.m.t_end_s}};
  j["start"] = {{"omega1_rad_s", k.m.start.omega1_rad_s},
                {"ratio", k.m.start.ratio},
                {"tau_in_Nm", k.m.start.tau_in_Nm},
                {"clamp2_N", k.m.start.clamp2_N}};
  j["reference"] = {{"cpu_s", k.ref.cpu_s},
                    {"steps", k.ref.steps},
                    {"from_cache", k.ref.from_cache},
                    {"failure", k.ref.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(k.ref.failure)},
                    {"samples", k.ref.series.size()},
                    {"hold_clamp1_N", jnum(val::reference_hold_clamp1_N(k.m, k.ref.series))}};
  j["plant"] = {{"samples", k.plant.size()},
                {"hold_clamp1_N", jnum(k.hold.clamp1_N)},
                {"hold_r1_rate_m_s", jnum(k.hold.r1_rate_m_s)},
                {"hold_trials", k.hold.trials}};
  j["errors"] = nlohmann::json::array();
  for (const auto& e : k.cmp.rows)
    j["errors"].push_back({{"quantity", e.quantity},
                           {"unit", e.unit},
                           {"rel_rms", jnum(e.rel_rms)},
                           {"plant_ss", jnum(e.plant_ss)},
                           {"reference_ss", jnum(e.reference_ss)},
                           {"ss_rel", jnum(e.ss_rel)}});
  j["gross_slip_s"] = {{"plant", k.cmp.gross_slip_plant_s >= 0 ? jnum(k.cmp.gross_slip_plant_s) : nullptr},
                       {"reference", k.cmp.gross_slip_reference_s >= 0 ? jnum(k.cmp.gross_slip_reference_s) : nullptr}};
  j["csv"] = csv;
  j["png"] = png.empty() ? nlohmann::json(nullptr) : nlohmann::json(png);
  return j;
}

nlohmann::json maps_json(const val::Maps& m) {
  nlohmann::json j;
  j["thrust_ratio"] = nlohmann::json::array();
  for (const auto& c : m.thrust)
    j["thrust_ratio"].push_back({{"ratio", c.ratio},
                                 {"torque_Nm", c.torque_Nm},
                                 {"clamp2_N", c.clamp2_N},
                                 {"torque_ratio", jnum(c.torque_ratio)},
                                 {"kappa_ref", jnum(c.kappa_ref)},
                                 {"kappa_plant", jnum(c.kappa_plant)},
                                 {"drift_ref_per_s", jnum(c.drift_ref_per_s)}});
  j["shift_rate"] = nlohmann::json::array();
  for (const auto& c : m.shift)
    j["shift_rate"].push_back({{"omega1_rad_s", c.omega1_rad_s},
                               {"ratio", c.ratio},
                               {"clamp2_N", c.clamp2_N},
                               {"delta_ln_F1_F2", c.delta},
                               {"rate_ref_per_s", c.rate_ref},
                               {"rate_plant_per_s", c.rate_plant},
                               {"slope_ref", jnum(c.slope_ref)},
                               {"slope_plant", jnum(c.slope_plant)},
                               {"r2_ref", jnum(c.r2_ref)},
                               {"r2_plant", jnum(c.r2_plant)}});
  j["gross_slip_onset"] = nlohmann::json::array();
  for (const auto& o : m.onset)
    j["gross_slip_onset"].push_back({{"torque_Nm", o.torque_Nm},
                                     {"clamp_ref_N", jnum(o.clamp_ref_N)},
                                     {"clamp_plant_N", jnum(o.clamp_plant_N)},
                                     {"clamp_closed_form_N", jnum(o.clamp_closed_N)}});
  return j;
}

// The run goals in the order of a run's row (suite_check.cpp's list).
const char* const kRunGoalNames[] = {"ratio RMS", "geometric ratio RMS", "omega1 RMS",
                                     "omega2 RMS", "mean F_ax1", "mean F_ax2"};

void print_text(const val::SuiteResult& r, const SuiteCliOptions& o, const char* set, const std::string& dir,
                const std::vector<std::string>& map_files) {
  std::printf("# suite %s against the reference (%s set, rtol %g); plant: %s%s\n\n", r.suite.name.c_str(), set,
              o.ref.rtol, o.plant.c_str(), o.params.empty() ? "" : (", parameters " + o.params).c_str());
  std::printf("%s.\n\n", r.suite.summary.c_str());
  std::printf("%d reference runs (%d from the cache), %.1f s of reference CPU in this invocation; overlays in %s.\n\n",
              r.reference_runs,
              r.from_cache, r.reference_cpu_s, dir.c_str());
  std::printf("Relative errors of the plant against the reference (bold: over the goal; goals: ratio %g %% RMS, "
              "speeds %g %% RMS, mean axial forces %g %%; u: the reference's own uncertainty u_val where measured, on the "
              "run or its kind, below). Holding F1: the plant's driver clamping that holds the "
              "start's ratio over the reference's.\n\n",
              100 * val::GoalLimits::ratio, 100 * val::GoalLimits::speed, 100 * val::GoalLimits::axial);
  std::printf("| run | kind | fit | ratio RMS | r2/r1 RMS | omega1 RMS | omega2 RMS | mean F_ax1 | mean F_ax2 | "
              "holding F1 | note |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& k : r.runs) {
    std::printf("| %s | %s | %s |", k.m.name.c_str(), k.m.kind.c_str(), k.held_out ? "held out" : "fit");
    for (const char* g : kRunGoalNames)
      for (const auto& row : r.goals)
        if (row.where == k.m.name && row.goal == g)
          std::printf(" %s%s |", cell(row).c_str(), row.has_u ? (" (u " + upct(row.u.u_val()) + ")").c_str() : "");
    const double ref_hold = val::reference_hold_clamp1_N(k.m, k.ref.series);
    std::printf(" %s | %s |\n", pct(k.hold.clamp1_N / ref_hold - 1.0).c_str(),
                k.ref.failure.empty() ? "" : k.ref.failure.c_str());
  }
  if (r.has_maps) {
    std::printf("\nMaps (CSV and figures in %s/maps): errors of the plant's cell against the reference's (goals: "
                "thrust ratio %g %%, shift-rate slope %g %%, gross-slip onset %g %%).\n\n",
                dir.c_str(), 100 * val::GoalLimits::thrust, 100 * val::GoalLimits::shift, 100 * val::GoalLimits::onset);
    std::printf("| goal | cell | error | reference's u_val (u_num, u_input) |\n|---|---|---|---|\n");
    for (const auto& row : r.goals)
      if (row.goal == "thrust-ratio cell" || row.goal == "shift-rate slope" || row.goal == "gross-slip onset clamping")
        std::printf("| %s | %s | %s | %s |\n", row.goal.c_str(), row.where.c_str(), cell(row).c_str(),
                    u_text(row).c_str());
    std::printf("\nShift rate against ln(F1/F2) (the creep-mode law: slope proportional to the primary speed):\n\n"
                "| primary speed | ratio | slope ref. [1/s] | slope plant [1/s] | ref. slope / omega1 [1/rad] | R^2 ref. |\n"
                "|---|---|---|---|---|---|\n");
    for (const auto& c : r.maps.shift)
      std::printf("| %g rad/s | %g | %s | %s | %s | %s |\n", c.omega1_rad_s, c.ratio, num(c.slope_ref).c_str(),
                  num(c.slope_plant).c_str(), num(c.slope_ref / c.omega1_rad_s).c_str(), num(c.r2_ref).c_str());
    for (const auto& f : map_files) std::printf("%s%s", &f == &map_files.front() ? "\nFiles: " : ", ", f.c_str());
    std::printf("\n");
  }
  if (!r.uncertainty.empty()) {
    std::printf("\nThe reference's own uncertainty (ASME V&V 20 manner): u_num the change at the tolerance / 10 and "
                "/ 100, u_input each open choice's spread / (2 sqrt 3), u_val = sqrt(u_num(100)^2 + u_input^2).\n\n"
                "| measured on | quantity | u_num /10 | u_num /100 | u_input | u_val |\n|---|---|---|---|---|---|\n");
    for (const auto& m : r.uncertainty)
      std::printf("| %s | %s | %s | %s | %s | %s |\n", m.where.c_str(), m.goal.c_str(), upct(m.u.u_num10).c_str(),
                  upct(m.u.u_num100).c_str(), upct(m.u.u_input).c_str(), upct(m.u.u_val()).c_str());
  }
  // Met per goal, fit and held out apart.
  std::printf("\n| goal | met (fit) | met (held out) |\n|---|---|---|\n");
  std::vector<std::string> goals;
  for (const auto& row : r.goals)
    if (std::find(goals.begin(), goals.end(), row.goal) == goals.end()) goals.push_back(row.goal);
  for (const auto& g : goals) {
    int met[2] = {0, 0}, n[2] = {0, 0};
    for (const auto& row : r.goals)
      if (row.goal == g && std::isfinite(row.error)) {
        ++n[row.held_out ? 1 : 0];
        met[row.held_out ? 1 : 0] += row.met() ? 1 : 0;
      }
    std::printf("| %s | %d/%d | %d/%d |\n", g.c_str(), met[0], n[0], met[1], n[1]);
  }
}

}  // namespace

int run_validate_suite(const SuiteCliOptions& o) {
  const val::Suite suite = val::suite_by_name(o.suite);
  val::ReferenceConfig cfg;
  cfg.set = val::parameter_set(o.ref.set.empty() ? "production" : o.ref.set);
  cfg.rtol = o.ref.rtol;
  if (!(o.ref.rtol >= 1e-11 && o.ref.rtol <= 1e-3)) throw UsageError{"--rtol: outside [1e-11, 1e-3]"};
  if (!(o.ref.max_steps >= 1 && o.ref.max_steps <= 1000000000000LL))
    throw UsageError{"--max-steps: outside [1, 1e12]"};
  cfg.max_steps_per_frame = std::min<long long>(o.ref.max_steps, 200000);
  val::SuiteOptions so;
  so.maps = o.maps;
  so.uncertainty = o.uncertainty;
  auto plant = resolve_scene(o.plant);
  cvt::Scene plant_scene = plant->scene;
  if (!o.params.empty()) apply_params_file(o.params, plant_scene);
  if ((plant_scene.features & cvt::rom_feature::wedging) == 0)
    throw UsageError{"--scene " + o.plant + ": a suite's plant needs the wedging feature (a variable ratio)"};
  const double total_s = val::suite_reference_s(suite, cfg, so);
  if (!(o.max_sim_s > 0 && std::isfinite(o.max_sim_s))) throw UsageError{"--max-t-end: must be > 0"};
  if (total_s > o.max_sim_s)
    throw UsageError{"suite " + o.suite + ": " + num(total_s) + " s of reference exceeds --max-t-end " +
                     num(o.max_sim_s) + " s (raise it, or --no-maps / --uncertainty none)"};
  prepare_out_dir(o.ref);
  const std::string dir = o.ref.out_dir + "/suite-" + o.suite;
  std::error_code ec;
  std::filesystem::create_directories(dir + "/maps", ec);
  if (ec) throw UsageError{"--out-dir: cannot create " + dir + "/maps: " + ec.message()};
  val::SuiteResult r;
  {
    Progress progress("validate --suite " + o.suite + ": reference", total_s);
    r = val::check_suite(suite, plant_scene, cfg, o.ref.out_dir + "/reference-cache", so,
                         [&](double t) { progress.update(t); });
  }
  std::vector<std::string> csvs, pngs;
  for (const auto& k : r.runs) {
    csvs.push_back(dir + "/" + k.m.name + ".csv");
    std::FILE* f = open_output(csvs.back());
    val::write_overlay_csv(f, k.plant, k.ref.series);
    close_output(f);
    pngs.emplace_back();
    if (o.figures) {
      pngs.back() = dir + "/" + k.m.name + ".png";
      val::write_overlay_png(dir, k.m.name, csvs.back(), pngs.back(), k.cmp.compared_s, k.m.t_end_s);
    }
  }
  const std::vector<std::string> map_files = r.has_maps ? val::write_maps(r.maps, dir + "/maps", o.figures)
                                                        : std::vector<std::string>{};
  const char* set = cvt::mbd::parameter_set_name(cfg.set);
  if (o.json) {
    nlohmann::json j;
    j["subcommand"] = "validate";
    j["suite"] = suite.name;
    j["summary"] = suite.summary;
    j["set"] = set;
    j["rtol"] = cfg.rtol;
    j["plant_scene"] = o.plant;
    j["uncertainty_plan"] = o.uncertainty;
    j["out_dir"] = dir;
    j["reference_runs"] = r.reference_runs;
    j["from_cache"] = r.from_cache;
    j["reference_cpu_s"] = r.reference_cpu_s;
    j["limits"] = {{"ratio", val::GoalLimits::ratio},   {"speed", val::GoalLimits::speed},
                   {"axial", val::GoalLimits::axial},   {"thrust", val::GoalLimits::thrust},
                   {"shift", val::GoalLimits::shift},   {"onset", val::GoalLimits::onset}};
    j["runs"] = nlohmann::json::array();
    for (std::size_t i = 0; i < r.runs.size(); ++i) j["runs"].push_back(to_json(r.runs[i], csvs[i], pngs[i]));
    j["goals"] = nlohmann::json::array();
    for (const auto& g : r.goals) j["goals"].push_back(to_json(g));
    j["uncertainty"] = nlohmann::json::array();
    for (const auto& m : r.uncertainty) j["uncertainty"].push_back({{"where", m.where}, {"goal", m.goal}, {"u", to_json(m.u)}});
    j["maps"] = r.has_maps ? maps_json(r.maps) : nlohmann::json(nullptr);
    j["map_files"] = map_files;
    print_json(j);
  } else {
    print_text(r, o, set, dir, map_files);
  }
  return 0;
}

}  // namespace cvtcli
