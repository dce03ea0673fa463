#!/bin/bash
# ctest cosim.reference_vcan, inside the vcan entry point (hil/vcan-run: the
# host's vcan0 or the micro-VM): the multibody reference on vcan0 behind its
# bridge program, a scenario's first seconds in lock-step against it
# (docs/sil.md#reference-plant):
#   cosim/tests/reference_vcan.sh BUILD_DIR OUT_DIR SCENARIO T_END [BRIDGE_OPTION...]
# The reference's release state comes from OUT_DIR/host/reference-cache (the
# host made it; the VM would take minutes for the start-up). Writes
# OUT_DIR/vcan/ (trace, JUnit, the bridge's log, summary and stderr) and
# prints the run's seconds.
set -u
BUILD=$1 OUT=$2 SCENARIO=$3 T_END=$4
shift 4
mkdir -p "$OUT/vcan"
t0=$(date +%s.%N)
"$BUILD/hil/cvtplant-sil" run --iface vcan0 --plant reference --scenario "$SCENARIO" --t-end "$T_END" --allow-partial \
  --out "$OUT/vcan" --junit "$OUT/vcan/sil-junit.xml" \
  --plant-cmd "$BUILD/cosim/cvtplant-reference-bridge --iface vcan0 --release-cache $OUT/host/reference-cache $* --log-clock sim --log $OUT/vcan/bridge.log --summary $OUT/vcan/bridge.json" \
  > "$OUT/vcan/run.txt" 2>&1
rc=$?
t1=$(date +%s.%N)
cat "$OUT/vcan/run.txt"
echo "reference_vcan: $SCENARIO to $T_END s on vcan0 against the reference: $(echo "$t1 - $t0" | bc) s wall, exit $rc"
exit $rc
