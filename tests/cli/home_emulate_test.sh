#!/usr/bin/env bash
# Homed is a fact the next process checks — three processes over pseudo-terminals, as an operator
# works: `cellctl emulate` in the background (its SCU, like one just powered up, has no actuator
# initialised); `cellctl run` of a recipe that requires x homed is refused before any motion, with the
# reason; `cellctl home --yes` homes every axis and writes the home record; the same `cellctl run` then
# completes. Without --yes and without a terminal to ask on, `cellctl home` refuses (exit 2).
#
# usage: home_emulate_test.sh <cellctl binary> <cell config>
# Everything (published pseudo-terminals, encoder EEPROM, state folder, run records) lives in a fresh
# temp dir.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 <cellctl binary> <cell config>" >&2
  exit 2
fi
cellctl=$1
source_config=$2

work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-home.XXXXXX")
emulated=$work/emulated.yaml  # the cell for `cellctl emulate`: publishes into $work
config=$work/cell.yaml        # the cell for home and run: its ports are those pseudo-terminals
emulate_log=$work/emulate.log
emulate_pid=""

cleanup() {
  if [[ -n $emulate_pid ]] && kill -0 "$emulate_pid" 2>/dev/null; then
    kill -INT "$emulate_pid" 2>/dev/null || true
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
publish_config "$source_config" "$emulated"
# The shipped config leaves state_dir to its default: this test's own, whether one was named or not.
sed -i -E "/^state_dir:/d" "$emulated"
echo "state_dir: $work/state" >>"$emulated"
client_config "$emulated" "$config"
grep -q "^state_dir: $work/state" "$config" || fail "could not move state_dir into $work"

cat >"$work/requires-x.yaml" <<'RECIPE'
recipe: {name: requires-x, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
steps:
  - require: {homed: [x]}
  - move: {to: {x: 20}, speed_mm_s: 10}
RECIPE

start_emulate "$emulated"

out=""
run_exits() {
  local expected=$1
  shift
  local rc=0
  out=$(timeout 120 "$cellctl" -c "$config" "$@" </dev/null 2>&1) || rc=$?
  printf '$ cellctl %s   (exit %d)\n%s\n' "$*" "$rc" "$out"
  [[ $rc -eq $expected ]] || fail "\`cellctl $*\` exited $rc, expected $expected"
}

# 1. Before homing: refused before any motion, with the reason.
run_exits 1 run "$work/requires-x.yaml" --journal "$work/run-before"
grep -q "failed step: axis x has no home record: home it first (cellctl home x)" <<<"$out" ||
  fail "the run before homing did not say why it was refused"
python3 - "$work/run-before/journal.jsonl" <<'PY' || fail "the refused run moved x"
import json, sys
samples = [json.loads(l) for l in open(sys.argv[1]) if '"sample"' in l]
assert samples, "no samples"
assert all(abs(s["scu_mm"][0]) < 0.01 for s in samples), "x moved"
PY

# 2. No terminal and no --yes: nothing is asked, nothing moves.
run_exits 2 home
grep -q "add --yes to home from a script" <<<"$out" || fail "home without --yes did not say how"

# 3. Homing, confirmed by --yes: progress per axis and phase, the record written.
run_exits 0 home --yes --journal "$work/home"
grep -q "x (sequence 0): end position" <<<"$out" || fail "home did not list what x will do"
grep -q "note: home x: encoder preset to 0.000 mm, reads 0.000 mm" <<<"$out" || fail "no preset read back shown"
grep -q "note: home z: homed" <<<"$out" || fail "z was not homed"
grep -q "home record written: $work/state/home.json" <<<"$out" || fail "the home record was not written"
[[ -f $work/home/home.yaml && -f $work/home/plot.svg ]] || fail "the homing run has no recipe or plot in its record"

# 4. The same run as in 1, in a new process: the record holds against the devices.
run_exits 0 run "$work/requires-x.yaml" --journal "$work/run-after"
grep -q "outcome: complete" <<<"$out" || fail "the run after homing did not complete"

kill -INT "$emulate_pid"
wait "$emulate_pid" || fail "cellctl emulate did not end cleanly on Ctrl-C"
emulate_pid=""
echo "PASS"
