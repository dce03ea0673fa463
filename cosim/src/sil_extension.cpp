// What cosim/ adds to cvtplant-sil (docs/sil.md#plants, #compare): the
// plant `reference` (the multibody reference behind the bridge) and the
// subcommand `compare`. Compiled into the cvtplant-sil program, registered
// at its static initialisation; this file parses the command line and
// prints, the work is the library's (reference_plant, compare).
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cvtplant/cosim/compare.hpp"
#include "cvtplant/cosim/reference_plant.hpp"
#include "cvtplant/port/posix_clock.hpp"
#include "cvtplant/sil/harness/extensions.hpp"

#ifndef CVT_COMPARE_REPORT_SCRIPT
#define CVT_COMPARE_REPORT_SCRIPT ""
#endif

namespace {

namespace h = cvt::sil::harness;
using cvt::cosim::ReferencePlant;

[[noreturn]] void bad_usage(const std::string& msg) {
  std::fprintf(stderr, "cvtplant-sil: %s (see --help)\n", msg.c_str());
  std::exit(2);
}

double number(const std::string& flag, const std::string& v, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double d = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || errno != 0 || !(d >= lo && d <= hi)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: expected %g..%g, got '", flag.c_str(), lo, hi);
    bad_usage(buf + v + "'");
  }
  return d;
}

// One NAME=VALUE of the reference's settings (the flags of
// cvtplant-reference-bridge without their dashes): "" or why not.
std::string apply_option(const std::string& opt, cvt::cosim::ReferenceOptions& ro) {
  const std::size_t eq = opt.find('=');
  const std::string name = opt.substr(0, eq), v = eq == std::string::npos ? "" : opt.substr(eq + 1);
  auto num = [&v](double lo, double hi, double& out) {
    char* end = nullptr;
    errno = 0;
    out = std::strtod(v.c_str(), &end);
    return end != v.c_str() && *end == '\0' && errno == 0 && out >= lo && out <= hi;
  };
  double d = 0;
  if (name == "rtol" && num(1e-12, 1e-2, d)) ro.stepper.rtol = d;
  else if (name == "ledger-tol" && num(1e-15, 1.0, d)) ro.stepper.ledger_tol = d;
  else if (name == "max-steps-per-frame" && num(1, 1e9, d)) ro.stepper.max_steps_per_frame = static_cast<long long>(d);
  else if (name == "rtol" || name == "ledger-tol" || name == "max-steps-per-frame")
    return name + ": a number in its range (see --help), got '" + v + "'";
  else
    return "the reference takes rtol=R, ledger-tol=X, max-steps-per-frame=N, got '" + opt + "'";
  return "";
}

cvt::cosim::ReferenceOptions reference_options(const h::PlantKindOptions& o) {
  cvt::cosim::ReferenceOptions ro;
  for (const std::string& opt : o.options) apply_option(opt, ro);  // checked when parsed
  ro.release_cache_dir = o.out_dir + "/reference-cache";
  std::error_code ec;
  std::filesystem::create_directories(ro.release_cache_dir, ec);
  if (ec) ro.release_cache_dir.clear();  // then this process's memory only
  return ro;
}

[[maybe_unused]] const bool kReferenceRegistered = (h::register_plant_kind(h::PlantKind{
    "reference",
    "the multibody reference (docs/mbd.md) behind the bridge: lock-step; its release states in OUT/reference-cache",
    [](h::InProcessBus& bus, const h::PlantKindOptions& o) -> std::unique_ptr<h::PlantUnderTest> {
      return std::make_unique<h::LoopbackPlant<cvt::sil::BasicBridge<ReferencePlant>>>(bus, o.frame_cost_ns, nullptr,
                                                                                         reference_options(o));
    },
    "cvtplant-reference-bridge",
    // The micro-VM (25x slower than the host) takes up to a second for the
    // ten frames of a Step; the host tens of milliseconds.
    5000,
    [](const h::Scenario& s, const h::PlantKindOptions& o) -> std::string {
      ReferencePlant p(reference_options(o));
      if (!p.load(*cvt::sil::builtin_scene_for(s.scene))) return p.load_refusal();
      p.reset();
      return p.keeps_time() ? "" : p.realtime_refusal();
    },
    [](const std::string& opt) {
      cvt::cosim::ReferenceOptions ro;
      return apply_option(opt, ro);
    },
    "                      --plant-option rtol=R (BDF tolerance, default 5e-7), ledger-tol=X (relative ledger\n"
    "                      residual that faults it, default 1e-6), max-steps-per-frame=N (default 200000)\n"}),
                                              true);

const char kCompareUsage[] =
    "       cvtplant-sil compare [--scenario NAME[,NAME...]|all] [--out DIR] [--t-end S] [--rtol R]\n"
    "                          [--ledger-tol X] [--max-steps-per-frame N] [--no-report]\n"
    "  compare: each scenario in lock-step on the loopback bus against the real-time plant and the\n"
    "  multibody reference, the example controller on each (docs/sil.md#compare): every criterion\n"
    "  on both plants and whether the verdicts agree (stdout), the traces overlaid\n"
    "  (DIR/compare-<scenario>.csv), the tables (DIR/compare-*.csv), each run's trace and JUnit\n"
    "  (DIR/rom/, DIR/reference/) and the HTML report DIR/compare-report.html (not with\n"
    "  --no-report); the reference's tolerance and caps as cvtplant-reference-bridge's.\n"
    "  Exit status: 0 every verdict agrees, 1 a verdict differs or a run failed, 2 bad command line.\n";

// The HTML report's script: installed beside this program, else the source tree's.
std::string report_script() {
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n > 0) {
    self[n] = '\0';
    const std::string beside = std::filesystem::path(self).parent_path() / "cvtplant-sil-compare-report";
    struct stat st {};
    if (stat(beside.c_str(), &st) == 0) return beside;
  }
  return CVT_COMPARE_REPORT_SCRIPT;
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

int compare_main(int argc, char** argv) {
  std::string scenario = "all", out_dir = ".";
  double t_end_s = 0;
  bool report = true;
  cvt::cosim::CompareOptions o;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::fputs(kCompareUsage, stdout);
      return 0;
    }
    if (a == "--no-report") {
      report = false;
      continue;
    }
    static const char* const kValueFlags[] = {"--scenario", "--out", "--t-end", "--rtol", "--ledger-tol",
                                              "--max-steps-per-frame"};
    bool known = false;
    for (const char* k : kValueFlags) known = known || a == k;
    if (!known) bad_usage("compare: unknown option '" + a + "'");
    if (i + 1 >= argc) bad_usage(a + ": missing value");
    const std::string v = argv[++i];
    if (a == "--scenario") scenario = v;
    else if (a == "--out") out_dir = v;
    else if (a == "--t-end") t_end_s = number(a, v, 0.01, 1e5);
    else if (a == "--rtol") o.reference.stepper.rtol = number(a, v, 1e-12, 1e-2);
    else if (a == "--ledger-tol") o.reference.stepper.ledger_tol = number(a, v, 1e-15, 1.0);
    else if (a == "--max-steps-per-frame")
      o.reference.stepper.max_steps_per_frame = static_cast<long long>(number(a, v, 1, 1e9));
  }
  const std::string err = h::select_scenarios(scenario, t_end_s, o.scenarios);
  if (!err.empty()) bad_usage(err);
  o.out_dir = out_dir;
  // Progress on a terminal only; piped, stdout carries the table alone.
  if (isatty(STDERR_FILENO)) {
    auto last = std::make_shared<std::int64_t>(0);
    o.progress = [last](const char* plant, const char* sc, double t, double t_end) {
      cvt::port::PosixMonotonicClock clock;
      const std::int64_t now = clock.now_ns();
      if (now - *last < 200000000 && t < t_end - 1e-9) return;
      *last = now;
      std::fprintf(stderr, "\rcompare: %-18s on the %-9s %6.2f of %5.2f s", sc, plant, t, t_end);
      if (t >= t_end - 1e-9) std::fputc('\n', stderr);
    };
  }
  std::vector<cvt::cosim::ScenarioComparison> result;
  try {
    result = cvt::cosim::compare_scenarios(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cvtplant-sil: compare: %s\n", e.what());
    return 1;
  }
  std::fputs(cvt::cosim::comparison_table(result).c_str(), stdout);
  std::printf("tables and traces in %s (compare-*.csv)\n", out_dir.c_str());
  bool agree = true;
  for (const auto& c : result) agree = agree && c.verdicts_agree;
  if (report) {
    const std::string script = report_script();
    const std::string cmd = shell_quote(script) + " " + shell_quote(out_dir);
    std::fflush(stdout);
    if (script.empty() || std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "cvtplant-sil: compare: the HTML report failed (%s); the CSV files are written\n",
                   cmd.c_str());
      return 1;
    }
  }
  return agree ? 0 : 1;
}

[[maybe_unused]] const bool kCompareRegistered = (h::register_subcommand({"compare", kCompareUsage, compare_main}), true);

}  // namespace
