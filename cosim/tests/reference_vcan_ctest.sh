#!/bin/bash
# ctest cosim.reference_vcan (docs/sil.md#tests): the first 0.3 s of tip-in
# in lock-step against the multibody reference, once on the loopback bus on
# the host (which also makes the reference's release state) and once on
# vcan0 through the vcan entry point (hil/vcan-run: the host's vcan0 or the
# micro-VM) with cvtplant-reference-bridge as the plant; then, on the host,
# the two runs checked against each other (check_reference_vcan.py):
#   cosim/tests/reference_vcan_ctest.sh BUILD_DIR SOURCE_DIR OUT_DIR
# Prints each step's seconds. Exit status: 0 when all passed.
set -u
BUILD=$1 SRC=$2 OUT=$3
SCENARIO=tip-in T_END=0.3
rm -rf "$OUT"
mkdir -p "$OUT"
t0=$SECONDS
"$BUILD/hil/cvtplant-sil" run --loopback --plant reference --scenario $SCENARIO --t-end $T_END --allow-partial \
  --out "$OUT/host" --junit "$OUT/host/sil-junit.xml" > "$OUT/host.txt" 2>&1
hrc=$?
echo "reference_vcan: loopback run on the host (with the start-up): $((SECONDS - t0)) s, exit $hrc"
t1=$SECONDS
"$SRC/hil/vcan-run" --rw "$OUT" -- "$SRC/cosim/tests/reference_vcan.sh" "$BUILD" "$OUT" $SCENARIO $T_END
rc=$?
echo "reference_vcan: vcan-run: $((SECONDS - t1)) s, exit $rc"
/usr/bin/python3 "$SRC/cosim/tests/check_reference_vcan.py" "$OUT" $SCENARIO $T_END || rc=1
exit $rc
