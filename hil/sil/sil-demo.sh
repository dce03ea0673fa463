#!/bin/bash
# One SIL run for `tools/dev demo` (docs/sil.md#demo), on a bus with vcan0
# (run it through hil/vcan-run): candump capturing the bus, cvtplant-bridge,
# and the example controller and harness (cvtplant-sil) on one scenario in
# lock-step; the candump log, the JUnit report and the trace go to OUT.
#   hil/sil/sil-demo.sh BUILD_DIR OUT_DIR [SCENARIO]
# Exit status: cvtplant-sil's (0 passed, 1 a criterion failed), 1 when
# candump or the bridge did not start.
set -u
BUILD=$1 OUT=$2 SCENARIO=${3:-ratio-sweep}
IF=${CVT_CAN_IF:-vcan0}
mkdir -p "$OUT"
rm -f "$OUT/bridge.ready" "$OUT/candump.log" "$OUT/candump-drops.txt" "$OUT/sil-junit.xml" "$OUT/sil-run.txt"

# candump is capturing once it logged a marker frame (ID 0x7FF, not in the
# DBC); a second marker at the end shows it logged everything before.
marker() {  # marker DATA
  for _ in $(seq 1 100); do
    cansend "$IF" "7FF#$1"
    sleep 0.1
    grep -q " 7FF#$1\$" "$OUT/candump.log" && return 0
  done
  return 1
}
# Lock-step runs as fast as the processes can: an 8 MiB receive buffer keeps
# candump's socket from overflowing (the default one dropped nine frames in
# ten), and -d makes any drop visible (a DROPCOUNT line, moved out of the log
# into candump-drops.txt at the end).
candump -L -d -r 8388608 "$IF" > "$OUT/candump.log" &
candump_pid=$!
if ! marker 5A; then
  echo "sil-demo: candump is not capturing" >&2
  kill "$candump_pid" 2>/dev/null
  exit 1
fi
"$BUILD/hil/bridge/cvtplant-bridge" --iface "$IF" --summary "$OUT/bridge.json" --ready-file "$OUT/bridge.ready" &
bridge=$!
for _ in $(seq 1 400); do [ -e "$OUT/bridge.ready" ] && break; sleep 0.05; done
rc=1
if [ -e "$OUT/bridge.ready" ]; then
  "$BUILD/hil/cvtplant-sil" run --iface "$IF" --scenario "$SCENARIO" --out "$OUT" --junit "$OUT/sil-junit.xml" \
    > "$OUT/sil-run.txt"
  rc=$?
else
  echo "sil-demo: the bridge did not start" >&2
fi
kill -TERM "$bridge" 2>/dev/null
wait "$bridge"
marker A5 || echo "sil-demo: candump may have missed the last frames" >&2
kill "$candump_pid" 2>/dev/null
wait "$candump_pid" 2>/dev/null
# candump's drop reports: the last one carries the total.
grep 'DROPCOUNT' "$OUT/candump.log" | tail -1 | sed -n 's/.*(total drops \([0-9]*\)).*/\1/p' > "$OUT/candump-drops.txt"
[ -s "$OUT/candump-drops.txt" ] || echo 0 > "$OUT/candump-drops.txt"
sed -i '/DROPCOUNT/d' "$OUT/candump.log"
exit $rc
