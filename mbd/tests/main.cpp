// Test runner of the multibody reference (docs/mbd.md#checks).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
