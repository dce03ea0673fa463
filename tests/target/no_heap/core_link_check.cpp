// Links the whole core archive (WHOLE_ARCHIVE) into an image that carries the
// no-heap check (port/cortex-m/ld/no_heap.ld): if anything in lib/ refers to
// the heap or the exception runtime, this target fails to link.
int main() { return 0; }
