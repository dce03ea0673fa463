#!/bin/bash
# Real peers on vcan0 (docs/can.md#vcan-tests). Run through hil/vcan-run:
#   hil/vcan-run -- hil/tests/can/vcan_peers.sh BUILD_BIN_DIR SOURCE_DIR OUT_DIR
# candump (can-utils) logs the bus; vcan_transport_test (the project's
# SocketCanTransport + codec) plays the controller against vcan_peer.py
# (python3-can + python3-canmatrix); then C++<->C++ round trips, a send burst
# and the FD refusal. Exit status 0 only if every part passed.
set -u
BIN=$1 SRC=$2 OUT=$3
IF=${CVT_CAN_IF:-vcan0}
N=${CVT_VCAN_N:-200}
PY=/usr/bin/python3
DBC=$SRC/hil/cvtplant.dbc
mkdir -p "$OUT"
rm -f "$OUT/peer.ready" "$OUT/candump.log"
rc=0

# Data frames (0:0) and every error class (#FFFFFFFF), log format.
candump -L "$IF,0:0,#FFFFFFFF" > "$OUT/candump.log" &
candump_pid=$!

$PY "$SRC/hil/tests/can/vcan_peer.py" "$IF" "$DBC" "$OUT/peer.ready" > "$OUT/vcan_peer.log" 2>&1 &
peer_pid=$!
for _ in $(seq 1 600); do [ -e "$OUT/peer.ready" ] && break; sleep 0.1; done
if [ ! -e "$OUT/peer.ready" ]; then echo "vcan_peers: python peer did not start"; cat "$OUT/vcan_peer.log"; exit 1; fi

"$BIN/vcan_transport_test" peer "$IF" "$N" || rc=1
wait "$peer_pid" || rc=1
cat "$OUT/vcan_peer.log"

"$BIN/vcan_transport_test" echo "$IF" 2000 &
echo_pid=$!
sleep 0.2
"$BIN/vcan_transport_test" ping "$IF" 2000 || rc=1
wait "$echo_pid" || rc=1
"$BIN/vcan_transport_test" blast "$IF" 20000 || rc=1
"$BIN/vcan_transport_test" fd "$IF" || rc=1

sleep 0.3
kill "$candump_pid" 2>/dev/null
wait "$candump_pid" 2>/dev/null
$PY "$SRC/hil/tests/can/check_candump.py" "$OUT/candump.log" "$DBC" "$N" || rc=1
echo "vcan_peers: $([ $rc = 0 ] && echo PASSED || echo FAILED)"
exit $rc
