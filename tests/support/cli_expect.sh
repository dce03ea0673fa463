# The command-line contract checks shared by the programs' check_cli.sh
# scripts (docs/cli.md#conventions): `expect STATUS CMD...` runs CMD, wants
# exit STATUS and, for a refusal (2), exactly one line on stderr; a miss is
# printed as FAIL and sets rc=1. Source it; the caller sets rc=0 first.
expect() {  # want_status, cmd...
  local want=$1; shift
  local err; err=$("$@" 2>&1 >/dev/null); local got=$?
  local lines; lines=$(printf '%s' "$err" | grep -c '')
  if [ "$got" != "$want" ]; then echo "FAIL: $* -> exit $got, want $want ($err)"; rc=1; return; fi
  if [ "$want" = 2 ] && [ "$lines" != 1 ]; then echo "FAIL: $* -> $lines stderr lines, want 1"; rc=1; return; fi
  echo "ok: $* -> $got${err:+: $err}"
}
