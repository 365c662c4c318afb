#!/bin/bash
# Issue 22 item 2, the workflow "home once, run recipe after recipe" rehearsed across processes: each
# dry run (--virtual-time) starts from the emulated plant the last one left in the state folder, as a
# powered cell would, so a `require: homed` recipe refuses before homing, runs after it in the next
# process, and refuses again once the plant has lost its power (--power-cycle).
# usage: dry_run_homed_test.sh CELLCTL CONFIG WORKDIR
set -u
cellctl=$1 source_config=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

config="$work/cell.yaml"
sed -E "s|^(    state_file:).*|\1 $work/encoder.eeprom|" "$source_config" >"$config"
sed -i -E "/^state_dir:/d" "$config"
echo "state_dir: $work/state" >>"$config"
cat >"$work/requires-x.yaml" <<'RECIPE'
recipe: {name: requires-x, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
steps:
  - {name: check homed, require: {homed: [x]}}
  - {name: out, move: {to: {x: 30}, speed_mm_s: 12}}
RECIPE

run() {  # run NAME [ARGS…]: the recipe in virtual time; its exit status, its output in NAME.txt
  local name=$1
  shift
  "$cellctl" -c "$config" run "$work/requires-x.yaml" --virtual-time --journal "$work/$name" "$@" \
    >"$work/$name.txt" 2>&1
}

run before
rc=$?
[ "$rc" -eq 1 ] || fail "a require: homed run before any homing exits $rc, not 1"
grep -q "failed step: axis x" "$work/before.txt" || fail "no reason: $(grep -m3 'fail' "$work/before.txt")"

"$cellctl" -c "$config" home x --virtual-time --yes --journal "$work/home" >"$work/home.txt" 2>&1 ||
  fail "home exits $?: $(tail -3 "$work/home.txt")"
[ -s "$work/state/plant.dry-run.json" ] || fail "the dry run kept no emulated plant"

run after
rc=$?
[ "$rc" -eq 0 ] || fail "homed in the last process, the run exits $rc: $(grep -m2 'failed step' "$work/after.txt")"
grep -q "outcome: complete" "$work/after.txt" || fail "not complete"

run again
[ $? -eq 0 ] || fail "a second run on the same homed plant fails: $(grep -m2 'failed step' "$work/again.txt")"

run power_cycled --power-cycle
rc=$?
[ "$rc" -eq 1 ] || fail "after a power cycle the run exits $rc, not 1"
grep -q "not initialised (power loss or reset since homing)" "$work/power_cycled.txt" ||
  fail "no power-loss reason: $(grep -m2 'failed step' "$work/power_cycled.txt")"
echo "home once, then run after run across processes; a power cycle loses the home — passed"
