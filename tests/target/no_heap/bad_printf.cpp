// Must NOT link (ctest tests.no_heap_rejects_printf): newlib's printf allocates
// its stdio buffers with malloc, which is why the port has its own console.
#include <cstdio>

int main() {
  std::printf("%d\n", 42);
  return 0;
}
