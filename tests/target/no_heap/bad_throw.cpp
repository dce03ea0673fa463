// Must NOT link (ctest tests.no_heap_rejects_throw): throws (this file alone is
// compiled with -fexceptions, as a library built without our flags would be).
volatile int g_trigger = 0;

int main() {
  if (g_trigger != 0) throw 42;
  return 0;
}
