#!/usr/bin/env bash
# Cross-target determinism (docs/architecture.md#determinism): the trace
# hashes of the reference scenario must be bit-identical on x86-64 (-O2),
# aarch64 (qemu-user) and Cortex-M4F (QEMU mps2-an386) for every scalar type
# each target prints. Needs the host-debug, aarch64-linux and cortex-m4f
# builds (tools/dev test builds them first).
set -euo pipefail
cd "$(dirname "$0")/../.."

host_bin=build/host-debug/tests/determinism/cvt_trace_hash_O2
a64_bin=build/aarch64-linux/tests/determinism/cvt_trace_hash_O2
m4_log=build/cortex-m4f/tests/target/trace_hash.log

for f in "$host_bin" "$a64_bin" "$m4_log"; do
  [ -e "$f" ] || { echo "missing $f (build the host-debug, aarch64-linux and cortex-m4f presets first)"; exit 1; }
done

host=$("$host_bin" | grep '^HASH ' | sort)
a64=$(qemu-aarch64 -L /usr/aarch64-linux-gnu "$a64_bin" | grep '^HASH ' | sort)
m4=$(tr -d '\r' < "$m4_log" | grep '^HASH ' | sort)

fail=0
echo "x86-64:"; echo "$host" | sed 's/^/  /'
if [ "$host" == "$a64" ]; then
  echo "aarch64: identical ($(echo "$a64" | wc -l) hashes)"
else
  echo "aarch64: DIFFERENT"; diff <(echo "$host") <(echo "$a64") || true; fail=1
fi
n_m4=$(echo "$m4" | grep -c . || true)
if [ "$n_m4" -lt 3 ]; then
  echo "cortex-m4f: expected at least 3 HASH lines in $m4_log, got $n_m4"; fail=1
else
  # Every hash the M4F printed must equal the host's line for that scalar/method.
  missing=$(comm -23 <(echo "$m4") <(echo "$host"))
  if [ -z "$missing" ]; then
    echo "cortex-m4f: identical ($n_m4 hashes)"
  else
    echo "cortex-m4f: DIFFERENT:"; echo "$missing"; fail=1
  fi
fi
[ "$fail" -eq 0 ] && echo "cross-target determinism: 1 passed, 0 failed" || echo "cross-target determinism: 0 passed, 1 failed"
exit "$fail"
