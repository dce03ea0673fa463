#!/usr/bin/env bash
# The controller manoeuvre suite against the multibody reference on the
# production-like set (docs/validation.md#suite): every manoeuvre, the maps
# and the reference's uncertainty runs, the goal table and JSON. The
# reference's runs are cached in OUT_DIR/reference-cache, so a second run
# costs the plant's only. About 63 s of simulated reference with the maps
# and the `subset` uncertainty plan: at 5-7 s of CPU per simulated second,
# several minutes of CPU; run it with nice on a shared machine.
#
# Usage: bench/validation-suite.sh [BUILD_DIR] [OUT_DIR] [extra validate options...]
#   e.g. bench/validation-suite.sh build/host-release build/validation --uncertainty none
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/host-release}
out=${2:-build/validation}
shift $(( $# > 2 ? 2 : $# ))
. bench/build-host.sh
build_host "$build" cvtplant
cli=$build/tools/cvtplant
mkdir -p "$out"
"$cli" validate --suite controller --out-dir "$out" --json "$@" >"$out/suite-controller.json"
"$cli" validate --suite controller --out-dir "$out" "$@"
echo "JSON: $out/suite-controller.json" >&2
