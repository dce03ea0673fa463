#!/bin/sh
# Compile the CAN codec (or another firmware translation unit built on it, such
# as the example controller, hil/tests/sil/m4_controller_smoke.cpp) for Cortex-M4F
# with the firmware flags and refuse any reference to the heap, exceptions or
# RTTI in the object.
# usage: check_m4_codec.sh <arm-none-eabi-g++> <source root> <out dir> [<source file>]
set -eu
CXX=$1; SRC=$2; OUT=$3
UNIT=${4:-$SRC/hil/tests/can/m4_codec_smoke.cpp}
OBJ=$OUT/$(basename "$UNIT" .cpp).o
NM=$(dirname "$(command -v "$CXX")")/arm-none-eabi-nm
mkdir -p "$OUT"
"$CXX" -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard \
  -fno-exceptions -fno-rtti -std=c++17 -O2 -Wall -Wextra -Werror \
  -ffp-contract=off -fno-fast-math \
  -I"$SRC/lib/include" -I"$SRC/hil/codegen/include" -I"$SRC/port/include" -I"$SRC/hil/controller/include" \
  -c "$UNIT" -o "$OBJ"
undef=$("$NM" -u "$OBJ" | awk '{print $2}')
echo "undefined symbols: ${undef:-<none>}"
bad=$(printf '%s\n' "$undef" | grep -E 'malloc|calloc|realloc|free|_Znw|_Zna|_Zdl|_Zda|__cxa_|_Unwind|typeinfo|_ZTI' || true)
if [ -n "$bad" ]; then
  echo "FAIL: heap/exception/RTTI references: $bad"
  exit 1
fi
size=$(dirname "$(command -v "$CXX")")/arm-none-eabi-size
"$size" "$OBJ"
echo "OK: $(basename "$UNIT") builds for Cortex-M4F without heap, exceptions or RTTI"
