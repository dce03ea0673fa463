// The one rule for names that become file names (docs/cli.md#names).
#include <doctest/doctest.h>

#include "cvtplant/files/names.hpp"

using cvt::files::name_problem;

TEST_SUITE("names") {
  TEST_CASE("the built-in and example scene names pass") {
    for (const char* n : {"seed-case1", "oscillator-coulomb", "tip-in-tension", "seed-case2-clamp-ramp", "x",
                          "run_2.b", "A1"})
      CHECK_MESSAGE(name_problem(n) == "", n);
    CHECK(name_problem(std::string(64, 'a')) == "");
  }

  TEST_CASE("names that would escape a directory, hide, break a line or be empty are refused") {
    CHECK(name_problem("").find("empty name") == 0);
    CHECK(name_problem("../escaped").find("starts with") == 0);
    CHECK(name_problem("a/../../b").find("holds '/'") == 0);
    CHECK(name_problem(".hidden").find("starts with") == 0);
    CHECK(name_problem("-rf").find("starts with") == 0);
    CHECK(name_problem("two\nlines").find("holds a control character") == 0);
    CHECK(name_problem("with space").find("holds a space") == 0);
    CHECK(name_problem("caf\xc3\xa9").find("holds a non-ASCII byte") == 0);
    CHECK(name_problem("a|b").find("holds '|'") == 0);
    CHECK(name_problem(std::string(65, 'a')).find("longer than 64") == 0);
    // Every refusal states the rule.
    CHECK(name_problem("a b").find("letters, digits") != std::string::npos);
  }
}
