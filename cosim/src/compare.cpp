// The closed-loop comparison (docs/sil.md#compare).
#include "cvtplant/cosim/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "cvtplant/sil/harness/example_controller.hpp"
#include "cvtplant/sil/harness/fault_injector.hpp"
#include "cvtplant/sil/harness/harness_node.hpp"
#include "cvtplant/sil/harness/plant.hpp"
#include "cvtplant/sil/harness/report.hpp"
#include "cvtplant/sil/harness/runner.hpp"

namespace cvt::cosim {

namespace h = cvt::sil::harness;

namespace {

using ReferenceBridge = cvt::sil::BasicBridge<ReferencePlant>;
using LoopbackReference = h::LoopbackPlant<ReferenceBridge>;

// The harness's reply timeout on the loopback bus (docs/sil.md#lost-frames):
// the plant answers while it is serviced, so only a frame lost on purpose
// waits for it.
constexpr std::int64_t kLoopbackReply_ns = 20000000;

// One scenario on one plant: its own loopback bus, harness and example
// controller, as cvtplant-sil run --loopback wires them.
h::ScenarioResult run_one(const h::Scenario& sc, h::InProcessBus& bus, h::PlantUnderTest& plant,
                          const std::string& dir, const std::function<void(double)>& on_period) {
  h::FaultInjector faults(bus.harness_node());
  h::HarnessNode node(faults, kLoopbackReply_ns, plant.idle());
  if (!node.sync()) throw std::runtime_error("the plant on the loopback bus does not answer SimCtrl");
  // The controller as `cvtplant-sil run` wires it by default.
  const cvtctl::ClampLawParams law;
  const cvtctl::RatioLawParams ratio_law = h::example_ratio_law(law);
  h::ExampleController ctl(bus.controller_node(), law, ratio_law);
  h::RunConfig cfg;
  cfg.out_dir = dir;
  cfg.plant = &plant;
  cfg.on_period = on_period;
  return h::run_lockstep(sc, node, faults, ctl, cfg);
}

const h::Check* find_check(const h::ScenarioResult& r, const std::string& name) {
  for (const h::Check& c : r.checks)
    if (c.name == name) return &c;
  return nullptr;
}

// The traces both runs record (docs/sil.md#compare), by their Sample member.
struct TraceDef {
  const char* name;
  const char* unit;
  float h::Sample::*member;
};
constexpr TraceDef kTraces[] = {
    {"ratio", "-", &h::Sample::geometric_ratio},   {"slip", "-", &h::Sample::slip},
    {"clamp_cmd", "N", &h::Sample::clamp_cmd_N},   {"axial", "N", &h::Sample::axial_N},
    {"driven_cmd", "N", &h::Sample::driven_cmd_N}, {"driven_axial", "N", &h::Sample::driven_axial_N},
    {"omega1", "rad/s", &h::Sample::omega1},       {"omega2", "rad/s", &h::Sample::omega2},
    {"torque", "N m", &h::Sample::torque_Nm},      {"safety", "-", &h::Sample::safety},
    {"radius1", "m", &h::Sample::radius1_m},
};

std::FILE* open_out(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error(path + ": cannot be written");
  return f;
}

void close_out(std::FILE* f, const std::string& path) {
  if (std::ferror(f) != 0 || std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string csv_text(const std::string& s) {
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

const char* verdict(const h::Check* c) {
  if (c == nullptr) return "absent";
  if (!c->judged) return "not judged";
  return c->pass ? "pass" : "FAIL";
}

void write_overlay(const std::string& path, const ScenarioComparison& c) {
  std::FILE* f = open_out(path);
  std::fprintf(f, "t_s,ratio_target,demand_Nm");
  for (const TraceDef& t : kTraces) std::fprintf(f, ",%s_rom,%s_ref", t.name, t.name);
  std::fprintf(f, ",stop_under_rom,stop_under_ref,stop_over_rom,stop_over_ref\n");
  const std::size_t n = std::max(c.rom.trace.size(), c.ref.trace.size());
  for (std::size_t i = 0; i < n; ++i) {
    const h::Sample* a = i < c.rom.trace.size() ? &c.rom.trace[i] : nullptr;
    const h::Sample* b = i < c.ref.trace.size() ? &c.ref.trace[i] : nullptr;
    const h::Sample& any = a != nullptr ? *a : *b;
    std::fprintf(f, "%.3f,%.6g,%.6g", any.t_s, any.ratio_target, any.demand_Nm);
    for (const TraceDef& t : kTraces)
      std::fprintf(f, ",%s,%s", a ? csv_number(a->*t.member).c_str() : "", b ? csv_number(b->*t.member).c_str() : "");
    auto flag = [](const h::Sample* s, bool h::Sample::*m) { return s == nullptr ? "" : (s->*m ? "1" : "0"); };
    std::fprintf(f, ",%s,%s,%s,%s\n", flag(a, &h::Sample::stop_under), flag(b, &h::Sample::stop_under),
                 flag(a, &h::Sample::stop_over), flag(b, &h::Sample::stop_over));
  }
  close_out(f, path);
}

void write_tables(const std::string& dir, const std::vector<ScenarioComparison>& all) {
  const std::string crit = dir + "/compare-criteria.csv";
  std::FILE* f = open_out(crit);
  std::fprintf(f,
               "scenario,criterion,verdict_rom,verdict_ref,agree,value_rom,value_ref,limit,difference,"
               "beyond_fifth_of_limit,detail_rom,detail_ref\n");
  for (const ScenarioComparison& c : all)
    for (const CriterionPair& p : c.criteria)
      std::fprintf(f, "%s,%s,%s,%s,%d,%s,%s,%s,%s,%d,%s,%s\n", c.name(), p.name.c_str(), verdict(p.rom),
                   verdict(p.ref), p.agree ? 1 : 0, csv_number(p.rom ? p.rom->value : NAN).c_str(),
                   csv_number(p.ref ? p.ref->value : NAN).c_str(),
                   csv_number(p.rom ? p.rom->limit : (p.ref ? p.ref->limit : NAN)).c_str(),
                   csv_number(p.difference).c_str(), p.beyond_fifth_of_limit ? 1 : 0,
                   csv_text(p.rom ? p.rom->detail : "").c_str(), csv_text(p.ref ? p.ref->detail : "").c_str());
  close_out(f, crit);
  const std::string tr = dir + "/compare-traces.csv";
  f = open_out(tr);
  std::fprintf(f, "scenario,trace,unit,rms_difference,rms_rom,samples\n");
  for (const ScenarioComparison& c : all)
    for (const TraceDifference& t : c.traces)
      std::fprintf(f, "%s,%s,%s,%s,%s,%d\n", c.name(), t.name, t.unit, csv_number(t.rms_difference).c_str(),
                   csv_number(t.rms_rom).c_str(), t.samples);
  close_out(f, tr);
  const std::string sc = dir + "/compare-scenarios.csv";
  f = open_out(sc);
  std::fprintf(f,
               "scenario,description,verdict_rom,verdict_ref,verdicts_agree,criteria,criteria_agreeing,"
               "sim_s,ref_step_cpu_s,ref_realtime_factor,ref_release_cpu_s,ref_release_cached,ref_lifted_frames\n");
  for (const ScenarioComparison& c : all) {
    int agreeing = 0;
    for (const CriterionPair& p : c.criteria) agreeing += p.agree ? 1 : 0;
    std::fprintf(f, "%s,%s,%s,%s,%d,%zu,%d,%.3f,%.3f,%s,%.3f,%d,%ld\n", c.name(), csv_text(c.rom.what).c_str(),
                 c.rom.pass() ? "PASS" : "FAIL", c.ref.pass() ? "PASS" : "FAIL", c.verdicts_agree ? 1 : 0,
                 c.criteria.size(), agreeing, c.ref_sim_s, c.ref_step_cpu_s,
                 csv_number(c.ref_step_cpu_s > 0 ? c.ref_sim_s / c.ref_step_cpu_s : NAN).c_str(), c.ref_reset_cpu_s,
                 c.ref_release_cached ? 1 : 0, c.ref_lifted_frames);
  }
  close_out(f, sc);
}

}  // namespace

std::vector<ScenarioComparison> compare_scenarios(const CompareOptions& o) {
  namespace fs = std::filesystem;
  const std::string rom_dir = o.out_dir + "/rom", ref_dir = o.out_dir + "/reference";
  ReferenceOptions ro = o.reference;
  if (ro.release_cache_dir.empty()) ro.release_cache_dir = o.out_dir + "/reference-cache";
  for (const std::string& d : {rom_dir, ref_dir, ro.release_cache_dir}) {
    std::error_code ec;
    fs::create_directories(d, ec);
    if (ec) throw std::runtime_error(d + ": " + ec.message());
  }
  // One bus and plant per side for all scenarios, as a cvtplant-sil run has:
  // the bridges' counters run on, each run takes its baselines at its Reset.
  h::InProcessBus rom_bus, ref_bus;
  h::LoopbackBridgePlant rom_plant(rom_bus, 0);
  LoopbackReference ref_plant(ref_bus, 0, nullptr, ro);
  std::vector<ScenarioComparison> all;
  std::vector<h::ScenarioResult> rom_results, ref_results;
  for (const h::Scenario& sc : o.scenarios) {
    auto progress = [&o, &sc](const char* plant) -> std::function<void(double)> {
      if (!o.progress) return {};
      return [&o, &sc, plant](double t) { o.progress(plant, sc.name, t, sc.t_end_s); };
    };
    ScenarioComparison c;
    c.rom = run_one(sc, rom_bus, rom_plant, rom_dir, progress("rom"));
    c.ref = run_one(sc, ref_bus, ref_plant, ref_dir, progress("reference"));
    const ReferencePlant& rp = ref_plant.bridge().plant();
    c.ref_step_cpu_s = rp.step_cpu_s();
    c.ref_reset_cpu_s = rp.reset_cpu_s();
    c.ref_release_cached = rp.release_from_cache();
    c.ref_lifted_frames = rp.lifted_frames();
    c.ref_sim_s = static_cast<double>(rp.frames()) * static_cast<double>(rp.frame_ns()) * 1e-9;
    // Every criterion of either run, in the plant run's order, then any the
    // reference's run alone has.
    std::vector<std::string> names;
    for (const h::Check& k : c.rom.checks) names.push_back(k.name);
    for (const h::Check& k : c.ref.checks)
      if (std::find(names.begin(), names.end(), k.name) == names.end()) names.push_back(k.name);
    c.verdicts_agree = true;
    for (const std::string& n : names) {
      CriterionPair p;
      p.name = n;
      p.rom = find_check(c.rom, n);
      p.ref = find_check(c.ref, n);
      p.agree = p.rom != nullptr && p.ref != nullptr && p.rom->judged == p.ref->judged &&
                (!p.rom->judged || p.rom->pass == p.ref->pass);
      if (p.rom != nullptr && p.ref != nullptr) {
        p.difference = p.ref->value - p.rom->value;
        p.beyond_fifth_of_limit = std::fabs(p.difference) > 0.2 * std::fabs(p.rom->limit);
        // A value on one plant only (a recovery that never came) is beyond any bound.
        if (std::isfinite(p.rom->limit) && std::isfinite(p.rom->value) != std::isfinite(p.ref->value))
          p.beyond_fifth_of_limit = true;
      }
      c.verdicts_agree = c.verdicts_agree && p.agree;
      c.criteria.push_back(p);
    }
    const std::size_t common = std::min(c.rom.trace.size(), c.ref.trace.size());
    for (const TraceDef& t : kTraces) {
      TraceDifference d{t.name, t.unit};
      double sd = 0, sr = 0;
      for (std::size_t i = 0; i < common; ++i) {
        const double a = c.rom.trace[i].*t.member, b = c.ref.trace[i].*t.member;
        sd += (b - a) * (b - a);
        sr += a * a;
      }
      d.samples = static_cast<int>(common);
      d.rms_difference = common > 0 ? std::sqrt(sd / static_cast<double>(common)) : NAN;
      d.rms_rom = common > 0 ? std::sqrt(sr / static_cast<double>(common)) : NAN;
      c.traces.push_back(d);
    }
    write_overlay(o.out_dir + "/compare-" + sc.name + ".csv", c);
    rom_results.push_back(c.rom);
    ref_results.push_back(c.ref);
    all.push_back(std::move(c));
  }
  if (!h::write_junit(rom_dir + "/sil-junit.xml", rom_results) || !h::write_junit(ref_dir + "/sil-junit.xml", ref_results))
    throw std::runtime_error(o.out_dir + ": the JUnit files cannot be written");
  write_tables(o.out_dir, all);
  return all;
}

std::string comparison_table(const std::vector<ScenarioComparison>& all) {
  std::string out;
  char buf[400];
  int agree = 0;
  for (const ScenarioComparison& c : all) {
    agree += c.verdicts_agree ? 1 : 0;
    std::snprintf(buf, sizeof buf, "%s: plant %s, reference %s, verdicts %s; reference %.1f s in %.1f s of CPU (%.2fx real time)\n",
                  c.name(), c.rom.pass() ? "PASS" : "FAIL", c.ref.pass() ? "PASS" : "FAIL",
                  c.verdicts_agree ? "agree" : "DISAGREE", c.ref_sim_s, c.ref_step_cpu_s,
                  c.ref_step_cpu_s > 0 ? c.ref_sim_s / c.ref_step_cpu_s : 0.0);
    out += buf;
    std::snprintf(buf, sizeof buf, "  %-32s %-10s %-10s %10s %10s %8s %s\n", "criterion", "plant", "reference",
                  "plant", "reference", "limit", "");
    out += buf;
    for (const CriterionPair& p : c.criteria) {
      const bool numeric = p.rom != nullptr && std::isfinite(p.rom->limit);
      auto val = [](const h::Check* k) { return k != nullptr && std::isfinite(k->value) ? csv_number(k->value) : std::string("-"); };
      std::snprintf(buf, sizeof buf, "  %-32s %-10s %-10s %10s %10s %8s %s%s\n", p.name.c_str(), verdict(p.rom),
                    verdict(p.ref), numeric ? val(p.rom).c_str() : "", numeric ? val(p.ref).c_str() : "",
                    numeric ? csv_number(p.rom->limit).c_str() : "", p.agree ? "" : "verdicts differ",
                    p.beyond_fifth_of_limit ? (p.agree ? "differs > 20 % of the limit" : "; > 20 % of the limit") : "");
      out += buf;
    }
    out += "  RMS difference:";
    for (const TraceDifference& t : c.traces) {
      std::snprintf(buf, sizeof buf, " %s %s %s;", t.name, csv_number(t.rms_difference).c_str(), t.unit);
      out += buf;
    }
    out += "\n";
  }
  std::snprintf(buf, sizeof buf, "verdicts agree in %d of %zu scenarios\n", agree, all.size());
  return out + buf;
}

}  // namespace cvt::cosim
