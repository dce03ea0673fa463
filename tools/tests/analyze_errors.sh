#!/usr/bin/env bash
# CLI contract of `cvtplant analyze` / `cvtplant lyapunov` (docs/analysis.md#cli):
# bad input -> exit 2 with a one-line message that names the problem;
# good input -> exit 0 and the documented JSON fields.
set -u
BIN="$1"
TMP="$2"
SRC="$(cd "$(dirname "$0")/../.." && pwd)"  # the source tree, for the example scene files
mkdir -p "$TMP"
fail=0

expect() {  # expect CODE PATTERN -- command...
  local code="$1" pattern="$2"
  shift 3
  local out rc
  out=$("$@" 2>&1 >/dev/null)
  rc=$?
  if [ "$rc" != "$code" ]; then
    echo "FAIL (exit $rc, want $code): $*"; echo "  stderr: $out"; fail=1; return
  fi
  if [ -n "$pattern" ] && ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL (message lacks /$pattern/): $*"; echo "  stderr: $out"; fail=1; return
  fi
  if [ "$code" = 2 ] && [ "$(printf '%s\n' "$out" | wc -l)" != 1 ]; then
    echo "FAIL (error is not one line): $*"; echo "  stderr: $out"; fail=1; return
  fi
  echo "ok: $*"
}

# Good series: a sine, 2000 samples.
awk 'BEGIN{print "t,s"; for(i=0;i<2000;i++) printf "%d,%.10f\n", i, sin(i*0.17)}' > "$TMP/sine.csv"
# Non-numeric cell on line 5 (header is line 1).
awk 'BEGIN{print "t,s"; for(i=0;i<2000;i++) { if(i==3) print "3,abc"; else printf "%d,%.10f\n", i, sin(i*0.17)}}' > "$TMP/bad_cell.csv"
awk 'BEGIN{print "t,s"; for(i=0;i<2000;i++) { if(i==10) print "10,nan"; else printf "%d,%.10f\n", i, sin(i*0.17)}}' > "$TMP/nan.csv"
awk 'BEGIN{print "t,s"; for(i=0;i<2000;i++) print i ",1.5"}' > "$TMP/const.csv"
awk 'BEGIN{print "t,s"; for(i=0;i<20;i++) printf "%d,%.10f\n", i, sin(i*0.17)}' > "$TMP/short.csv"

for tool in ami fnn cao lle rqa test01 classify recurrence figures; do
  extra=()
  [ "$tool" = recurrence ] && extra=(--png "$TMP/bad.png")
  [ "$tool" = figures ] && extra=(--out-dir "$TMP/bad_fig")
  expect 2 "no column 'missing'.*columns: t, s" -- "$BIN" analyze $tool --csv "$TMP/sine.csv" --column missing "${extra[@]}"
  expect 2 "bad_cell.csv:5: column 's': 'abc' is not a number" -- "$BIN" analyze $tool --csv "$TMP/bad_cell.csv" --column s "${extra[@]}"
  expect 2 "nan.csv:12: column 's': NaN" -- "$BIN" analyze $tool --csv "$TMP/nan.csv" --column s "${extra[@]}"
  expect 2 "constant" -- "$BIN" analyze $tool --csv "$TMP/const.csv" --column s "${extra[@]}"
  expect 2 "too few points" -- "$BIN" analyze $tool --csv "$TMP/short.csv" --column s "${extra[@]}"
done
expect 2 "column is required" -- "$BIN" analyze figures --csv "$TMP/sine.csv" --out-dir "$TMP/bad_fig"
expect 2 "give --csv" -- "$BIN" analyze figures --out-dir "$TMP/bad_fig"

# seed-section4 and the ROM lyapunov scenes (docs/analysis.md#seed-section4, #rom-lyapunov).
expect 2 "'nope' is neither a built-in scene" -- "$BIN" analyze seed-section4 --scene nope --out-dir "$TMP/s4"
expect 2 "unknown signal 'torque'" -- "$BIN" analyze seed-section4 --scene seed-case1 --signals torque --out-dir "$TMP/s4"
expect 2 "leaves no data" -- "$BIN" analyze seed-section4 --scene seed-case1 --t-end 1 --t-transient 5 --out-dir "$TMP/s4"
expect 2 "--tau: .0. is outside 1..100000" -- "$BIN" analyze seed-section4 --scene seed-case1 --tau 0 --out-dir "$TMP/s4"
expect 2 "--t-end: .-3. is outside \\(0, 100000\\]" -- "$BIN" analyze seed-section4 --scene seed-case1 --t-end -3 --out-dir "$TMP/s4"
expect 2 "expected 6 comma-separated values" -- "$BIN" lyapunov --scene seed-case1 --x0 1,2 --t-end 1  # the tension plant on fixed sheaves
expect 2 "no parameter 'clamp'" -- "$BIN" lyapunov --scene seed-case2 --param clamp=3000 --t-end 1
expect 2 "clamp" -- "$BIN" lyapunov --scene seed-case1 --param clamp_N=-1 --t-end 1
# Any plant scene, built-in or a file, is a model if its inputs are constant.
expect 2 "tau_in varies in time; the spectrum tools need constant inputs" -- "$BIN" lyapunov --scene tip-in --t-end 1
expect 2 "varies in time" -- "$BIN" lyapunov --scene "$SRC/tools/scenes/vehicle-launch.toml" --t-end 1
expect 2 "unknown scene 'nope.toml'" -- "$BIN" analyze trajectory --scene nope.toml --t-end 1

# --help on every subcommand: exit 0, a usage text that lists the options.
for sub in "lyapunov" "analyze" "analyze ami" "analyze fnn" "analyze cao" "analyze lle" "analyze rqa" \
           "analyze recurrence" "analyze test01" "analyze classify" "analyze trajectory" "analyze sweep" \
           "analyze merge" "analyze figures" "analyze seed-section4"; do
  # shellcheck disable=SC2086
  out=$("$BIN" $sub --help 2>&1)
  rc=$?
  if [ "$rc" = 0 ] && grep -q "Usage" <<<"$out" && grep -q -- "--help" <<<"$out"; then
    echo "ok: $sub --help"
  else
    echo "FAIL: $sub --help (exit $rc)"; fail=1
  fi
done

# figures from a series: the documented PNGs, each a PNG.
if "$BIN" analyze figures --csv "$TMP/sine.csv" --column s --out-dir "$TMP/fig" >/dev/null; then
  for f in time_history delay_reconstruction ami fnn divergence recurrence; do
    head -c 8 "$TMP/fig/$f.png" 2>/dev/null | od -An -c | grep -q "P   N   G" && echo "ok: figures $f.png" ||
      { echo "FAIL: figures $f.png"; fail=1; }
  done
else
  echo "FAIL: analyze figures on a sine"; fail=1
fi
expect 2 "cannot read" -- "$BIN" analyze fnn --csv "$TMP/does_not_exist.csv" --column s
expect 2 "too few points" -- "$BIN" analyze lle --csv "$TMP/sine.csv" --column s --m 10 --tau 210
expect 2 "" -- "$BIN" analyze lle --csv "$TMP/sine.csv" --column s --method foo
expect 2 "unknown scene 'nope'" -- "$BIN" lyapunov --scene nope --t-end 10
expect 2 "expected 3 comma-separated values" -- "$BIN" lyapunov --scene lorenz --x0 1,2 --t-end 10
expect 2 "no parameter 'rhoo'" -- "$BIN" lyapunov --scene lorenz --param rhoo=28 --t-end 10
expect 2 "--t-end: .0. is outside \\(0, 1e\\+09\\]" -- "$BIN" lyapunov --scene lorenz --t-end 0
expect 1 "non-finite" -- "$BIN" lyapunov --scene lorenz --dt 1 --t-end 100
expect 2 "n must be an integer" -- "$BIN" analyze sweep --scene logistic --axis r=3:4:2.5
expect 2 "--shard .3/2.: .3. is outside 0..1" -- "$BIN" analyze sweep --scene logistic --axis r=3:4:4 --shard 3/2

# Good paths produce the documented fields.
out=$("$BIN" analyze classify --csv "$TMP/sine.csv" --column s --json) || { echo "FAIL classify sine"; fail=1; }
grep -q '"classification": "periodic"' <<<"$out" && echo "ok: sine -> periodic" || { echo "FAIL: sine not periodic: $out"; fail=1; }
out=$("$BIN" lyapunov --scene henon --t-end 100000 --json) || { echo "FAIL lyapunov henon"; fail=1; }
grep -q '"exponents"' <<<"$out" && grep -q '"ci"' <<<"$out" && echo "ok: lyapunov json" || { echo "FAIL: lyapunov json"; fail=1; }
"$BIN" analyze recurrence --csv "$TMP/sine.csv" --column s --png "$TMP/rp.png" >/dev/null &&
  head -c 8 "$TMP/rp.png" | od -An -c | grep -q "P   N   G" && echo "ok: recurrence png" || { echo "FAIL: recurrence png"; fail=1; }

# Sharded sweep + merge equals the unsharded sweep; a missing shard is refused.
"$BIN" analyze sweep --scene logistic --axis r=3.4:4:7 --t-end 2000 --out "$TMP/all.csv" --jobs 2 || fail=1
"$BIN" analyze sweep --scene logistic --axis r=3.4:4:7 --t-end 2000 --shard 0/2 --out "$TMP/s0.csv" || fail=1
"$BIN" analyze sweep --scene logistic --axis r=3.4:4:7 --t-end 2000 --shard 1/2 --out "$TMP/s1.csv" || fail=1
"$BIN" analyze merge "$TMP/s1.csv" "$TMP/s0.csv" --out "$TMP/merged.csv" || fail=1
cmp -s "$TMP/all.csv" "$TMP/merged.csv" && echo "ok: shards merge to the full sweep" || { echo "FAIL: merged != full"; fail=1; }
expect 2 "points missing" -- "$BIN" analyze merge "$TMP/s0.csv"
"$BIN" analyze sweep --scene logistic --axis r=3.4:4:8 --t-end 2000 --shard 1/2 --out "$TMP/other.csv" || fail=1
expect 2 "different sweep" -- "$BIN" analyze merge "$TMP/s0.csv" "$TMP/other.csv"

exit $fail
