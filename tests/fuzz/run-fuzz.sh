#!/bin/sh
# Build and run one libFuzzer target (docs/can.md#fuzzing, docs/cli.md#fuzzing).
#   tests/fuzz/run-fuzz.sh [TARGET] [libFuzzer args...]
# TARGET: can_decoder (the default), scene_file, cli_numbers or cache_entry. Without
# libFuzzer args: a 20 s smoke run (the CAN decoder's CI convention); a full
# run, e.g.
#   tests/fuzz/run-fuzz.sh scene_file -runs=1000000
# Corpora (kept in git, only read): tests/fuzz/corpus (CAN), corpus-scene,
# corpus-numbers, corpus-cache; new inputs go to $CVT_FUZZ_BUILD/<target>-corpus-new. Fold
# them in after a long run with
#   build-fuzz/fuzz_<target> -merge=1 tests/fuzz/<corpus> build-fuzz/<target>-corpus-new
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${CVT_FUZZ_BUILD:-$root/build-fuzz}
CXX=${CXX_FUZZ:-clang++-14}
target=can_decoder
case "${1:-}" in
  can_decoder | scene_file | cli_numbers | cache_entry) target=$1; shift ;;
  -* | "") ;;
  *) echo "run-fuzz.sh: unknown target '$1' (can_decoder, scene_file, cli_numbers, cache_entry)" >&2; exit 2 ;;
esac
mkdir -p "$out"
flags="-std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -ffp-contract=off"
cli="$root/tools/cvtplant"
files="-I$root/files/include $root/files/src/names.cpp $root/files/src/paths.cpp $root/files/src/replace.cpp"
case $target in
  can_decoder)
    corpus=$here/corpus max_len=600
    # shellcheck disable=SC2086
    "$CXX" $flags -I"$root/lib/include" -I"$root/hil/codegen/include" "$here/fuzz_can_decoder.cpp" \
      -o "$out/fuzz_can_decoder" ;;
  scene_file)
    # toml++ compiled into the target (header-only), so the parser is
    # instrumented too. Its internal asserts are off, as in Debian's library
    # that cvtplant links: toml++ 3.3.0 asserts "bare key character" in
    # parse_key before it reports a control character in a table header as
    # the syntax error it is (corpus-scene/control-char-key.toml).
    corpus=$here/corpus-scene max_len=4096
    # shellcheck disable=SC2086
    "$CXX" $flags -DTOML_HEADER_ONLY=1 '-DTOML_ASSERT(expr)=static_assert(true)' -I"$root/lib/include" -I/usr/include/eigen3 -I"$cli" \
      "$here/fuzz_scene_file.cpp" "$cli/scene_file.cpp" "$cli/io_util.cpp" "$cli/options.cpp" $files \
      -o "$out/fuzz_scene_file" ;;
  cli_numbers)
    corpus=$here/corpus-numbers max_len=512
    # shellcheck disable=SC2086
    "$CXX" $flags -I"$cli" "$here/fuzz_cli_numbers.cpp" "$cli/io_util.cpp" "$cli/options.cpp" $files \
      -o "$out/fuzz_cli_numbers" ;;
  cache_entry)
    # The entry's format and checks alone (validation/src/cache_entry.cpp):
    # no reference run, no SUNDIALS.
    corpus=$here/corpus-cache max_len=8192
    # shellcheck disable=SC2086
    "$CXX" $flags -I"$root/validation/include" -I"$root/mbd/include" -I"$root/lib/include" -I/usr/include/eigen3 \
      "$here/fuzz_cache_entry.cpp" "$root/validation/src/cache_entry.cpp" -o "$out/fuzz_cache_entry" ;;
esac
if [ $# -eq 0 ]; then set -- -max_total_time=20; fi
mkdir -p "$out/$target-corpus-new"
exec "$out/fuzz_$target" -max_len=$max_len -print_final_stats=1 "$@" "$out/$target-corpus-new" "$corpus"
