#include "cvtplant/sil/harness/report.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace cvt::sil::harness {

bool write_trace(const std::string& csv, const std::vector<Sample>& trace) {
  std::FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "cvtplant-sil: %s: %s\n", csv.c_str(), std::strerror(errno));
    return false;
  }
  std::fprintf(f, "t_s,demand_Nm,clamp_cmd_N,axial_force_N,torque_transmitted_Nm,slip,omega1_rad_s,omega2_rad_s,"
                  "safety_factor,fault_cmd_timeout,fault_watchdog,ratio_target,geometric_ratio,driven_clamp_cmd_N,"
                  "driven_axial_force_N,radius_driver_m,end_stop_underdrive,end_stop_overdrive\n");
  for (const Sample& s : trace)
    std::fprintf(f, "%.3f,%.2f,%.0f,%.0f,%.2f,%.4f,%.2f,%.2f,%.3f,%d,%d,%.4f,%.4f,%.0f,%.0f,%.5f,%d,%d\n", s.t_s,
                 s.demand_Nm, s.clamp_cmd_N, s.axial_N, s.torque_Nm, s.slip, s.omega1, s.omega2, s.safety,
                 s.cmd_timeout, s.watchdog, s.ratio_target, s.geometric_ratio, s.driven_cmd_N, s.driven_axial_N,
                 s.radius1_m, s.stop_under, s.stop_over);
  std::fclose(f);
  return true;
}

namespace {

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '<') o += "&lt;";
    else if (ch == '>') o += "&gt;";
    else if (ch == '&') o += "&amp;";
    else if (ch == '"') o += "&quot;";
    else o += ch;
  }
  return o;
}

}  // namespace

bool write_junit(const std::string& path, const std::vector<ScenarioResult>& results) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  int tests = 0, failures = 0, skipped = 0;
  double wall = 0;
  for (const auto& r : results) {
    wall += r.wall_s;
    for (const auto& c : r.checks) {
      ++tests;
      failures += c.judged && !c.pass ? 1 : 0;
      skipped += c.judged ? 0 : 1;
    }
  }
  std::fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  std::fprintf(f, "<testsuites name=\"cvtplant-sil\" tests=\"%d\" failures=\"%d\" skipped=\"%d\" time=\"%.3f\">\n",
               tests, failures, skipped, wall);
  for (const auto& r : results) {
    int fails = 0, skips = 0;
    for (const auto& c : r.checks) {
      fails += c.judged && !c.pass ? 1 : 0;
      skips += c.judged ? 0 : 1;
    }
    std::fprintf(f, "  <testsuite name=\"sil.%s\" tests=\"%zu\" failures=\"%d\" skipped=\"%d\" time=\"%.3f\">\n",
                 r.name.c_str(), r.checks.size(), fails, skips, r.wall_s);
    std::fprintf(f, "    <properties><property name=\"description\" value=\"%s\"/></properties>\n",
                 xml_escape(r.what).c_str());
    for (const auto& c : r.checks) {
      std::fprintf(f, "    <testcase classname=\"sil.%s\" name=\"%s\" time=\"0\">\n", r.name.c_str(), c.name.c_str());
      if (!c.judged) std::fprintf(f, "      <skipped message=\"%s\"/>\n", xml_escape(c.detail).c_str());
      else if (!c.pass) std::fprintf(f, "      <failure message=\"%s\"/>\n", xml_escape(c.detail).c_str());
      std::fprintf(f, "      <system-out>%s</system-out>\n    </testcase>\n", xml_escape(c.detail).c_str());
    }
    std::fprintf(f, "  </testsuite>\n");
  }
  std::fprintf(f, "</testsuites>\n");
  const bool ok = std::ferror(f) == 0;
  return std::fclose(f) == 0 && ok;
}

void print_result(const ScenarioResult& r, const char* what) {
  std::printf("%s %s (%.1f s wall): %s\n", r.pass() ? "PASS" : "FAIL", r.name.c_str(), r.wall_s, what);
  for (const Check& c : r.checks)
    std::printf("  %s %s: %s\n", !c.judged ? "skip" : c.pass ? "ok  " : "FAIL", c.name.c_str(), c.detail.c_str());
  std::fflush(stdout);
}

}  // namespace cvt::sil::harness
