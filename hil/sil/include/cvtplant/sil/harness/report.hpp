// What a SIL run writes (docs/sil.md#scenarios): one CSV trace per scenario
// run, one JUnit XML file for all of them, and the console lines. Host only.
#pragma once

#include <string>
#include <vector>

#include "cvtplant/sil/harness/criteria.hpp"

namespace cvt::sil::harness {

// The trace as CSV, one row per sample; false (with a line on stderr) when
// the file cannot be written.
bool write_trace(const std::string& csv, const std::vector<Sample>& trace);

// One <testsuite> per scenario run, one <testcase> per check: the measured
// values in <system-out>, <failure> on a miss, <skipped> when not judged.
bool write_junit(const std::string& path, const std::vector<ScenarioResult>& results);

// PASS/FAIL line of a scenario run and one line per check, on stdout.
void print_result(const ScenarioResult& r, const char* what);

}  // namespace cvt::sil::harness
