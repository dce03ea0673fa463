// Must NOT link (ctest tests.no_heap_rejects_malloc): calls malloc.
#include <cstdlib>

int main() {
  void* volatile p = std::malloc(16);
  return p != nullptr ? 0 : 1;
}
