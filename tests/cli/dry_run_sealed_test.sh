#!/usr/bin/env bash
# Issue 22 item 1: a dry run never writes the cell's files. Every command of the first-day walk-through
# that could write, run as a rehearsal, leaves the config byte for byte as it was:
#  - on the shipped (emulated) cell and on the hardware example (real ports): `teach-in --virtual-time
#    --yes`, `home --virtual-time --yes`, `run --virtual-time`; the Teach-In's result is in the dry
#    run's copy, <state_dir>/config.dry-run.yaml;
#  - on the hardware example, reached on `cellctl emulate`'s pseudo-terminal (--port): `encoder
#    preset`, `encoder direction`, `encoder set-address`; their change in the dry run's copy too.
#
# usage: dry_run_sealed_test.sh <cellctl binary> <config/cell.yaml> <config/examples/cell-hardware.yaml> <recipe>
set -euo pipefail
cellctl=$1 recipe=$4
work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-dry-run-sealed.XXXXXX")
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

# own_cell SOURCE NAME: SOURCE in $work/NAME/cell.yaml, its encoder EEPROM and state folder beside it;
# cell.orig.yaml is the copy every command is compared with.
own_cell() {
  mkdir -p "$work/$2"
  sed -E "s|^(    state_file:).*|\1 $work/$2/encoder.eeprom|" "$1" >"$work/$2/cell.yaml"
  printf '\nstate_dir: %s/%s/state\n' "$work" "$2" >>"$work/$2/cell.yaml"
  cp "$work/$2/cell.yaml" "$work/$2/cell.orig.yaml"
}
# unchanged NAME <cellctl arguments…>: the command exits 0 and NAME's config is as it was.
unchanged() {
  local name=$1 rc=0 out
  shift
  out=$("$cellctl" -c "$work/$name/cell.yaml" "$@" 2>&1 </dev/null) || rc=$?
  printf '$ cellctl -c %s/cell.yaml %s   (exit %d)\n%s\n' "$name" "$*" "$rc" "$(tail -4 <<<"$out")"
  [[ $rc -eq 0 ]] || fail "\`cellctl $*\` exited $rc: $out"
  cmp "$work/$name/cell.orig.yaml" "$work/$name/cell.yaml" ||
    fail "\`cellctl $*\` changed the $name config: $(diff "$work/$name/cell.orig.yaml" "$work/$name/cell.yaml")"
  [[ ! -e $work/$name/cell.yaml.bak ]] || fail "\`cellctl $*\` made a backup of the $name config"
}

own_cell "$2" emulated
own_cell "$3" hardware
for name in emulated hardware; do
  unchanged "$name" teach-in x --distance 100 --from 5 --virtual-time --yes --journal "$work/$name/teach-in"
  grep -Eq "^  measuring_units: [0-9]+$" "$work/$name/state/config.dry-run.yaml" ||
    fail "the Teach-In's result is not in $name's config.dry-run.yaml"
  unchanged "$name" home --virtual-time --yes --journal "$work/$name/home"
  unchanged "$name" run "$recipe" --virtual-time --journal "$work/$name/run"
done

# The encoder commands of the walk-through's first step, on `cellctl emulate` (the shipped cell's
# emulators) reached with --port from the hardware config.
publish_config "$2" "$work/emulate.yaml"
start_emulate "$work/emulate.yaml"
rm -f "$work/hardware/state/config.dry-run.yaml"
unchanged hardware encoder preset 1000 --port "$work/encoder"
grep -Eq "^  preset_offset: -?[0-9]+$" "$work/hardware/state/config.dry-run.yaml" ||
  fail "the preset is not in the dry run's copy"
unchanged hardware encoder direction cw --port "$work/encoder"
grep -q "^  code_sequence: cw$" "$work/hardware/state/config.dry-run.yaml" ||
  fail "the direction is not in the dry run's copy"
# No encoder at station 126 (the emulator keeps its address): refused, exit 4 — and nothing written.
rc=0
"$cellctl" -c "$work/hardware/cell.yaml" encoder set-address 7 --port "$work/encoder" --timeout 2 \
  </dev/null >"$work/set-address.txt" 2>&1 || rc=$?
[[ $rc -eq 4 ]] || fail "set-address exited $rc: $(cat "$work/set-address.txt")"
cmp "$work/hardware/cell.orig.yaml" "$work/hardware/cell.yaml" || fail "set-address changed the config"
echo "a dry run never writes the cell's files: OK"
