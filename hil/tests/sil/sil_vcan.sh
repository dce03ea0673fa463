#!/bin/bash
# The SIL suite on vcan0, in one vcan-run invocation so the micro-VM boots
# once (docs/sil.md#tests):
#   hil/vcan-run --rw OUT_PARENT -- hil/tests/sil/sil_vcan.sh BUILD_DIR SOURCE_DIR OUT_DIR
# 1. cvtplant-bridge (lock-step) + cvtplant-sil: the ten scenarios (three
#    ratio control, two driving, five faults) with the example controller
#    -> OUT/sil-junit.xml (every scenario present and passed, the ratio
#    scenarios with their tracking, slip and fault criteria, and again in
#    real time on the wall clock), OUT/sil-*.csv;
#    an undersized clamp (--safety 0.8) must be caught as gross slip;
#    the python3-can/canmatrix peer (sil_peer.py: malformed frames and the
#    faults) on the same bridge; the bridge's JSON summary must show every
#    rejection reason counted;
#    candump's capture and the bridge's own log are written for
#    check_sil_log.py, which sil_vcan_ctest.sh runs on the host afterwards;
#    a receive-queue overflow provoked with SIGSTOP + cangen must show up in
#    PlantBusDiag and PlantStatus.
# 2. Determinism: two fresh bridges, same scenario, byte-identical logs.
# 3. Real time at 1 kHz with cvtplant-controller beside it for 2 s;
#    jitter, overruns and the controller's fresh-data fraction reported;
#    the fraction (>= 0.8) and counts checked when the plant kept time.
# 4. Lock-step round trips (reported).
# 5. gnuplot summary plot OUT/sil-summary.png.
set -u
BUILD=$1 SRC=$2 OUT=$3
IF=${CVT_CAN_IF:-vcan0}
PY=/usr/bin/python3
DBC=$SRC/hil/cvtplant.dbc
BRIDGE=$BUILD/hil/bridge/cvtplant-bridge
SIL=$BUILD/hil/cvtplant-sil
mkdir -p "$OUT"
rm -f "$OUT"/*.log "$OUT"/*.json "$OUT"/*.xml "$OUT"/*.csv "$OUT"/*.png "$OUT"/*.ready
rc=0
fail() { echo "hil.sil_vcan: FAIL: $*"; rc=1; }

start_bridge() {  # name, extra args...
  local name=$1; shift
  rm -f "$OUT/$name.ready"
  "$BRIDGE" --iface "$IF" --ready-file "$OUT/$name.ready" --summary "$OUT/$name.json" "$@" &
  bridge_pid=$!
  for _ in $(seq 1 400); do [ -e "$OUT/$name.ready" ] && return 0; sleep 0.05; done
  fail "bridge $name did not start"
}
stop_bridge() {
  kill -TERM "$bridge_pid" 2>/dev/null
  wait "$bridge_pid" || fail "bridge exit status $?"
}

# ---- 1. scenarios, negative control, python peer, candump -------------------
candump -L -r 8388608 "$IF,0:0,#FFFFFFFF" > "$OUT/candump.log" &
candump_pid=$!
# candump must be capturing before the bridge's first frame: a marker frame
# (ID 0x7FF, not in the DBC) proves it.
for _ in $(seq 1 100); do
  cansend "$IF" 7FF#5A
  sleep 0.2
  grep -q ' 7FF#5A$' "$OUT/candump.log" && break
done
grep -q ' 7FF#5A$' "$OUT/candump.log" || fail "candump is not capturing"
start_bridge bridge-sil --log "$OUT/bridge-sil.log"
t0=$(date +%s.%N)
"$SIL" run --iface "$IF" --mode both --out "$OUT" --junit "$OUT/sil-junit.xml" || fail "SIL scenarios"
t1=$(date +%s.%N)
# Every scenario, the fault scenarios included, ran here in lock-step over
# vcan0 and passed every criterion (docs/sil.md#scenarios); the ratio
# scenarios also in real time, judged in full when the plant kept time,
# otherwise on no fault and no rejected frame (docs/sil.md#ratio-realtime).
$PY - "$OUT/sil-junit.xml" <<'PYEOF' || fail "JUnit report"
import sys
import xml.etree.ElementTree as ET
want = ["ratio-sweep", "kick-down", "slip-recovery", "tip-in", "load-step", "clamp-loss", "lost-frames", "frozen-controller", "controller-restart",
        "controller-flood"]
suites = {s.get("name"): s for s in ET.parse(sys.argv[1]).getroot().iter("testsuite")}
common = ["lockstep_time_exact", "slip_bounded", "no_watchdog_fault"]
ratio = ["ratio_tracked", "no_cmd_timeout"]
def checks(n):
    return {c.get("name") for c in suites["sil." + n].iter("testcase")}
def judged(n, check):
    return any(c.get("name") == check and c.find("skipped") is None for c in suites["sil." + n].iter("testcase"))
bad = [n for n in want if "sil." + n not in suites or suites["sil." + n].get("failures") != "0" or
       not set(common + (ratio if n in want[:3] else [])) <= checks(n)]
# Real time: the functional criteria always judged, the rest present.
rt_always = ["realtime_paced", "frames_valid", "no_watchdog_fault"]
rt = [n + ".realtime" for n in want[:3]]
bad += [n for n in rt if "sil." + n not in suites or suites["sil." + n].get("failures") != "0" or
        not set(rt_always + common[1:] + ratio + ["control_on_fresh_groups"]) <= checks(n) or
        not all(judged(n, c) for c in rt_always)]
full = [n for n in rt if "sil." + n in suites and suites["sil." + n].get("skipped") == "0"]
print("hil.sil_vcan: JUnit: %d scenarios, %d checks, %s; real time judged in full (plant kept time): %s" % (
    len(suites), sum(int(s.get("tests")) for s in suites.values()),
    "all passed" if not bad else "missing or failed: %s" % bad, full or "none"))
for n in rt:
    for c in suites.get("sil." + n, ET.Element("x")).iter("testcase"):
        if c.get("name") == "realtime_paced":
            print("hil.sil_vcan: %s: %s" % (n, c.findtext("system-out")))
sys.exit(1 if bad else 0)
PYEOF
mkdir -p "$OUT/undersized"
if "$SIL" run --iface "$IF" --scenario load-step --safety 0.8 --out "$OUT/undersized" > "$OUT/undersized/out.txt"; then
  fail "an undersized clamp (safety 0.8) passed the gross-slip criterion"
elif ! grep -q "FAIL no_gross_slip" "$OUT/undersized/out.txt"; then
  cat "$OUT/undersized/out.txt"; fail "undersized clamp: expected exactly the gross-slip criterion to fail"
else
  echo "hil.sil_vcan: undersized clamp (safety 0.8) caught: $(grep 'no_gross_slip' "$OUT/undersized/out.txt" | sed 's/^ *//')"
fi
$PY "$SRC/hil/tests/sil/sil_peer.py" "$IF" "$DBC" || fail "python peer"
t2=$(date +%s.%N)
echo "hil.sil_vcan: scenarios $(awk "BEGIN{print $t1 - $t0}") s, negative control + python peer $(awk "BEGIN{print $t2 - $t1}") s"
stop_bridge
# A closing marker: once candump logged it, it has logged every frame before.
for _ in $(seq 1 100); do
  cansend "$IF" 7FF#A5
  sleep 0.2
  grep -q ' 7FF#A5$' "$OUT/candump.log" && break
done
kill "$candump_pid" 2>/dev/null; wait "$candump_pid" 2>/dev/null
$PY - "$OUT/bridge-sil.json" <<'PYEOF' || fail "bridge summary counters"
import json, sys
s = json.load(open(sys.argv[1]))
rx = s["rx"]
need = ["wrong_crc", "wrong_dlc", "unknown_id", "out_of_range", "repeated", "error_frames"]
missing = [k for k in need if rx[k] < 1]
print("bridge summary: rx %s, cmd_timeouts %d, tx sent %d failed %d" % (
    {k: rx[k] for k in need + ["accepted", "rejected"]}, s["cmd_timeouts"], s["tx"]["sent"], s["tx"]["failed"]))
ok = not missing and s["cmd_timeouts"] >= 1 and s["tx"]["failed"] == 0 and s["plant_fault"] == "none"
if missing:
    print("not counted:", missing)
sys.exit(0 if ok else 1)
PYEOF
# candump.log against bridge-sil.log: checked on the host afterwards
# (sil_vcan_ctest.sh), where Python runs without the VM's emulation.

# ---- 1b. receive-queue overflow, reported on the bus ------------------------
# The bridge is stopped (SIGSTOP) while cangen floods the bus: its socket
# queue overflows in the kernel. Once it runs again, PlantBusDiag must carry
# the kernel's drop count (SO_RXQ_OVFL), equal to its JSON summary, and the
# next PlantStatus fault_frames_dropped.
start_bridge bridge-ovf
$PY "$SRC/hil/tests/sil/sil_bus_diag.py" "$IF" "$DBC" > "$OUT/ovf-before.json" || fail "bus diagnostics before the flood"
kill -STOP "$bridge_pid"
cangen "$IF" -g 0 -n ${CVT_SIL_FLOOD:-4000} -I 555 -L 8 -D 0011223344556677 || fail "cangen flood"
kill -CONT "$bridge_pid"
$PY "$SRC/hil/tests/sil/sil_bus_diag.py" "$IF" "$DBC" > "$OUT/ovf-after.json" || fail "bus diagnostics after the flood"
stop_bridge
$PY - "$OUT/ovf-before.json" "$OUT/ovf-after.json" "$OUT/bridge-ovf.json" <<'PYEOF' || fail "overflow not reported on the bus"
import json, sys
before, after = (json.loads(open(p).read()) for p in sys.argv[1:3])
s = json.load(open(sys.argv[3]))
print("hil.sil_vcan: receive-queue overflow: PlantBusDiag.rx_kernel_drops %d -> %d, JSON %d; fault_frames_dropped %s; "
      "rejected_frames %d -> %d" % (before["rx_kernel_drops"], after["rx_kernel_drops"], s["bus"]["rx_kernel_drops"],
                                    after["fault_frames_dropped"], before["rejected_frames"], after["rejected_frames"]))
ok = (before["rx_kernel_drops"] == 0 and after["rx_kernel_drops"] > 0 and
      after["rx_kernel_drops"] == s["bus"]["rx_kernel_drops"] % 65536 and after["fault_frames_dropped"] and
      not before["fault_frames_dropped"] and after["bus_state"] == "ErrorActive")
sys.exit(0 if ok else 1)
PYEOF

t3=$(date +%s.%N)
# ---- 2. determinism ---------------------------------------------------------
for run in 1 2; do
  start_bridge det$run --log "$OUT/det$run.log" --log-clock sim
  mkdir -p "$OUT/det$run"
  "$SIL" run --iface "$IF" --scenario tip-in --out "$OUT/det$run" > /dev/null || fail "determinism run $run"
  stop_bridge
done
if [ -s "$OUT/det1.log" ] && cmp -s "$OUT/det1.log" "$OUT/det2.log"; then
  echo "hil.sil_vcan: determinism: two runs, $(wc -l < "$OUT/det1.log") frames, byte-identical (sha256 $(sha256sum < "$OUT/det1.log" | cut -c1-16))"
else
  fail "determinism: the two lock-step traces differ"
fi

echo "hil.sil_vcan: summary and overflow checks $(awk "BEGIN{print $t3 - $t2}") s, determinism $(awk "BEGIN{print $(date +%s.%N) - $t3}") s"
# ---- 3. real time, 4. round trips (figures, docs/sil.md#figures) -----------
# Real time with the example controller beside it, following the plant's
# groups (docs/sil.md#controller-schedule). The controller runs 2 s and the
# bridge is stopped only after it, so every control step has a plant running
# (--duration-s 60 only caps a run whose controller never ends).
start_bridge bridge-rt --mode realtime --duration-s 60 --sched-fifo 50
"$BUILD/hil/controller/cvtplant-controller" --iface "$IF" --demand-Nm 80 --duration-s 2 > "$OUT/controller-rt.json" \
  || fail "controller exit status"
stop_bridge
$PY - "$OUT/bridge-rt.json" "$OUT/controller-rt.json" <<'PYEOF' || fail "real-time summary"
import json, sys
s = json.load(open(sys.argv[1]))
c = json.load(open(sys.argv[2]))
rt = s["realtime"]
if rt is None:
    print("hil.sil_vcan: the bridge never ran in real time (stopped before its pacing loop)")
    sys.exit(1)
j = rt["jitter_ns"]
print("hil.sil_vcan: real time 1 kHz with the controller: %d periods, %d overruns, SCHED_FIFO %s, lateness p50 %.1f us "
      "p99 %.1f us p99.9 %.1f us max %.1f us; bridge accepted %d frames, %d cmd timeouts; controller %s"
      % (rt["periods"], rt["overruns"], rt["sched_fifo"], j["p50"] / 1e3, j["p99"] / 1e3, j["p99_9"] / 1e3,
         j["max"] / 1e3, s["rx"]["accepted"], s["cmd_timeouts"], c))
print("hil.sil_vcan: controller steps with fresh plant data: %d of %d (%.3f), longest gap between steps %.1f ms"
      % (c["fresh_periods"], c["periods"], c["fresh_fraction"], c["max_step_gap_ms"]))
# What holds however starved the VM is: the bridge paced frames in real
# time, the two nodes talked, the plant ran without a fault, and nothing was
# rejected but the counter jump that may follow each command timeout (the
# frames queued during the outage are drained, so the next fresh one skips
# their counters, docs/sil.md#timeouts; a run at host load 8 had 7 timeouts
# and 1 such jump), or frames the kernel dropped. What depends on CPU time is checked only when the plant
# kept time (at most 10 % of its frames overran): at least 2000 frames in the
# controller's 2 s, 50 commands applied, a fresh-data fraction of at least
# 0.8. The TCG VM on a loaded host often does not keep time (a run at host
# load 14 had a median lateness of 1.6 s); the exact figures of the schedule
# are the in-process test's (test_controller_schedule.cpp).
on_time = rt["overruns"] <= 0.1 * rt["periods"]
ok = (rt["periods"] >= 1 and j["max"] >= j["p99_9"] >= j["p99"] >= j["p50"] >= 0 and
      s["rx"]["accepted"] >= 1 and s["rx"]["rejected"] == s["rx"]["wrong_sequence"] <=
      s["cmd_timeouts"] + s["bus"]["rx_kernel_drops"] and
      s["plant_fault"] == "none" and c["accepted"] >= 1 and c["rejected"] == 0)
if on_time:
    ok = ok and rt["periods"] >= 2000 and s["rx"]["accepted"] >= 50 and c["fresh_fraction"] >= 0.8
print("hil.sil_vcan: %d of %d frames overran: %s; bridge rejected %d (%d counter jumps after %d command timeouts)" % (
    rt["overruns"], rt["periods"], "the plant kept time, frames, commands and fresh-data floor 0.8 checked" if on_time
    else "the VM did not keep time, only the functional checks apply", s["rx"]["rejected"],
    s["rx"]["wrong_sequence"], s["cmd_timeouts"]))
sys.exit(0 if ok else 1)
PYEOF
# Ratio control in real time (docs/sil.md#ratio-scenarios): the variable-
# ratio plant paced at 1 kHz, the controller free-running with set-point
# steps 1.5 -> 1.7 -> 1.3, then 0.8, beyond the overdrive stop (reached at
# the bounded shift speed after about 0.7 s); the controller reports the
# largest settled error. What needs CPU time (tracking, slip, the stop
# reached) is judged only when both processes kept time: at most 1 % of the
# plant's frames overran and the controller stepped on fresh data in at
# least 95 % of its periods. A late controller's clamping lags the shift,
# and slip grows with the lateness: a run with 9.8 % of the frames overrun
# reached 0.13 of slip. A starved VM's controller misses its deadlines, the
# bridge's timeout ramps take over both clampings and shift the ratio
# (docs/sil.md#timeouts). The host-independent figure is the virtual-clock
# test (sil_bridge_tests "onto both end stops").
start_bridge bridge-rt-ratio --mode realtime --duration-s 60 --scene ratio-control
"$BUILD/hil/controller/cvtplant-controller" --iface "$IF" --demand-Nm 60 --duration-s 5.5 \
  --ratio-steps 0:1.5,0.5:1.7,2.5:1.3,4:0.8 > "$OUT/controller-rt-ratio.json" || fail "ratio controller exit status"
stop_bridge
$PY - "$OUT/bridge-rt-ratio.json" "$OUT/controller-rt-ratio.json" <<'PYEOF' || fail "real-time ratio control"
import json, sys
s = json.load(open(sys.argv[1]))
c = json.load(open(sys.argv[2]))
r = c["ratio"]
rt = s["realtime"]
if rt is None:
    print("hil.sil_vcan: real-time ratio control: the bridge never ran in real time")
    sys.exit(1)
on_time = rt["overruns"] <= 0.01 * rt["periods"] and c["fresh_fraction"] >= 0.95
print("hil.sil_vcan: real-time ratio control: %d periods (%d overruns), controller on fresh data %.3f, plant fault %s, "
      "%d settled samples, max |ratio - set-point| %.4f, max |slip| %.4f, %d stop-refined frames, %d shift timeouts; %s"
      % (rt["periods"], rt["overruns"], c["fresh_fraction"], s["plant_fault"], r["settled_samples"],
         r["max_abs_error_settled"], r["max_abs_slip"], s["stop_refined_frames"], s["shift_timeouts"],
         "both kept time: tracking, slip and the stop checked" if on_time
         else "the VM did not keep time (more than 1 % overruns or under 0.95 fresh), only the functional checks apply"))
ok = s["plant_fault"] == "none" and c["accepted"] >= 1 and c["rejected"] == 0 and r["steps"] == 4
if on_time:
    ok = (ok and r["settled_samples"] >= 20 and r["max_abs_error_settled"] <= 0.05 and r["max_abs_slip"] <= 0.10
          and s["stop_refined_frames"] > 0)
sys.exit(0 if ok else 1)
PYEOF
# Round trips, both ends on one CPU and on any CPU (hil/bench/sil-bench.sh
# makes the long runs).
for pin in 0 any; do
  if [ $pin = any ]; then run=(); else run=(taskset -c $pin); fi
  "${run[@]}" "$BRIDGE" --iface "$IF" --ready-file "$OUT/bench.ready" --summary "$OUT/bridge-bench-$pin.json" &
  bridge_pid=$!
  for _ in $(seq 1 400); do [ -e "$OUT/bench.ready" ] && break; sleep 0.05; done
  "${run[@]}" "$SIL" bench --iface "$IF" --steps ${CVT_SIL_BENCH_STEPS:-500} | tee "$OUT/bench-cpu-$pin.json" || fail "lock-step bench"
  stop_bridge
  rm -f "$OUT/bench.ready"
done

# ---- 5. plot ----------------------------------------------------------------
gnuplot -e "dir='$OUT'" "$SRC/hil/tests/sil/sil_plot.gp" && [ -s "$OUT/sil-summary.png" ] || fail "summary plot"

echo "hil.sil_vcan: $([ $rc = 0 ] && echo PASSED || echo FAILED)"
exit $rc
