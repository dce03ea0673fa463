#!/bin/bash
# Command-line contract of cvtplant-bridge, cvtplant-sil and cvtplant-controller (docs/sil.md#cli):
# --help exits 0; a bad flag or value gives exactly one line on stderr and
# exit 2; an interface that cannot be opened gives exit 1.
#   check_cli.sh BRIDGE SIL CONTROLLER
set -u
BRIDGE=$1 SIL=$2 CONTROLLER=$3
rc=0
# shellcheck source=/dev/null
source "$(dirname "$0")/../../../tests/support/cli_expect.sh"
expect 0 "$BRIDGE" --help
expect 2 "$BRIDGE" --bogus
expect 2 "$BRIDGE" --mode fast
expect 2 "$BRIDGE" --scene no-such-scene
expect 2 "$BRIDGE" --duration-s -1
expect 2 "$BRIDGE" --sched-fifo 100
expect 2 "$BRIDGE" --log-clock wall
expect 2 "$BRIDGE" --cmd-timeout-reaction substitute
expect 2 "$BRIDGE" --iface
expect 1 "$BRIDGE" --iface nosuchcan0
expect 0 "$SIL" --help
expect 2 "$SIL"
expect 2 "$SIL" fly
expect 2 "$SIL" run --scenario nope
expect 2 "$SIL" run --safety x
expect 2 "$SIL" run --clamp-floor 5
expect 2 "$SIL" run --clamp-floor 1e5
expect 2 "$SIL" run --controller external --clamp-floor 2000
expect 2 "$SIL" run --reply-timeout-ms 0
expect 2 "$SIL" run --mode fast
expect 2 "$SIL" run --loopback --mode realtime --scenario tip-in
expect 2 "$SIL" run --loopback --mode realtime --loopback-frame-cost-us -1
expect 2 "$SIL" run --mode realtime --loopback-frame-cost-us 1500
expect 2 "$SIL" run --loopback --loopback-frame-cost-us 1500
expect 2 "$SIL" bench --steps 0
expect 2 "$SIL" run --controller ecu
expect 2 "$SIL" run --loopback --controller external
expect 2 "$SIL" run --controller external --scenario clamp-loss
expect 2 "$SIL" run --controller external --safety 1.5
expect 2 "$SIL" run --controller-timeout-ms 0
expect 2 "$SIL" run --t-end 2 --scenario ratio-sweep
expect 2 "$SIL" run --scenario tip-in,nope
expect 2 "$SIL" run --scenario tip-in,
expect 2 "$SIL" run --loopback --plant-cmd true
expect 2 "$SIL" bench --controller external
expect 1 "$SIL" run --iface nosuchcan0
# An output directory that cannot be made is an error, not missing traces.
expect 1 "$SIL" run --loopback --scenario tip-in --out /proc/cvtplant-no-such-dir
expect 0 "$CONTROLLER" --help
expect 2 "$CONTROLLER" --bogus
expect 2 "$CONTROLLER" --lockstep --demand-Nm
expect 2 "$CONTROLLER" --demand-Nm 900
expect 2 "$CONTROLLER" --schedule sometimes
expect 2 "$CONTROLLER" --ratio-steps 0:1.5,0.5
expect 2 "$CONTROLLER" --ratio-steps 0:9
expect 2 "$CONTROLLER" --ratio-steps 1:1.5
expect 2 "$CONTROLLER" --ratio-steps 0:1.5,0:1.2
expect 1 "$CONTROLLER" --iface nosuchcan0
exit $rc
