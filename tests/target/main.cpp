// Target test runner: runs every registered CVT_TARGET_TEST in name order and
// returns the number of failed checks (capped at kExitMaxFailures) as the
// image's exit status, which QEMU passes on as its own (docs/build.md#qemu).
#include "cvtplant/port/console.hpp"
#include "cvtplant/port/startup.hpp"
#include "harness.hpp"

namespace cvt::target {
namespace {

TestCase* g_head = nullptr;
std::uint32_t g_checks = 0;
std::uint32_t g_failures = 0;
std::uint32_t g_test_failures = 0;

}  // namespace

TestCase::TestCase(const char* name_, const char* file_, int line_, TestFn fn_)
    : name(name_), file(file_), line(line_), fn(fn_) {
  TestCase** slot = &g_head;
  while (*slot != nullptr && std::strcmp((*slot)->name, name) < 0) slot = &(*slot)->next;
  next = *slot;
  *slot = this;
}

void note_check() { ++g_checks; }

cvt::port::Console& begin_failure(const char* file, int line, const char* what) {
  ++g_failures;
  ++g_test_failures;
  auto& c = cvt::port::console();
  c << file << ':' << static_cast<std::int32_t>(line) << ": FAILED " << what;
  return c;
}

void end_failure() { cvt::port::console() << '\n'; }

}  // namespace cvt::target

int main() {
  using namespace cvt::target;
  auto& out = cvt::port::console();
  out << "cvtplant target tests\n";
  std::uint32_t tests = 0;
  std::uint32_t failed_tests = 0;
  for (TestCase* t = g_head; t != nullptr; t = t->next) {
    g_test_failures = 0;
    t->fn();
    ++tests;
    if (g_test_failures != 0) ++failed_tests;
    out << (g_test_failures == 0 ? "[ ok ] " : "[FAIL] ") << t->name << '\n';
  }
  out << "SUMMARY tests=" << tests << " failed_tests=" << failed_tests << " checks=" << g_checks
      << " failed_checks=" << g_failures << '\n';
  out << (g_failures == 0 ? "RESULT PASS\n" : "RESULT FAIL\n");
  return g_failures > static_cast<std::uint32_t>(cvt::port::kExitMaxFailures)
             ? cvt::port::kExitMaxFailures
             : static_cast<int>(g_failures);
}
