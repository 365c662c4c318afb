#!/usr/bin/env bash
# Issue 22 item 6 on the emulated SCU (`cellctl emulate`, its pseudo-terminals): `scu move` beyond the
# axis's travel moves only when meant (--beyond-travel, confirmed by --yes) and never beyond the
# stroke; a move that ends short says its real cause — the advice of a higher --speed-mm-s only when
# the actuator did not move at all.
#
# usage: scu_move_limits_test.sh <cellctl binary> <cell config>
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 <cellctl binary> <cell config>" >&2
  exit 2
fi
cellctl=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-scu-move.XXXXXX")
emulate_log=$work/emulate.log
emulate_pid=""
cleanup() {
  if [[ -n $emulate_pid ]] && kill -0 "$emulate_pid" 2>/dev/null; then
    kill -TERM "$emulate_pid" 2>/dev/null || true
    wait "$emulate_pid" 2>/dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  [[ -s $emulate_log ]] && { echo "--- cellctl emulate output:" >&2; cat "$emulate_log" >&2; }
  exit 1
}

source "$(dirname "${BASH_SOURCE[0]}")/emulate_lib.sh"
publish_config "$2" "$work/emulated.yaml"
client_config "$work/emulated.yaml" "$work/cell.yaml"
start_emulate "$work/emulated.yaml"

out=""
# run_exits <code> <what> <cellctl arguments…>: the command must exit <code>; its output is kept in $out.
run_exits() {
  local expected=$1 what=$2 rc=0
  shift 2
  out=$("$cellctl" -c "$work/cell.yaml" "$@" 2>&1 </dev/null) || rc=$?
  printf '$ cellctl %s   (exit %d)\n%s\n' "$*" "$rc" "$out"
  [[ $rc -eq $expected ]] || fail "$what: \`cellctl $*\` exited $rc, expected $expected"
}
expect() { grep -Eq -- "$2" <<<"$out" || fail "$1: the output does not match /$2/"; }
refute() { grep -Eq -- "$2" <<<"$out" && fail "$1: the output matches /$2/"; return 0; }

# Axis x (actuator 1) travels 0 to 190 mm, its stroke is 200 mm. (The emulated plant may keep its
# positions between processes: compared before and after, not with a start position.)
position() { grep -E -o "^actuator 1 +-?[0-9.]+ mm" <<<"$out"; }
run_exits 0 "SCU status before" scu status
before=$(position)
run_exits 2 "beyond the travel" scu move --actuator 1 --position-mm 195 --speed-mm-s 20
expect "beyond the travel" "195 mm is beyond axis x's travel of 0 to 190 mm"
run_exits 0 "SCU status after the refusal" scu status
[[ $(position) == "$before" ]] || fail "the refused move moved actuator 1: $before, then $(position)"
run_exits 0 "beyond the travel, deliberately" scu move --actuator 1 --position-mm 195 --speed-mm-s 20 \
  --beyond-travel --yes
expect "beyond the travel, deliberately" "^function F1 +arrived"
run_exits 2 "beyond the stroke, deliberately" scu move --actuator 1 --position-mm 250 --beyond-travel --yes
expect "beyond the stroke" "250 mm is beyond actuator 1's stroke of 0 to 200 mm"
# Below the actuator's minimum speed (0.8 mm/s in the shipped cell) the motor does not turn.
run_exits 1 "too slow to move" scu move --actuator 1 --position-mm 100 --speed-mm-s 0.5
expect "too slow to move" "stopped short of the target .*it did not move: .*try a higher --speed-mm-s"
run_exits 0 "back" scu move --actuator 1 --position-mm 10 --speed-mm-s 20
refute "an arrival gives no advice" "speed-mm-s"
echo "PASS"
