#!/bin/sh
# Build and run the CAN decoder fuzzer (docs/can.md#fuzzing).
#   tests/fuzz/run-fuzz.sh [libFuzzer args...]
# Defaults to a 20 s smoke run (the CI convention); a full run, e.g.
#   tests/fuzz/run-fuzz.sh -runs=1000000
# Corpus: tests/fuzz/corpus is kept in git and only read; new inputs go to
# $CVT_FUZZ_BUILD/corpus-new. Fold them in after a long run with
#   build-fuzz/fuzz_can_decoder -merge=1 tests/fuzz/corpus build-fuzz/corpus-new
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${CVT_FUZZ_BUILD:-$root/build-fuzz}
CXX=${CXX_FUZZ:-clang++-14}
mkdir -p "$out"
"$CXX" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -ffp-contract=off -I"$root/lib/include" -I"$root/hil/codegen/include" "$here/fuzz_can_decoder.cpp" -o "$out/fuzz_can_decoder"
if [ $# -eq 0 ]; then set -- -max_total_time=20; fi
mkdir -p "$out/corpus-new"
exec "$out/fuzz_can_decoder" -max_len=600 -print_final_stats=1 "$@" "$out/corpus-new" "$here/corpus"
