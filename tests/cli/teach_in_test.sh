#!/bin/bash
# Issue 10 parts 4 and 5 as a user meets them, each scenario on its own copy of the cell config with
# its own encoder EEPROM file in a fresh folder (nothing shared in /tmp):
#  - `cellctl teach-in x` in virtual time: taught, verified, written into the dry run's copy of the
#    config (the cell's config untouched), and a run of the demo on that copy completes;
#  - the same with an injected SCU fault during the travel: exit 1, config and EEPROM untouched;
#  - an encoder preset since the config was written (its EEPROM holds offset 1000): the run is refused
#    at start with both values and what to do; with preset_offset: 1000 recorded, it runs.
# usage: teach_in_test.sh CELLCTL CONFIG RECIPE WORKDIR
set -u
cellctl=$1 source_config=$2 recipe=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# own_config NAME: the shipped cell with its encoder EEPROM in NAME's folder.
own_config() {
  mkdir -p "$work/$1"
  sed -E "s|^(    state_file:).*|\1 $work/$1/encoder.eeprom|" "$source_config" >"$work/$1/cell.yaml"
  grep -q "state_file: $work/$1/encoder.eeprom" "$work/$1/cell.yaml" || fail "no state_file to move"
  cp "$work/$1/cell.yaml" "$work/$1/cell.orig.yaml"
  echo "$work/$1/cell.yaml"
}

# 1. Teach-In end to end, rehearsed: taught, verified, written into the dry run's copy of the config
#    (issue 22: a dry run never writes the cell's config), and the demo runs on that copy.
config=$(own_config taught)
taught="$work/taught/state/config.dry-run.yaml"
"$cellctl" -c "$config" teach-in x --distance 100 --from 5 --virtual-time --yes --journal "$work/taught/j" \
  --state-dir "$work/taught/state" >"$work/taught/out.txt" 2>&1
rc=$?
[ "$rc" -eq 0 ] || fail "teach-in exits $rc: $(tail -5 "$work/taught/out.txt")"
grep -q "verified: moving back, the encoder measured 100.0" "$work/taught/out.txt" || fail "no verification said"
cmp -s "$config" "$work/taught/cell.orig.yaml" || fail "a dry-run Teach-In changed the cell's config"
[ -e "$config.bak" ] && fail "a backup of the cell's config was written"
grep -Eq "^  measuring_units: [0-9]+$" "$taught" || fail "measuring_units not written: $(grep -A20 '^encoder:' "$taught")"
grep -q "^  counts_per_mm: 1000$" "$taught" || fail "counts_per_mm not written"
grep -q "^  units_select: per_total_range$" "$taught" || fail "units_select not written"
grep -q "^  mm_per_revolution:" "$taught" && fail "mm_per_revolution left beside counts_per_mm"
grep -q "encoder.measuring_units: (none) → " "$work/taught/out.txt" || fail "the change is not printed"
ls "$work/taught/state/" | grep -q "\.new-" && fail "a temporary file was left"
grep -Eq "^taught_units [1-9][0-9]+$" "$work/taught/encoder.eeprom" || fail "the encoder kept no Teach-In"
"$cellctl" -c "$taught" run "$recipe" --virtual-time --journal "$work/taught/run" --state-dir "$work/taught/state" \
  >"$work/taught/run.txt" 2>&1 || fail "the demo on the taught config fails: $(tail -5 "$work/taught/run.txt")"

# 2. A fault during the travel: nothing written, the encoder as it was.
config=$(own_config fault)
"$cellctl" -c "$config" teach-in x --distance 100 --from 5 --virtual-time --yes --journal "$work/fault/j" \
  --fault scu:error@8 >"$work/fault/out.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "teach-in stopped by a fault exits $rc, not 1"
grep -q "Teach-In failed: stopped by the monitor" "$work/fault/out.txt" || fail "no reason: $(tail -3 "$work/fault/out.txt")"
grep -q "the encoder's configured parameters are restored" "$work/fault/out.txt" || fail "restore not said"
cmp -s "$config" "$work/fault/cell.orig.yaml" || fail "the config changed after a failed Teach-In"
[ -e "$config.bak" ] && fail "a backup was written although nothing changed"
[ ! -e "$work/fault/encoder.eeprom" ] || ! grep -Eq "^(offset|taught_units) [1-9-]" "$work/fault/encoder.eeprom" ||
  fail "the encoder's EEPROM changed: $(cat "$work/fault/encoder.eeprom")"

# 3. A preset the config does not know: refused at start, with the reason; recorded, it runs.
config=$(own_config preset)
printf 'offset 1000\ncode_sequence cw\ntaught_units 0\naddress 0\n' >"$work/preset/encoder.eeprom"
"$cellctl" -c "$config" run "$recipe" --virtual-time --journal "$work/preset/refused" >"$work/preset/refused.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "a run with an unrecorded preset exits $rc, not 1"
grep -q "the encoder holds preset offset 1000 .* this config expects encoder.preset_offset: 0" \
  "$work/preset/refused.txt" || fail "the refusal does not say why: $(tail -5 "$work/preset/refused.txt")"
grep -q "16373\|1637[0-9]\.[0-9]* mm" "$work/preset/refused.txt" && fail "a wrapped position reached the operator"
sed -i 's/^encoder:$/encoder:\n  preset_offset: 1000/' "$config"
"$cellctl" -c "$config" run "$recipe" --virtual-time --journal "$work/preset/run" >"$work/preset/run.txt" 2>&1 ||
  fail "the run with the preset recorded fails: $(tail -5 "$work/preset/run.txt")"
echo "teach-in and encoder zero scenarios: OK"
