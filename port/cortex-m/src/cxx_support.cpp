// The few C/C++ runtime hooks a heap-free, exception-free image still needs.
// Defining them here keeps libsupc++/libc from supplying versions that drag
// in the heap or the unwinder (docs/build.md#no-heap).
#include <cstdint>

#include "cvtplant/port/console.hpp"
#include "cvtplant/port/startup.hpp"

extern "C" {

// Static objects with destructors register them here. A firmware image never
// tears its statics down, so registration is a no-op; libsupc++'s version
// would go through newlib's __register_exitproc.
int __aeabi_atexit(void*, void (*)(void*), void*) { return 0; }
int __cxa_atexit(void (*)(void*), void*, void*) { return 0; }
void* __dso_handle = nullptr;

// Called through a vtable slot of an abstract class: a programming error.
// libsupc++'s version calls std::terminate, which pulls in the unwinder.
void __cxa_pure_virtual() {
  cvt::port::console() << "FATAL: pure virtual call\n";
  cvt::port::exit_image(cvt::port::kExitAbort);
}

// assert() failures (builds without NDEBUG) and Eigen's eigen_assert.
// newlib's version formats with fiprintf, which needs malloc.
void __assert_func(const char* file, int line, const char* func, const char* expr) {
  cvt::port::console() << "ASSERT FAILED: " << (expr ? expr : "?") << " at " << (file ? file : "?")
                       << ':' << static_cast<std::int32_t>(line) << " in " << (func ? func : "?")
                       << '\n';
  cvt::port::exit_image(cvt::port::kExitAbort);
}

void abort() {
  cvt::port::console() << "FATAL: abort()\n";
  cvt::port::exit_image(cvt::port::kExitAbort);
}

}  // extern "C"
