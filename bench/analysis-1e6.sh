#!/usr/bin/env bash
# The time-series estimators at 10^6 samples (docs/analysis.md#benchmarks):
# one benchmark per process, so each peak RSS is its own; CPU time (user) and
# peak RSS from /usr/bin/time -v, the measures from the benchmark's counters.
#   bench/analysis-1e6.sh [build dir, default build/host-release]
set -euo pipefail
B=${1:-build/host-release}/bench/bench_analysis
[ -x "$B" ] || { echo "no $B: cmake --build --preset host-release --target bench_analysis" >&2; exit 2; }
echo "load: $(uptime | sed 's/.*load average/load average/')"
printf '%-32s %10s %10s %12s  %s\n' benchmark user_s wall_s peak_rss_MB counters
for f in BM_Fnn/1000000 BM_Rqa_stream/1000000 BM_Rqa_stream_rr2/1000000 BM_Rqa_stream/100000 BM_Rqa_kdtree/100000 \
         BM_Rqa_stream_rr2/100000 BM_Rqa_kdtree_rr2/100000; do
  log=$(mktemp)
  /usr/bin/time -v "$B" --benchmark_filter="^$f/" --benchmark_counters_tabular=false >"$log" 2>&1
  user=$(awk -F': ' '/User time/ {print $2}' "$log")
  wall=$(awk -F': ' '/Elapsed \(wall/ {print $2}' "$log")
  rss=$(awk -F': ' '/Maximum resident/ {printf "%.0f", $2 / 1024}' "$log")
  counters=$(grep -E "^$f/" "$log" | sed -E 's/^[^ ]+ +[0-9.]+ ms +[0-9.]+ ms +[0-9]+ *//')
  printf '%-32s %10s %10s %12s  %s\n' "$f" "$user" "$wall" "$rss" "$counters"
  rm -f "$log"
done
