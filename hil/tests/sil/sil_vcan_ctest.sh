#!/bin/bash
# ctest hil.sil_vcan (docs/sil.md#tests): the SIL suite on vcan0 through the vcan
# entry point (hil/vcan-run: the host's vcan0, or the micro-VM, booted once),
# then the checks that only read the files it wrote, on the host, where
# Python is not slowed down by the VM's emulation:
#   hil/tests/sil/sil_vcan_ctest.sh BUILD_DIR SOURCE_DIR OUT_DIR
# Exit status: 0 when both passed; vcan-run's status (125: no VM) otherwise.
set -u
BUILD=$1 SRC=$2 OUT=$3
mkdir -p "$OUT"
"$SRC/hil/vcan-run" --rw "$(dirname "$OUT")" -- "$SRC/hil/tests/sil/sil_vcan.sh" "$BUILD" "$SRC" "$OUT"
rc=$?
if [ -s "$OUT/candump.log" ] && [ -s "$OUT/bridge-sil.log" ]; then
  /usr/bin/python3 "$SRC/hil/tests/sil/check_sil_log.py" "$OUT/candump.log" "$OUT/bridge-sil.log" \
    "$SRC/hil/cvtplant.dbc" || { echo "hil.sil_vcan: FAIL: candump vs bridge log"; [ $rc = 0 ] && rc=1; }
else
  echo "hil.sil_vcan: FAIL: no candump.log / bridge-sil.log in $OUT"
  [ $rc = 0 ] && rc=1
fi
exit $rc
