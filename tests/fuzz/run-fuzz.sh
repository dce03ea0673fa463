#!/bin/sh
# Build and run one libFuzzer target (docs/can.md#fuzzing, docs/cli.md#fuzzing).
#   tests/fuzz/run-fuzz.sh [TARGET] [libFuzzer args...]
# TARGET: can_decoder (the default), scene_file or cli_numbers. The targets
# are built by CMake in the `fuzz` preset's tree, build/fuzz (clang 14,
# tests/fuzz/CMakeLists.txt). Without libFuzzer args: a 20 s smoke run (the
# CAN decoder's CI convention); a full run, e.g.
#   tests/fuzz/run-fuzz.sh scene_file -runs=1000000
# Corpora (kept in git, only read): tests/fuzz/corpus (CAN), corpus-scene,
# corpus-numbers; new inputs go to build/fuzz/<target>-corpus-new. Fold
# them in after a long run with
#   build/fuzz/tests/fuzz/fuzz_<target> -merge=1 tests/fuzz/<corpus> build/fuzz/<target>-corpus-new
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$root/build/fuzz
target=can_decoder
case "${1:-}" in
  can_decoder | scene_file | cli_numbers) target=$1; shift ;;
  -* | "") ;;
  *) echo "run-fuzz.sh: unknown target '$1' (can_decoder, scene_file, cli_numbers)" >&2; exit 2 ;;
esac
case $target in
  can_decoder) corpus=$here/corpus max_len=600 ;;
  scene_file) corpus=$here/corpus-scene max_len=4096 ;;
  cli_numbers) corpus=$here/corpus-numbers max_len=512 ;;
esac
cd "$root"
[ -f "$out/CMakeCache.txt" ] || cmake --preset fuzz >&2
cmake --build --preset fuzz --target "fuzz_$target" >&2
if [ $# -eq 0 ]; then set -- -max_total_time=20; fi
mkdir -p "$out/$target-corpus-new"
exec "$out/tests/fuzz/fuzz_$target" -max_len=$max_len -print_final_stats=1 "$@" "$out/$target-corpus-new" "$corpus"
