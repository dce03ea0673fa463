// Must NOT link (ctest tests.no_heap_rejects_new): uses operator new.
int main() {
  int* volatile p = new int(3);
  return *p == 3 ? 0 : 1;
}
