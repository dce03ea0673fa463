#!/usr/bin/env bash
# Regenerates the cost table of docs/rom.md#cost and prints it as markdown:
# for every row of bench/cost_cases.hpp (each built-in
# scene at its real-time default, and each optional feature),
#   - Cortex-M4F instructions per 1 ms frame in float (QEMU icount; the
#     target test tests/target/test_rom_cost.cpp prints ICOUNT lines),
#   - host ns per frame in float and double (bench/bench_rom.cpp, median of
#     5 repetitions; this host is shared, so read ratios, not absolutes).
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
# target_tests keeps its console output (ICOUNT and HASH lines) in this log.
ctest --test-dir build/cortex-m4f -R '^target_tests$' --output-on-failure >&2
m4_log=build/cortex-m4f/tests/target/trace_hash.log

echo "building and running bench_rom in $host..." >&2
[ -f "$host/CMakeCache.txt" ] || cmake -S . -B "$host" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCVT_BUILD_BENCH=ON >&2
cmake --build "$host" --target bench_rom >&2
"$host/bench/bench_rom" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_format=json >"$work/bench.json"

python3 - "$m4_log" "$work/bench.json" <<'EOF'
import json, sys
log, bench = sys.argv[1], sys.argv[2]
m4, parts, fixed = {}, [], {}
for line in open(log, errors="replace"):
    f = line.split()
    if len(f) == 5 and f[:3] == ["ICOUNT", "rom_frame", "float"]:
        m4[f[3]] = int(f[4])
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_frame", "q16_16"]:
        fixed[f[3]] = int(f[4])
    elif len(f) == 5 and f[:3] == ["ICOUNT", "rom_part", "float"]:
        parts.append((f[3], int(f[4])))
ns = {}
for b in json.load(open(bench))["benchmarks"]:
    if b.get("aggregate_name") == "median":
        scale = {"ns": 1, "us": 1e3, "ms": 1e6}[b["time_unit"]]
        ns[b["run_name"]] = b["real_time"] * scale
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
if parts:
    print()
    print("| part of a seed-case1 frame (float, M4F) | instructions |")
    print("|---|---:|")
    for name, n in parts:
        print("| %s | %d |" % (name, n))
EOF
