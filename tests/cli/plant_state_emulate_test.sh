#!/usr/bin/env bash
# The emulated plant keeps its state between emulations, as a powered cell does (issue 22, item 2):
# `cellctl emulate` homes (through a client `cellctl home --yes`), ends; a new `cellctl emulate` of the
# same state folder still has the actuators initialised where homing left them, so a recipe that
# requires x homed completes in another process. Losing power is deliberate: `cellctl emulate
# --power-cycle` starts with no actuator initialised, and the same run is refused with its reason.
#
# usage: plant_state_emulate_test.sh <cellctl binary> <cell config>
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 <cellctl binary> <cell config>" >&2
  exit 2
fi
cellctl=$1
source_config=$2

work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-plant.XXXXXX")
emulated=$work/emulated.yaml
config=$work/cell.yaml
emulate_log=$work/emulate.log
emulate_pid=""

stop_emulate() {
  if [[ -n $emulate_pid ]] && kill -0 "$emulate_pid" 2>/dev/null; then
    kill -INT "$emulate_pid" 2>/dev/null || true
    wait "$emulate_pid" 2>/dev/null || true
  fi
  emulate_pid=""
}
cleanup() {
  stop_emulate
  [[ -n ${KEEP:-} ]] || rm -rf "$work"
}
trap cleanup EXIT

fail() {
  echo "FAIL: $*" >&2
  [[ -s $emulate_log ]] && { echo "--- cellctl emulate output:" >&2; cat "$emulate_log" >&2; }
  exit 1
}

source "$(dirname "${BASH_SOURCE[0]}")/emulate_lib.sh"
publish_config "$source_config" "$emulated"
# The state folder in $work (added when the config leaves it at its default).
if grep -q "^state_dir:" "$emulated"; then
  sed -i -E "s|^state_dir:.*|state_dir: $work/state|" "$emulated"
else
  echo "state_dir: $work/state" >>"$emulated"
fi
client_config "$emulated" "$config"

cat >"$work/requires-x.yaml" <<'RECIPE'
recipe: {name: requires-x, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
steps:
  - require: {homed: [x]}
  - move: {to: {x: 20}, speed_mm_s: 10}
RECIPE

out=""
run_exits() {
  local expected=$1
  shift
  local rc=0
  out=$(timeout 120 "$cellctl" -c "$config" "$@" </dev/null 2>&1) || rc=$?
  printf '$ cellctl %s   (exit %d)\n%s\n' "$*" "$rc" "$out"
  [[ $rc -eq $expected ]] || fail "\`cellctl $*\` exited $rc, expected $expected"
}

# 1. Home on one emulation, then end it (Ctrl-C): its plant is kept in the state folder.
start_emulate "$emulated"
grep -q "^plant    $work/state/plant.dry-run.json" "$emulate_log" || fail "emulate did not name its plant state"
run_exits 0 home --yes --journal "$work/home"
stop_emulate
python3 - "$work/state/plant.dry-run.json" <<'PY' || fail "the plant state does not hold x and z homed"
import json, sys
s = json.load(open(sys.argv[1]))
acts = {a["actuator"]: a for a in s["scu_actuators"]}
assert acts[1]["initialised"] and acts[2]["initialised"], acts
assert abs(acts[1]["position_mm"] - 5.0) < 0.2, acts
PY

# 2. A new emulation, still powered: the run that requires x homed completes in a new process.
start_emulate "$emulated"
run_exits 0 run "$work/requires-x.yaml" --journal "$work/run-powered"
grep -q "outcome: complete" <<<"$out" || fail "the run on the still-powered plant did not complete"
stop_emulate

# 3. A deliberate power cycle: nothing initialised, the same run refused with its reason.
"$cellctl" -c "$emulated" emulate --power-cycle >"$emulate_log" 2>&1 &
emulate_pid=$!
for _ in $(seq 100); do
  grep -q "Ctrl-C ends the emulation" "$emulate_log" && break
  kill -0 "$emulate_pid" 2>/dev/null || fail "cellctl emulate --power-cycle exited"
  sleep 0.1
done
grep -q "after a power cycle: no actuator initialised" "$emulate_log" || fail "emulate --power-cycle did not say so"
run_exits 1 run "$work/requires-x.yaml" --journal "$work/run-power-cycled"
grep -q "the SCU reports actuator 1 not initialised (power loss or reset since homing)" <<<"$out" ||
  fail "the run after a power cycle was not refused for the lost initialisation"
stop_emulate
echo "PASS"
