// Test runner for the nonlinear-dynamics toolkit (tools/analysis).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
