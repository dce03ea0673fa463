#!/bin/bash
# The FMU's shared object holds no mutable global state (docs/fmu.md#instances):
# no object of its own in .data or .bss, only the C runtime's start-up
# bookkeeping. Read-only tables (.rodata, .data.rel.ro: vtables, the signal and
# parameter lists) are fine. Eigen's indexing placeholders (Eigen::all, last,
# lastp1, fix<N>) are empty `static const` tag objects that an unoptimised
# build gives a byte of .bss; they hold no state and are allowed by name.
# usage: no_global_state.sh OBJDUMP FMU.so
set -euo pipefail
objdump=$1 so=$2
found=$("$objdump" -t "$so" | awk '($4 == ".data" || $4 == ".bss" || $3 == ".data" || $3 == ".bss") && $NF !~ /^(completed\.[0-9]+|__dso_handle|__TMC_END__|__data_start|data_start|__bss_start|_edata|_end|_ZN5EigenL(4last|6lastp1|3all|3fixILi[0-9]+EE)E)$/ { print $NF }')
if [ -n "$found" ]; then
  echo "mutable globals in $so:"
  echo "$found"
  echo "0 passed, 1 failed"
  exit 1
fi
echo "no mutable global in $(basename "$so")"
echo "1 passed, 0 failed"
