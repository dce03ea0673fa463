#!/bin/bash
# Command-line contract of cvtplant-reference-bridge and of what cosim adds to
# cvtplant-sil (--plant reference, --plant-option, compare; docs/sil.md#cli):
# --help exits 0; a bad flag or value gives exactly one line on stderr and
# exit 2; an interface that cannot be opened or an output that cannot be
# written gives exit 1.
#   check_cli.sh REFERENCE_BRIDGE SIL
set -u
REF=$1 SIL=$2
rc=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck source=/dev/null
source "$(dirname "$0")/../../tests/support/cli_expect.sh"
expect 0 "$REF" --help
expect 2 "$REF" --bogus
expect 2 "$REF" --rtol 0
expect 2 "$REF" --rtol 1e-3x
expect 2 "$REF" --ledger-tol -1
expect 2 "$REF" --max-steps-per-frame 0
expect 2 "$REF" --inject-fault ledger
expect 2 "$REF" --inject-fault melted@1
expect 2 "$REF" --inject-fault none@1
expect 2 "$REF" --inject-fault ledger@-1
expect 2 "$REF" --scene no-such-scene
expect 2 "$REF" --release-cache
expect 1 "$REF" --iface nosuchcan0
expect 0 "$SIL" compare --help
expect 2 "$SIL" run --loopback --plant nope
expect 2 "$SIL" run --loopback --plant reference --plant-option rtol=fast
expect 2 "$SIL" run --loopback --plant reference --plant-option gears=3
expect 2 "$SIL" run --loopback --plant-option rtol=1e-6
expect 2 "$SIL" run --iface nosuchcan0 --plant reference --plant-option rtol=1e-6
expect 2 "$SIL" bench --loopback --plant reference
expect 2 "$SIL" run --loopback --plant reference --scenario tip-in --t-end 0.5
expect 2 "$SIL" compare --bogus
expect 2 "$SIL" compare --scenario nope
expect 2 "$SIL" compare --t-end 0.5 --scenario tip-in
expect 2 "$SIL" compare --rtol 2
expect 2 "$SIL" compare --out
: > "$tmp/file"
expect 1 "$SIL" compare --scenario tip-in --out "$tmp/file/sub" --no-report
# --help lists the plants this build has and their options.
if "$SIL" --help | grep -q '^  reference ' && "$SIL" --help | grep -q 'rtol=R'; then
  echo "ok: cvtplant-sil --help lists the plant reference and its options"
else
  echo "FAIL: cvtplant-sil --help does not list the plant reference"; rc=1
fi
exit $rc
