// Must NOT link (ctest tests.no_heap_rejects_delete_virtual): never calls new or
// delete, but a virtual destructor makes GCC emit a deleting destructor that
// references sized operator delete -- a real trap for firmware interfaces.
struct Base {
  virtual ~Base() = default;
  virtual int value() const { return 1; }
};
struct Derived : Base {
  int value() const override { return 2; }
};

int main() {
  Derived d;
  Base* volatile b = &d;
  return b->value() == 2 ? 0 : 1;
}
