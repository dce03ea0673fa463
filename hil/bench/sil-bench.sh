#!/bin/bash
# SIL figures (docs/sil.md#figures): lock-step round trips per second,
# real-time 1 kHz jitter of cvtplant-bridge on vcan0, and the example
# controller's fresh-data fraction with both schedules
# (docs/sil.md#controller-schedule). Run it where vcan0 is:
#   mkdir -p OUT && hil/vcan-run --rw OUT -- env [STEPS=N] [RT_S=S] [LOAD=N] hil/bench/sil-bench.sh BUILD_DIR OUT
# (--rw OUT: the micro-VM shares only the listed directories writable, and
# OUT must exist; vcan-run says whether it used the host's vcan0 or the VM.)
# Environment: STEPS (round trips, default 20000), RT_S (seconds per
# real-time run, default 10), LOAD (busy loops beside the controller-schedule
# runs, default 0).
set -u
BUILD=$1 OUT=$2
IF=${CVT_CAN_IF:-vcan0}
STEPS=${STEPS:-20000} RT_S=${RT_S:-10}
BRIDGE=$BUILD/hil/bridge/cvtplant-bridge
SIL=$BUILD/hil/cvtplant-sil
mkdir -p "$OUT"
rc=0
echo "sil-bench: $(uname -r), $(nproc) CPUs, interface $IF"

# Lock-step: the harness sends Step(1) and waits for the group's PlantStatus.
# Once with bridge and harness on one CPU (no cross-CPU wake-up per frame),
# once free to run anywhere.
for pin in cpu0 any; do
  run=(); [ $pin = cpu0 ] && run=(taskset -c 0)
  "${run[@]}" "$BRIDGE" --iface "$IF" --summary "$OUT/bench-bridge-$pin.json" &
  pid=$!
  sleep 0.5
  "${run[@]}" "$SIL" bench --iface "$IF" --steps "$STEPS" | tee "$OUT/bench-lockstep-$pin.json" || rc=1
  "${run[@]}" "$SIL" bench --iface "$IF" --steps $((STEPS / 4)) --with-controller | tee "$OUT/bench-lockstep-controller-$pin.json" || rc=1
  kill -TERM $pid; wait $pid || rc=1
done

# Real time at the scene's 1 kHz frame rate: with SCHED_FIFO, without, and
# with SCHED_FIFO and cvtplant-controller sending CtrlCmd every 10 ms.
for mode in fifo plain fifo+controller; do
  extra=(); [ $mode != plain ] && extra=(--sched-fifo 80)
  ctl_pid=
  if [ $mode = fifo+controller ]; then
    "$BUILD/hil/controller/cvtplant-controller" --iface "$IF" --demand-Nm 80 --duration-s $((RT_S + 2)) > "$OUT/bench-controller.json" &
    ctl_pid=$!
    sleep 0.5
  fi
  "$BRIDGE" --iface "$IF" --mode realtime --duration-s "$RT_S" "${extra[@]}" --summary "$OUT/bench-rt-$mode.json" || rc=1
  [ -n "$ctl_pid" ] && { kill -TERM $ctl_pid; wait $ctl_pid; cat "$OUT/bench-controller.json"; }
  /usr/bin/python3 - "$OUT/bench-rt-$mode.json" "$mode" <<'PYEOF'
import json, sys
s = json.load(open(sys.argv[1]))
rt = s["realtime"]
j = rt["jitter_ns"]
print("sil-bench: real time 1 kHz (%s): %d periods, %d overruns, SCHED_FIFO granted %s %s; lateness p50 %.1f us, p99 %.1f us, p99.9 %.1f us, max %.1f us; rx accepted %d, cmd timeouts %d"
      % (sys.argv[2], rt["periods"], rt["overruns"], rt["sched_fifo"], rt["sched_fifo_error"],
         j["p50"] / 1e3, j["p99"] / 1e3, j["p99_9"] / 1e3, j["max"] / 1e3, s["rx"]["accepted"], s["cmd_timeouts"]))
PYEOF
done
# The example controller's schedule (docs/sil.md#controller-schedule): the
# bridge in real time for RT_S + 2 s, the controller for RT_S s inside it,
# once on its own fixed 10 ms clock and once following the plant's groups;
# LOAD busy loops (default 0) compete for the CPUs.
hogs=()
for _ in $(seq 1 "${LOAD:-0}"); do (while :; do :; done) & hogs+=($!); done
for sched in fixed group; do
  "$BRIDGE" --iface "$IF" --mode realtime --duration-s $((RT_S + 2)) --sched-fifo 80 \
    --summary "$OUT/bench-schedule-bridge-$sched.json" &
  pid=$!
  sleep 1
  "$BUILD/hil/controller/cvtplant-controller" --iface "$IF" --demand-Nm 80 --duration-s "$RT_S" --schedule $sched \
    > "$OUT/bench-schedule-$sched.json" || rc=1
  wait $pid || rc=1
  /usr/bin/python3 -c 'import json, sys; c = json.load(open(sys.argv[1]))
print("sil-bench: controller schedule %s (load %s): %d of %d steps with fresh plant data (%.3f), longest gap %.1f ms"
      % (c["schedule"], sys.argv[2], c["fresh_periods"], c["periods"], c["fresh_fraction"], c["max_step_gap_ms"]))' \
    "$OUT/bench-schedule-$sched.json" "${LOAD:-0}"
done
[ ${#hogs[@]} -gt 0 ] && kill "${hogs[@]}"
exit $rc
