#!/bin/bash
# The ratio figure of a SIL run (docs/sil.md#plot): from a loopback
# ratio-sweep trace, hil/sil/sil_ratio_plot.gp must write a 1100 x 1000 PNG
# with drawn content (a blank or single-panel image compresses to a few kB).
#   check_ratio_plot.sh CVTPLANT_SIL SOURCE_DIR OUT_DIR
set -u
SIL=$1 SRC=$2 OUT=$3
mkdir -p "$OUT"
rm -f "$OUT/sil-ratio-sweep.png"
"$SIL" run --loopback --scenario ratio-sweep --out "$OUT" > /dev/null || { echo "FAIL: ratio-sweep run"; exit 1; }
gnuplot -e "csv='$OUT/sil-ratio-sweep.csv'; png='$OUT/sil-ratio-sweep.png'; name='ratio-sweep'; how='loopback'" \
  "$SRC/hil/sil/sil_ratio_plot.gp" || { echo "FAIL: gnuplot"; exit 1; }
/usr/bin/python3 - "$OUT/sil-ratio-sweep.png" <<'PYEOF'
import struct, sys
d = open(sys.argv[1], "rb").read()
ok = d[:8] == b"\x89PNG\r\n\x1a\n"
w, h = struct.unpack(">II", d[16:24]) if ok else (0, 0)
print("ratio figure: %d x %d px, %d bytes" % (w, h, len(d)))
sys.exit(0 if ok and (w, h) == (1100, 1000) and len(d) > 60000 else 1)
PYEOF
