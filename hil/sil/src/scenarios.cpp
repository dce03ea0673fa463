// The scenario table (docs/sil.md#scenarios, #ratio-scenarios, #fault-scenarios).
#include "cvtplant/sil/harness/scenario.hpp"

#include <cstdio>

namespace cvt::sil::harness {

float ramp(double t, double t0, double t1, float a, float b) {
  if (t <= t0) return a;
  if (t >= t1) return b;
  return a + (b - a) * static_cast<float>((t - t0) / (t1 - t0));
}

float clamp_supply(const Scenario& sc, double t) {
  return sc.clamp_drop_start_s >= 0 && t >= sc.clamp_drop_start_s - 1e-9 && t < sc.clamp_drop_end_s - 1e-9
             ? sc.clamp_drop_factor
             : 1.0f;
}

namespace {

// docs/sil.md#ratio-scenarios: the three ratio-control scenarios on the
// variable-ratio scene (ratio-control: wedging, 60 N m, road load).
void add_ratio_scenarios(std::vector<Scenario>& v) {
  Scenario sw{"ratio-sweep",
              "60 N m; set-point 1.5 -> 2.3 (low) -> 1.0 (overdrive) -> 1.5 in ramps, then beyond both end stops", 0,
              [](double) { return 60.0f; }};
  sw.scene = cvt::can::SceneId::RatioControl;
  sw.ratio_target = [](double t) {
    if (t < 4.0) return ramp(t, 0.5, 2.5, 1.5f, 2.3f);
    if (t < 9.0) return ramp(t, 4.0, 7.0, 2.3f, 1.0f);
    if (t < 12.0) return ramp(t, 9.0, 10.0, 1.0f, 1.5f);
    // The reference moves at no more than 0.5 ratio/s (docs/sil.md#ratio-control):
    // 2.3 s from 1.5 to the underdrive stop, 3.5 s from there to the overdrive one.
    if (t < 15.0) return 2.9f;  // beyond the underdrive stop (2.65)
    return 0.8f;                // beyond the overdrive stop (0.89)
  };
  sw.t_end_s = 20.0;
  sw.track_bound = 0.05;
  sw.expect_end_stop = true;
  sw.end_stops_by_s = 20.0;
  sw.min_t_end_s = 3.6;  // the first ramp's set-point held 1 s
  v.push_back(sw);
  Scenario kd{"kick-down", "ratio 1.0 at 40 N m; at 2 s tip-in to 120 N m over 0.2 s and set-point 1.0 -> 2.0", 6.0,
              [](double t) { return ramp(t, 2.0, 2.2, 40.0f, 120.0f); }};
  kd.scene = cvt::can::SceneId::RatioControl;
  kd.ratio_target = [](double t) { return t < 0.5 ? 1.5f : (t < 2.0 ? 1.0f : 2.0f); };
  kd.track_bound = 0.05;
  kd.settle_s = 2.5;  // the downshift takes 2 s at the bounded shift speed
  kd.min_t_end_s = 4.6;
  v.push_back(kd);
  Scenario sr{"slip-recovery", "ratio 1.5 at 100 N m; the clamping supply drops to 20 % for 500 ms at 1 s, then back",
              3.5, [](double) { return 100.0f; }};
  sr.scene = cvt::can::SceneId::RatioControl;
  sr.ratio_target = [](double) { return 1.5f; };
  sr.track_bound = 0.05;
  sr.clamp_drop_start_s = 1.0;
  sr.clamp_drop_end_s = 1.5;
  sr.clamp_drop_factor = 0.2f;
  sr.min_t_end_s = 2.6;
  v.push_back(sr);
}

}  // namespace

std::vector<Scenario> scenarios() {
  std::vector<Scenario> v;
  add_ratio_scenarios(v);
  Scenario ti{"tip-in", "driver demand 20 -> 120 N m over 0.2 s at 1 s", 3.0,
              [](double t) { return ramp(t, 1.0, 1.2, 20.0f, 120.0f); }};
  ti.min_t_end_s = 1.5;
  v.push_back(ti);
  Scenario ls{"load-step", "80 N m demand; harness load override 0 -> 100 N m at 1 s", 3.0,
              [](double) { return 80.0f; }};
  ls.load_override = true;
  ls.load_Nm = [](double t) { return t < 1.0 ? 0.0f : 100.0f; };
  ls.min_t_end_s = 1.5;
  v.push_back(ls);
  Scenario cl{"clamp-loss", "100 N m; the controller's CtrlCmd is lost for 200 ms at 1 s", 2.5,
              [](double) { return 100.0f; }};
  cl.link_loss_start_s = 1.0;
  cl.link_loss_end_s = 1.2;
  cl.min_t_end_s = 1.3;
  v.push_back(cl);
  Scenario lf{"lost-frames",
              "100 N m; two CtrlCmd lost at 0.5 s, a Step request at 0.8 s, a PlantStatus at 1.0 s, a PlantSpeeds at "
              "1.2 s",
              1.5, [](double) { return 100.0f; }};
  lf.faults.lost_cmd_periods = {50, 51};
  lf.faults.lost_step_period = 80;
  lf.faults.lost_status_period = 100;
  lf.faults.lost_speeds_period = 120;
  lf.min_t_end_s = 1.3;
  v.push_back(lf);
  Scenario fz{"frozen-controller", "100 N m; the controller hangs at 1 s for 300 ms, its CAN driver repeating its last frame",
              2.0, [](double) { return 100.0f; }};
  fz.faults.freeze_start_s = 1.0;
  fz.faults.freeze_end_s = 1.3;
  fz.min_t_end_s = 1.4;
  v.push_back(fz);
  Scenario rb{"controller-restart", "100 N m; the controller restarts at 1 s, its E2E counter from 0", 1.5,
              [](double) { return 100.0f; }};
  rb.faults.reboot_s = 1.0;
  rb.min_t_end_s = 1.1;
  v.push_back(rb);
  Scenario fl{"controller-flood", "100 N m; for 100 ms at 1 s the controller sends 20 CtrlCmd per 10 ms period", 1.5,
              [](double) { return 100.0f; }};
  fl.faults.flood_start_s = 1.0;
  fl.faults.flood_end_s = 1.1;
  fl.faults.flood_frames = 20;
  fl.min_t_end_s = 1.2;
  v.push_back(fl);
  return v;
}

std::string select_scenarios(const std::string& list, double t_end_s, std::vector<Scenario>& out,
                             const std::function<bool(const Scenario&, std::string& why)>& accept,
                             std::vector<std::string>* left_out, const std::string& refusal_prefix, bool partial) {
  std::vector<std::string> names;
  for (std::size_t p = 0; p <= list.size();) {
    const std::size_t q = list.find(',', p);
    names.push_back(list.substr(p, q == std::string::npos ? std::string::npos : q - p));
    p = q == std::string::npos ? list.size() + 1 : q + 1;
  }
  const std::vector<Scenario> all = scenarios();
  for (const std::string& n : names) {
    bool found = false;
    for (const Scenario& s : all) found = found || n == "all" || n == s.name;
    if (!found || n.empty()) return "--scenario: expected " + scenario_names() + ", got '" + n + "'";
  }
  for (const Scenario& s : all) {
    bool want = false;
    for (const std::string& n : names) want = want || n == "all" || n == s.name;
    if (!want) continue;
    std::string why;
    if (accept && !accept(s, why)) {
      if (list == "all") {
        if (left_out != nullptr) left_out->push_back(s.name);
        continue;
      }
      return refusal_prefix + why;
    }
    Scenario c = s;
    if (t_end_s > 0 && t_end_s < c.t_end_s) {
      if (t_end_s < c.min_t_end_s && !partial) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "--t-end: %s needs at least %.1f s to judge its criteria, got %g (--allow-partial: its first "
                      "seconds only)",
                      s.name, c.min_t_end_s, t_end_s);
        return buf;
      }
      c.t_end_s = t_end_s;
    }
    out.push_back(c);
  }
  return "";
}

bool partial_criterion(const std::string& name) {
  static const char* const kAnyLength[] = {"trace_written",   "plant_parameters_published", "bridge_answered_every_step",
                                           "lockstep_time_exact", "frames_valid",          "slip_bounded",
                                           "no_gross_slip",   "no_watchdog_fault",          "no_cmd_timeout"};
  for (const char* n : kAnyLength)
    if (name == n) return true;
  return false;
}

std::string scenario_names() {
  std::string n;
  for (const Scenario& s : scenarios()) n += std::string(n.empty() ? "" : ", ") + s.name;
  return n + " or all";
}

}  // namespace cvt::sil::harness
