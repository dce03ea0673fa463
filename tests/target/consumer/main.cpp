// Uses the installed headers and archive the way firmware would.
#include "cvtplant/scalar/scalar.hpp"

#if defined(CONSUMER_ON_TARGET)
#include "cvtplant/port/console.hpp"
#define SAY(text) (cvt::port::console() << (text) << '\n')
#else
#include <cstdio>
#define SAY(text) std::puts(text)
#endif

#include <cstring>

int main() {
  // A header-only piece of the core, checked so the program has a real result.
  const bool ok = std::strcmp(cvt::scalar_name<float>::value, "float") == 0;
  SAY(ok ? "consumer OK" : "consumer FAILED");
  return ok ? 0 : 1;
}
