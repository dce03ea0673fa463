// libFuzzer target for the reference cache's entry checks
// (docs/validation.md#cache, docs/cli.md#fuzzing): parse_cache_entry on any
// bytes as the key file's entry lines and the CSV. The input is a flag byte,
// the key file's lines after the key up to the first NUL, then the CSV; with
// the flag's bit 0 set the harness writes the CSV's true checksum into the
// key file, so the fuzzer reaches the row and cell checks behind it.
// Properties checked on every input, beyond "no crash, no sanitizer report":
//  - it never throws;
//  - a refusal is one line that names the key or the CSV file;
//  - an accepted entry has at least two rows, at most the run's samples and
//    all of them when it records no failure, every column as long as the
//    times, the times on the run's grid, every value finite and within
//    1e12 but the two slip columns and the geometric ratio, which may be nan.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cvtplant/validation/cache.hpp"

namespace {

[[noreturn]] void violated() { __builtin_trap(); }

const std::string kKey = "cvtplant multibody reference (fuzz), cache format 6\nrun.t_end_s 0.005\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* in, size_t n) {
  if (n < 1) return -1;
  const bool fix_sum = (in[0] & 1) != 0;
  const std::string rest(reinterpret_cast<const char*>(in + 1), n - 1);
  const std::size_t nul = rest.find('\0');
  std::string trailer = nul == std::string::npos ? rest : rest.substr(0, nul);
  const std::string csv = nul == std::string::npos ? std::string() : rest.substr(nul + 1);
  if (fix_sum) {
    const std::size_t at = trailer.find("entry csv_fnv1a64 ");
    if (at != std::string::npos && trailer.size() >= at + 18 + 16)
      trailer.replace(at + 18, 16, cvt::validation::key_hash(csv));
  }
  cvt::mbd::RunOptions r;
  r.t_end_s = 0.005;
  r.sample_s = 1e-3;
  cvt::validation::ReferenceRun out;
  std::string problem;
  try {
    problem = cvt::validation::parse_cache_entry(kKey + trailer, csv, kKey, r, "E", out);
  } catch (...) {
    violated();
  }
  if (!problem.empty()) {
    if (problem.find('\n') != std::string::npos) violated();
    if (problem.rfind("E.key: ", 0) != 0 && problem.rfind("E.csv: ", 0) != 0) violated();
    return 0;
  }
  const auto& s = out.series;
  const std::size_t rows = s.size();
  if (rows < 2 || rows > 6) violated();
  if (out.failure.empty() && rows != 6) violated();
  for (const auto col : cvt::validation::kSeriesColumns)
    if ((s.*col).size() != rows) violated();
  if (out.sheave1_m.size() != rows || out.sheave2_m.size() != rows) violated();
  for (std::size_t i = 0; i < rows; ++i) {
    if (std::fabs(s.t_s[i] - 1e-3 * static_cast<double>(i)) > 1e-12) violated();
    const double finite[] = {s.t_s[i],      s.omega1_rad_s[i], s.omega2_rad_s[i], s.F_ax1_N[i], s.torque_driver_Nm[i],
                             s.F_ax2_N[i],  s.clamp1_N[i],     s.clamp2_N[i],     s.tau_in_Nm[i], s.tau_load_Nm[i],
                             out.sheave1_m[i], out.sheave2_m[i]};
    for (const double v : finite)
      if (!(std::fabs(v) <= 1e12)) violated();
    for (const double v : {s.slip1_m_s[i], s.wrap_slip_m_s[i], s.ratio_geom[i]})
      if (!std::isnan(v) && !(std::fabs(v) <= 1e12)) violated();
  }
  return 0;
}
