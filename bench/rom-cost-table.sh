#!/usr/bin/env bash
# Regenerates the cost table of docs/rom.md#cost and prints it as markdown:
# for every row of bench/cost_cases.hpp (each built-in
# scene at its real-time default, and each optional feature),
#   - Cortex-M4F instructions per 1 ms frame in float (QEMU icount; the
#     target test tests/target/test_rom_cost.cpp prints ICOUNT lines),
#   - host ns per frame in float and double (bench/bench_rom.cpp, median of
#     5 repetitions of the CPU time: on a shared host the wall time also
#     counts the time other jobs held the core; read ratios, not absolutes),
#   - Cortex-M4F instructions of every frame of a run of the default scene
#     (tests/target/test_rom_run_cost.cpp; ICOUNT rom_run lines),
#   - the spread of a frame's cost over 20,000 consecutive frames of each
#     scene in double (median, p99, p99.9, max; wall time of each frame, so
#     the tail includes interrupts and preemption on a shared host).
# Builds what it needs: the cortex-m4f preset's target image and bench_rom in
# a host Release tree.
#
# Usage: bench/rom-cost-table.sh [HOST_BUILD_DIR]     (default: build-rom)
set -euo pipefail
cd "$(dirname "$0")/.."
host=${1:-build-rom}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "building the Cortex-M4F target image and running it under QEMU..." >&2
[ -f build/cortex-m4f/CMakeCache.txt ] || cmake --preset cortex-m4f >&2
cmake --build --preset cortex-m4f --target cvt_target_tests >&2
# tests.target keeps its console output (ICOUNT and HASH lines) in this log.
ctest --test-dir build/cortex-m4f -R '^tests.target$' --output-on-failure >&2
m4_log=build/cortex-m4f/tests/target/trace_hash.log

echo "building and running bench_rom in $host..." >&2
[ -f "$host/CMakeCache.txt" ] || cmake -S . -B "$host" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCVT_BUILD_BENCH=ON >&2
cmake --build "$host" --target bench_rom >&2
"$host/bench/bench_rom" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_format=json >"$work/bench.json"

python3 - "$m4_log" "$work/bench.json" <<'EOF'
import json, sys
log, bench = sys.argv[1], sys.argv[2]
m4, parts, fixed, wparts, runs, exact = {}, [], {}, [], {}, {}
for line in open(log, errors="replace"):
    f = line.split()
    if len(f) == 16 and f[:3] == ["ICOUNT", "rom_run", "float"]:
        runs[f[3]] = dict(zip(f[4::2], map(int, f[5::2])))
    elif len(f) == 10 and f[:3] == ["ICOUNT", "rom_run_exact", "float"]:
        exact[f[3]] = {"median_frame": int(f[5]), "median": int(f[6]), "max_frame": int(f[8]), "max": int(f[9])}
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_frame", "float"]:
        m4[f[3]] = int(f[4])
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_frame", "q16_16"]:
        fixed[f[3]] = int(f[4])
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_part", "float"]:
        parts.append((f[3], int(f[4])))
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_part_wedging", "float"]:
        wparts.append((f[3], int(f[4])))
ns, spread = {}, {}
for b in json.load(open(bench))["benchmarks"]:
    if b.get("aggregate_name") == "median":
        scale = {"ns": 1, "us": 1e3, "ms": 1e6}[b["time_unit"]]
        if b["run_name"].startswith("spread/"):
            spread[b["run_name"][len("spread/"):]] = b
        else:
            ns[b["run_name"]] = b["cpu_time"] * scale
if not m4:
    sys.exit("no ICOUNT rom_frame lines in " + log)
print("| row | M4F instr/frame (float) | host ns/frame float | host ns/frame double |")
print("|---|---:|---:|---:|")
for label, n in m4.items():
    f32 = ns.get("float/" + label)
    f64 = ns.get("double/" + label)
    cell = lambda v: "-" if v is None else "%.0f" % v
    print("| %s | %d | %s | %s |" % (label, n, cell(f32), cell(f64)))
for label, n in fixed.items():
    print("| %s (q16.16) | %d | - | - |" % (label, n))
for title, rows in (("part of a seed-case1 frame", parts), ("part of a ratio-control frame", wparts)):
    if rows:
        print()
        print("| %s (float, M4F) | instructions |" % title)
        print("|---|---:|")
        for name, n in rows:
            print("| %s | %d |" % (name, n))
if runs:
    print()
    print("| scene, every frame of a run from its start (float, M4F) | frames | min | median | p99.9 | max | max / median |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for label, r in runs.items():
        e = exact.get(label)
        # The median and maximum frames counted exactly; the others within 5.
        med = e["median"] if e else r["median"]
        mx = e["max"] if e else r["max"]
        print("| %s | %d | %d | %d | %d | %d (frame %d) | %.3f |" % (label, r["frames"], r["min"], med, r["p999"], mx,
                                                                    r["max_frame"], mx / med))
if spread:
    print()
    print("| scene, 20,000 consecutive frames (double, host wall time) | median ns | p99 ns | p99.9 ns | max ns | p99 / median | p99.9 / median | max / median |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, b in spread.items():
        label = label.replace("/iterations:1", "")
        print("| %s | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %.2f |" % (
            label, b["median_ns"], b["p99_ns"], b["p999_ns"], b["max_ns"], b["p99_ns"] / b["median_ns"],
            b["p999_over_median"], b["max_over_median"]))
EOF
