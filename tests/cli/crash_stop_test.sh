#!/usr/bin/env bash
# A crash still stops the cell: `cellctl emulate` publishes the three devices' pseudo-terminals (with
# --trace: every telegram they receive is logged), a second cellctl runs a recipe against them as
# against hardware, and once the spindle turns and x moves it is sent a fatal signal. The dying
# process must write the SCU's F20 (every actuator stops) and the converter's CMD System Stopp to the
# ports — the converter has no communication watchdog — and the emulated devices must have received
# them: the SCU's actuators stop and the spindle runs down, long before any time-out of the SCU's own.
#
# usage: crash_stop_test.sh <cellctl binary> <cell config> <signal name, e.g. SEGV>
set -euo pipefail

if [[ $# -ne 3 ]]; then
  echo "usage: $0 <cellctl binary> <cell config> <signal>" >&2
  exit 2
fi
cellctl=$1
source_config=$2
signal=$3

work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-crash.XXXXXX")
emulated=$work/emulated.yaml  # the cell for `cellctl emulate`: publishes its pseudo-terminals in $work
config=$work/cell.yaml        # the cell for the run: its ports are those pseudo-terminals
emulate_log=$work/emulate.log
emulate_pid=""
run_pid=""

cleanup() {
  for pid in $run_pid $emulate_pid; do
    if kill -0 "$pid" 2>/dev/null; then
      kill -TERM "$pid" 2>/dev/null || true
      wait "$pid" 2>/dev/null || true
    fi
  done
  rm -rf "$work"
}
trap cleanup EXIT

fail() {
  echo "FAIL: $*" >&2
  [[ -s $emulate_log ]] && { echo "--- cellctl emulate output (last 40 lines):" >&2; tail -n 40 "$emulate_log" >&2; }
  [[ -s $work/run.log ]] && { echo "--- cellctl run output:" >&2; cat "$work/run.log" >&2; }
  exit 1
}

source "$(dirname "${BASH_SOURCE[0]}")/emulate_lib.sh"
publish_config "$source_config" "$emulated"
sed -i -E "s|^state_dir:.*|state_dir: $work/state|" "$emulated"
client_config "$emulated" "$config"

cat >"$work/long-move.yaml" <<'RECIPE'
recipe: {name: long-move, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  spindle: {min_hz: 200, max_hz: 600}
  timeouts: {move_s: 60, spindle_s: 10}
steps:
  - require: {encoder_ready: true, spindle_at_rest: true}
  - spindle: {start_hz: 300, direction: cw}
  - move: {to: {x: 150}, speed_mm_s: 5}
RECIPE

start_emulate "$emulated" --trace
"$cellctl" -c "$config" run "$work/long-move.yaml" --journal "$work/run" >"$work/run.log" 2>&1 &
run_pid=$!

# The move is under way (its step, the third, started: the spindle is up, x moves): a condition,
# at most 60 s.
move_started() {
  python3 - "$work/run/journal.jsonl" <<'PY'
import json, sys
try:
    lines = open(sys.argv[1]).read().splitlines()
except OSError:
    sys.exit(1)
started = [json.loads(l) for l in lines if '"step_started"' in l]
sys.exit(0 if any(e.get("step") == 3 for e in started) else 1)
PY
}
for _ in $(seq 300); do
  kill -0 "$run_pid" 2>/dev/null || fail "cellctl run ended before its move started"
  move_started && break
  sleep 0.2
done
move_started || fail "the move step never started"
sleep 1  # x is well under way (5 mm/s) and the spindle at speed; what follows is judged on the trace
before=$(wc -l <"$emulate_log")

kill "-$signal" "$run_pid"
set +e
wait "$run_pid"
rc=$?
set -e
run_pid=""
expected=$((128 + $(kill -l "$signal")))
[[ $rc -eq $expected ]] || fail "cellctl run exited $rc after SIG$signal, expected $expected (death by the signal)"

# What the emulated devices received after the signal: the stops, within a bounded wait for the
# trace writer (a condition, at most 5 s). The trace has a line per read: a stop written right after a
# telegram of the loop's may come in the same read, so it is looked for anywhere in the device's lines.
f20='scu RX( [0-9a-f]{2})* 52 45 13 '
stopp='spindle RX( [0-9a-f]{2})* 02 30 31 61 31 30 30 '
for _ in $(seq 50); do
  tail -n "+$((before + 1))" "$emulate_log" | grep -qE "$f20" &&
    tail -n "+$((before + 1))" "$emulate_log" | grep -qE "$stopp" && break
  sleep 0.1
done
tail -n "+$((before + 1))" "$emulate_log" | grep -qE "$f20" ||
  fail "the SCU emulator received no F20 (RE 0x13) after SIG$signal"
tail -n "+$((before + 1))" "$emulate_log" | grep -qE "$stopp" ||
  fail "the spindle emulator received no CMD System Stopp (MSGID a1) after SIG$signal"

# And the devices act on them: the spindle reports standstill long before anything else would stop it.
status=""
for _ in $(seq 60); do
  status=$("$cellctl" -c "$config" spindle status 2>&1) || true
  grep -qi "at rest" <<<"$status" && break
  sleep 0.5
done
grep -qi "at rest" <<<"$status" || fail "the spindle is not at rest after the crash stop: $status"
echo "PASS: SIG$signal — F20 and CMD System Stopp written by the dying process; the spindle at rest"
