#!/bin/sh
# Compile the CAN codec (or another firmware translation unit built on it, such
# as the example controller, hil/tests/sil/m4_controller_smoke.cpp) for Cortex-M4F
# with the firmware flags and refuse any reference to the heap, exceptions or
# RTTI in the object. The compiler and its flags are the toolchain file's
# (a Release build of the cortex-m4f preset); the language level, warnings
# and include folders are the project's, with warnings as errors.
# usage: check_m4_codec.sh <toolchain file> <source root> <out dir> [<source file>]
set -eu
TOOLCHAIN=$1; SRC=$2; OUT=$3
UNIT=${4:-$SRC/hil/tests/can/m4_codec_smoke.cpp}
OBJ=$OUT/$(basename "$UNIT" .cpp).o
mkdir -p "$OUT"
cmake -DTOOLCHAIN="$TOOLCHAIN" -DOUT="$OUT/toolchain.txt" -P "$(dirname "$0")/toolchain_flags.cmake"
{ read -r CXX; read -r FLAGS; } < "$OUT/toolchain.txt"
NM=$(dirname "$CXX")/arm-none-eabi-nm
echo "$CXX $FLAGS"
# shellcheck disable=SC2086
"$CXX" $FLAGS -std=c++17 -Wall -Wextra -Werror \
  -I"$SRC/lib/include" -I"$SRC/hil/codegen/include" -I"$SRC/port/include" -I"$SRC/hil/controller/include" \
  -c "$UNIT" -o "$OBJ"
undef=$("$NM" -u "$OBJ" | awk '{print $2}')
echo "undefined symbols: ${undef:-<none>}"
bad=$(printf '%s\n' "$undef" | grep -E 'malloc|calloc|realloc|free|_Znw|_Zna|_Zdl|_Zda|__cxa_|_Unwind|typeinfo|_ZTI' || true)
if [ -n "$bad" ]; then
  echo "FAIL: heap/exception/RTTI references: $bad"
  exit 1
fi
size=$(dirname "$CXX")/arm-none-eabi-size
"$size" "$OBJ"
echo "OK: $(basename "$UNIT") builds for Cortex-M4F without heap, exceptions or RTTI"
