// libFuzzer target for the command line's numeric parsing (docs/cli.md#fuzzing):
// the validated options of tools/cvtplant/options.hpp through CLI11, the
// strict token checks and the comma-separated lists of io_util.hpp.
// Input: tokens separated by NUL bytes, parsed as the arguments of a
// subcommand with real and integer options of several ranges. Properties:
//  - parsing either succeeds or throws a CLI11 ParseError / UsageError;
//  - every value that was accepted is finite and inside its option's range,
//    and is the value strtod/strtoll give for the token;
//  - check_real/check_int agree with an independent reading of the token.
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "commands.hpp"
#include "io_util.hpp"
#include "options.hpp"

namespace {

[[noreturn]] void violated() { __builtin_trap(); }

struct RealOpt {
  const char* name;
  cvtcli::Range range;
};
constexpr RealOpt kReals[] = {{"--t-end", {0, 1e5, true}},
                              {"--dt", {1e-7, 1}},
                              {"--rr", {0, 1, true, true}},
                              {"--t-transient", {0, 1e9}}};
struct IntOpt {
  const char* name;
  long long lo, hi;
};
constexpr IntOpt kInts[] = {{"--substeps", 1, 10000}, {"--n-c", 1, 10000}, {"--discard", 0, 1000000000000LL}};

// An independent reading: the whole token is a finite double.
bool reads_as_real(const std::string& t, double& v) {
  if (t.empty() || t.size() > 64) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(t.c_str(), &end);
  return *end == '\0' && end != t.c_str() && std::isfinite(v) && errno != ERANGE;
}

void check_tokens(const std::vector<std::string>& tokens) {
  for (const std::string& t : tokens) {
    for (const RealOpt& o : kReals) {
      double got = 0, ref = 0;
      const bool ok = cvtcli::check_real(t, o.range, &got).empty();
      const bool want = reads_as_real(t, ref) && o.range.contains(ref);
      if (ok != want) violated();
      if (ok && got != ref) violated();
    }
    for (const IntOpt& o : kInts) {
      long long got = 0;
      if (cvtcli::check_int(t, o.lo, o.hi, &got).empty()) {
        if (got < o.lo || got > o.hi) violated();
        double ref = 0;
        if (!reads_as_real(t, ref) || ref != static_cast<double>(got)) violated();
      }
    }
    try {
      const std::vector<double> v = cvtcli::parse_list(t, 0, "--x0");
      for (double x : v)
        if (!std::isfinite(x)) violated();
    } catch (const cvtcli::UsageError& e) {
      if (e.message.size() > 400) violated();
    }
  }
}

// One parser for the whole run (building a CLI11 app costs more than a
// parse); clear() forgets the previous input's results.
struct Parser {
  CLI::App app{"fuzz"};
  double reals[4] = {-1, -1, -1, -1};
  int substeps = -1, n_c = -1;
  long discard = -1;
  Parser() {
    for (int i = 0; i < 4; ++i) cvtcli::add_real(&app, kReals[i].name, reals[i], kReals[i].range, "");
    cvtcli::add_int(&app, kInts[0].name, substeps, kInts[0].lo, kInts[0].hi, "");
    cvtcli::add_int(&app, kInts[1].name, n_c, kInts[1].lo, kInts[1].hi, "");
    cvtcli::add_int(&app, kInts[2].name, discard, kInts[2].lo, kInts[2].hi, "");
  }
};

void check_parse(const std::vector<std::string>& tokens) {
  static Parser p;
  p.app.clear();
  std::vector<std::string> args(tokens.rbegin(), tokens.rend());  // CLI11 takes them reversed
  try {
    p.app.parse(args);
  } catch (const CLI::ParseError&) {
    return;
  }
  for (int i = 0; i < 4; ++i)
    if (p.app.count(kReals[i].name) > 0 && !kReals[i].range.contains(p.reals[i])) violated();
  if (p.app.count("--substeps") > 0 && (p.substeps < 1 || p.substeps > 10000)) violated();
  if (p.app.count("--n-c") > 0 && (p.n_c < 1 || p.n_c > 10000)) violated();
  if (p.app.count("--discard") > 0 && p.discard < 0) violated();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* in, size_t n) {
  if (n > 4096) return -1;
  std::vector<std::string> tokens(1);
  for (size_t i = 0; i < n; ++i) {
    if (in[i] == 0) {
      tokens.emplace_back();
    } else {
      tokens.back().push_back(static_cast<char>(in[i]));
    }
  }
  if (tokens.size() > 64) return -1;
  check_tokens(tokens);
  check_parse(tokens);
  return 0;
}
