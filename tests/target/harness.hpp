#pragma once
// Heap-free mini test harness for the target test image (no doctest on the
// target: it needs the heap, exceptions and stdio).
// docs/build.md#target-tests
//
// Add tests by dropping a test_<topic>.cpp file into tests/target/ (the CMake
// glob picks it up) containing
//     CVT_TARGET_TEST(fixed_saturates) { CHECK_EQ(a, b); ... }
// Each test registers itself from a static constructor into an intrusive
// list kept sorted by name, so the run order is independent of link order.
// Failed checks print file:line, the expression and the values, and count;
// main() returns the number of failed checks (capped) as the exit status.
#include <cstdint>
#include <cstring>

#include "cvtplant/port/console.hpp"

namespace cvt::target {

using TestFn = void (*)();

struct TestCase {
  TestCase(const char* name, const char* file, int line, TestFn fn);
  const char* name;
  const char* file;
  int line;
  TestFn fn;
  TestCase* next = nullptr;
};

// Bookkeeping for the running test; defined in main.cpp.
void note_check();
cvt::port::Console& begin_failure(const char* file, int line, const char* what);
void end_failure();

// Value printers used by the CHECK_* macros. Floats print with 9 decimals and
// their exact bit pattern, so a mismatch can be replayed on the host.
inline void print_value(cvt::port::Console& c, bool v) { c << (v ? "true" : "false"); }
inline void print_value(cvt::port::Console& c, char v) { c << static_cast<int>(v); }
inline void print_value(cvt::port::Console& c, signed char v) { c << static_cast<int>(v); }
inline void print_value(cvt::port::Console& c, unsigned char v) { c << static_cast<unsigned>(v); }
inline void print_value(cvt::port::Console& c, short v) { c << static_cast<int>(v); }
inline void print_value(cvt::port::Console& c, unsigned short v) { c << static_cast<unsigned>(v); }
inline void print_value(cvt::port::Console& c, int v) { c << v; }
inline void print_value(cvt::port::Console& c, unsigned v) { c << v; }
inline void print_value(cvt::port::Console& c, long v) { c << v; }
inline void print_value(cvt::port::Console& c, unsigned long v) { c << v; }
inline void print_value(cvt::port::Console& c, long long v) { c << v; }
inline void print_value(cvt::port::Console& c, unsigned long long v) { c << v; }
inline void print_value(cvt::port::Console& c, float v) {
  c.fixed(v, 9) << " (";
  c.bits(v) << ')';
}
inline void print_value(cvt::port::Console& c, double v) {
  c.fixed(v, 9) << " (";
  c.bits(v) << ')';
}
inline void print_value(cvt::port::Console& c, const char* v) { c << '"' << v << '"'; }
// Anything else (e.g. Fixed<F>): convert explicitly at the call site.

template <class A, class B>
void report_binary(const char* file, int line, const char* expr, const A& a, const B& b) {
  auto& c = begin_failure(file, line, expr);
  c << "\n    lhs = ";
  print_value(c, a);
  c << "\n    rhs = ";
  print_value(c, b);
  end_failure();
}

inline bool str_equal(const char* a, const char* b) { return std::strcmp(a, b) == 0; }

inline double abs_diff(double a, double b) { return a > b ? a - b : b - a; }

}  // namespace cvt::target

#define CVT_TARGET_CAT2(a, b) a##b
#define CVT_TARGET_CAT(a, b) CVT_TARGET_CAT2(a, b)

// Defines and registers a test. `name` must be a unique identifier.
#define CVT_TARGET_TEST(name)                                                              \
  static void CVT_TARGET_CAT(cvt_target_test_, name)();                                     \
  static ::cvt::target::TestCase CVT_TARGET_CAT(cvt_target_case_, name)(                    \
      #name, __FILE__, __LINE__, &CVT_TARGET_CAT(cvt_target_test_, name));                  \
  static void CVT_TARGET_CAT(cvt_target_test_, name)()

#define CHECK(cond)                                                                         \
  do {                                                                                      \
    ::cvt::target::note_check();                                                            \
    if (!(cond)) {                                                                          \
      ::cvt::target::begin_failure(__FILE__, __LINE__, "CHECK(" #cond ")");                 \
      ::cvt::target::end_failure();                                                         \
    }                                                                                       \
  } while (0)

#define CVT_TARGET_CHECK_OP(a, op, b, text)                                                 \
  do {                                                                                      \
    ::cvt::target::note_check();                                                            \
    const auto& cvt_lhs_ = (a);                                                             \
    const auto& cvt_rhs_ = (b);                                                             \
    if (!(cvt_lhs_ op cvt_rhs_)) ::cvt::target::report_binary(__FILE__, __LINE__, text,     \
                                                              cvt_lhs_, cvt_rhs_);          \
  } while (0)

#define CHECK_EQ(a, b) CVT_TARGET_CHECK_OP(a, ==, b, "CHECK_EQ(" #a ", " #b ")")
#define CHECK_NE(a, b) CVT_TARGET_CHECK_OP(a, !=, b, "CHECK_NE(" #a ", " #b ")")
#define CHECK_LT(a, b) CVT_TARGET_CHECK_OP(a, <, b, "CHECK_LT(" #a ", " #b ")")
#define CHECK_LE(a, b) CVT_TARGET_CHECK_OP(a, <=, b, "CHECK_LE(" #a ", " #b ")")
#define CHECK_GT(a, b) CVT_TARGET_CHECK_OP(a, >, b, "CHECK_GT(" #a ", " #b ")")
#define CHECK_GE(a, b) CVT_TARGET_CHECK_OP(a, >=, b, "CHECK_GE(" #a ", " #b ")")

// |a - b| <= tol, evaluated in double. NaN never passes.
#define CHECK_NEAR(a, b, tol)                                                               \
  do {                                                                                      \
    ::cvt::target::note_check();                                                            \
    const double cvt_a_ = static_cast<double>(a);                                           \
    const double cvt_b_ = static_cast<double>(b);                                           \
    if (!(::cvt::target::abs_diff(cvt_a_, cvt_b_) <= static_cast<double>(tol)))             \
      ::cvt::target::report_binary(__FILE__, __LINE__,                                      \
                                   "CHECK_NEAR(" #a ", " #b ", " #tol ")", cvt_a_, cvt_b_); \
  } while (0)

// C-string equality.
#define CHECK_STR_EQ(a, b)                                                                  \
  do {                                                                                      \
    ::cvt::target::note_check();                                                            \
    const char* cvt_a_ = (a);                                                               \
    const char* cvt_b_ = (b);                                                               \
    if (!::cvt::target::str_equal(cvt_a_, cvt_b_))                                          \
      ::cvt::target::report_binary(__FILE__, __LINE__, "CHECK_STR_EQ(" #a ", " #b ")",      \
                                   cvt_a_, cvt_b_);                                         \
  } while (0)
