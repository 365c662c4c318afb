#!/usr/bin/env bash
# End to end, as an integrator commissions an emulated cell: `cellctl emulate` publishes the three
# devices' pseudo-terminals, then the commissioning commands talk to them through the cell config —
# SCU status and a move, spindle start/status/stop, encoder status, with --port and --timeout before or
# after the action, progress shown while they wait — and Ctrl-C ends the emulation
# cleanly (exit 0, published links removed). A command the SCU session refuses exits 1. A second
# `cellctl emulate` of the same cell is refused (exit 4, naming the live one) and leaves the links alone.
# With --trace the emulation writes a hex trace of what each device received and sent.
#
# usage: emulate_commissioning_test.sh <cellctl binary> <cell config>
# The config is copied with publish_as and the encoder's EEPROM state file moved into a fresh temp
# dir, so parallel runs (and a user's own `cellctl emulate`) do not collide.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 <cellctl binary> <cell config>" >&2
  exit 2
fi
cellctl=$1
source_config=$2

work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-e2e.XXXXXX")
config=$work/cell.yaml
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
  if [[ -s $emulate_log ]]; then
    echo "--- cellctl emulate output:" >&2
    cat "$emulate_log" >&2
  fi
  exit 1
}

# --- the config copy and cellctl emulate in the background ----------------------------------------
source "$(dirname "${BASH_SOURCE[0]}")/emulate_lib.sh"
publish_config "$source_config" "$config"
links=("$work/scu" "$work/spindle" "$work/encoder")
start_emulate "$config" --trace
for l in "${links[@]}"; do
  [[ -c $(readlink "$l") ]] || fail "$l points to $(readlink "$l"), which is not a character device"
done

# --- a second emulation of the same cell is refused, and the first one's links stay ----------------
targets=()
for l in "${links[@]}"; do targets+=("$(readlink "$l")"); done
second_rc=0
second_out=$(timeout 10 "$cellctl" -c "$config" emulate 2>&1) || second_rc=$?
printf '$ cellctl emulate (a second one)   (exit %d)\n%s\n' "$second_rc" "$second_out"
[[ $second_rc -eq 4 ]] || fail "a second cellctl emulate on the same publish_as exited $second_rc, expected 4"
grep -q "$work/scu is published by another live \`cellctl emulate\` (pid $emulate_pid)" <<<"$second_out" ||
  fail "the second cellctl emulate did not say which live emulation holds $work/scu"
for i in "${!links[@]}"; do
  [[ $(readlink "${links[$i]}") == "${targets[$i]}" ]] ||
    fail "${links[$i]} was replaced or removed by the refused second emulation"
done

# --- the commissioning commands --------------------------------------------------------------------
out=""
# run_exits <code> <what> <cellctl arguments…>: the command must exit <code>; its output is kept in $out.
run_exits() {
  local expected=$1
  local what=$2
  shift 2
  local rc=0
  local started=$SECONDS
  out=$("$cellctl" -c "$config" "$@" 2>&1) || rc=$?
  printf '$ cellctl %s   (exit %d, %d s)\n%s\n' "$*" "$rc" $((SECONDS - started)) "$out"
  [[ $rc -eq $expected ]] || fail "$what: \`cellctl $*\` exited $rc, expected $expected"
}
# run <what> <cellctl arguments…>: the command must exit 0.
run() {
  run_exits 0 "$@"
}
# expect <what> <extended regex>: the last command's output must match.
expect() {
  grep -Eq -- "$2" <<<"$out" || fail "$1: the output does not match /$2/"
}

run "SCU status" scu status
expect "SCU status" "^actuator 1 +-?[0-9.]+ mm \(-?[0-9]+ edges\), at rest"
expect "SCU status" "^errors +none"
# --port and --timeout where a person types them: before the action and after it alike; a --port
# after the action is the one used (a missing device is named, exit 4).
run "SCU status, options before the action" scu --port "$work/scu" --timeout 5 status
expect "SCU status, options before the action" "^actuator 1 +-?[0-9.]+ mm"
run "SCU status, options after the action" scu status --port "$work/scu" --timeout 5
expect "SCU status, options after the action" "^actuator 1 +-?[0-9.]+ mm"
run_exits 4 "SCU status on a --port after the action that does not exist" scu status --port "$work/no-such-port"
expect "SCU status on a missing --port names the device" "SCU: serial port $work/no-such-port does not exist"
run_exits 2 "SCU status with a --timeout after the action out of range" scu status --timeout 0.01
expect "SCU status, --timeout out of range" "--timeout: Value 0.01 not in range"
run "spindle start --help" spindle start --help
expect "spindle start --help lists the group's options" "^  --port TEXT"
expect "spindle start --help lists the group's options" "^  --timeout FLOAT"

# A port another process holds while the emulation runs: said so, not "start cellctl emulate".
holder_log=$work/holder.log
# (In a process group of its own, so that the whole holder — flock and its sleep — ends at once.)
setsid flock "$work/scu" -c 'echo held; exec sleep 20' >"$holder_log" 2>&1 &
holder_pid=$!
for _ in $(seq 100); do
  grep -q held "$holder_log" && break
  sleep 0.1
done
grep -q held "$holder_log" || fail "flock did not take $work/scu within 10 s"
run_exits 4 "SCU status on a port another process holds" scu status
kill -- -"$holder_pid" 2>/dev/null || true
wait "$holder_pid" 2>/dev/null || true
expect "busy published port" "SCU: serial port $work/scu is in use by another process \\(\`cellctl emulate\` \\(pid $emulate_pid\\) publishes it; another command talks to the SCU now"
grep -q "start \`cellctl emulate\`" <<<"$out" && fail "a busy port advises starting cellctl emulate while it runs"

run "SCU move" scu move --function 1 --actuator 1 --position-mm 20 --speed-mm-s 20
expect "SCU move" "^function F1 +arrived"
# Not silent while it moves: a progress line at once and every 0.5 s (20 mm at 20 mm/s take at least 1 s).
expect "SCU move shows progress at once" "^ +0\.0 s  F1 (queued|running): actuator 1 at -?[0-9]+\.[0-9]{2} mm, target 20\.00 mm$"
expect "SCU move shows progress while running" "^ +0\.5 s  F1 running: actuator 1 at [0-9]+\.[0-9]{2} mm, target 20\.00 mm$"
# The SCU's own arrival tolerance (arrival_tolerance_edges in the config) is 2 edges.
run "SCU status after the move" scu status
expect "SCU status after the move" "^actuator 1 +(19\.8|19\.9|20\.0|20\.1|20\.2)0 mm \((198|199|200|201|202) edges\), at rest"
# A command the session refuses is a failure (exit 1), not a bad command line (2).
run_exits 1 "SCU move with a function the config does not define" scu move --function 3 --actuator 1 \
  --position-mm 10
expect "SCU move refused" "move refused: F3"

run "spindle start" spindle start --frequency 400
expect "spindle start" "^motion +at speed"
expect "spindle start" "^frequency +set 400 Hz"
expect "spindle start shows the run-up" "^ +0\.5 s  running up to 400 Hz: actual [0-9]+ Hz$"
run "spindle status while running" spindle status
expect "spindle status while running" "^motion +at speed"
expect "spindle status while running" "^frequency +set 400 Hz, actual (39[5-9]|40[0-5]) Hz"
expect "spindle status while running" "^state +ok"
run "spindle stop" spindle stop --timeout 20 --port "$work/spindle"
expect "spindle stop" "^motion +at rest"
expect "spindle stop shows the run-down" "^ +0\.0 s  running down: actual [0-9]+ Hz$"

run "encoder status" encoder status --port "$work/encoder" --timeout 5
expect "encoder status" "^bus +active \((data_exchange|diag_cyclic)\), [1-9][0-9]* exchanges"
expect "encoder status" "^position +[0-9]+ counts = [0-9]+\.[0-9]{3} mm"
# The encoder's shaft turns with axis 1, which the SCU moved to 200 edges = 20 mm by its own sensor;
# that sensor reads 0.2 % long (scale_error in the config), so the encoder sees 20 / 1.002 = 19.96 mm.
expect "encoder status: the axis the SCU moved" "^position +[0-9]+ counts = 19\.9[0-9]{2} mm"

# set-address talks to station 126 only; the emulated encoder is at 5: said so, at once, exit 4.
run_exits 4 "encoder set-address to an encoder not at 126" encoder set-address 7 --timeout 10
expect "encoder set-address names what happened" "no encoder answers at address 126 \\([0-9]+ tries\\)"
grep -q "within 10 s" <<<"$out" && fail "encoder set-address blamed a time-out that did not happen"

# An SCU command on the encoder's port: no SCU answers; the reason names the device and port once.
run_exits 4 "SCU status on a port where no SCU answers" scu status --port "$work/encoder" --timeout 5
expect "SCU status where no SCU answers" "SCU on $work/encoder"
[[ $(grep -o "$work/encoder" <<<"$out" | wc -l) -eq 1 ]] || fail "the SCU's fault names its port more than once"

# --- a preset and a direction change are recorded in the config, where every start-up checks them --
cp "$config" "$work/cell.before-preset.yaml"
run "encoder preset" encoder preset 1000 --timeout 10
expect "encoder preset records the new offset" "^config +encoder.preset_offset: \(none\) → -?[0-9]+"
grep -Eq "^  preset_offset: -?[0-9]+$" "$config" || fail "encoder preset did not record preset_offset in the config"
cmp -s "$config.bak" "$work/cell.before-preset.yaml" || fail "the config's backup is not the config as it was"
run "encoder status after the preset" encoder status --timeout 5
expect "encoder status after the preset" "^position +1000 counts"
grep -q WARNING <<<"$out" && fail "encoder status warns although the preset is recorded"
run "encoder direction" encoder direction ccw --timeout 10
grep -q "^  code_sequence: ccw$" "$config" || fail "encoder direction did not record code_sequence: ccw"
run "encoder status after the direction change" encoder status --timeout 5
expect "the direction change lasts past the next command" "counting up counterclockwise"

# --- Ctrl-C ends the emulation ---------------------------------------------------------------------
kill -INT "$emulate_pid"
for _ in $(seq 100); do
  kill -0 "$emulate_pid" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$emulate_pid" 2>/dev/null && fail "cellctl emulate still runs 10 s after SIGINT"
rc=0
wait "$emulate_pid" || rc=$?
emulate_pid=""
[[ $rc -eq 0 ]] || fail "cellctl emulate exited $rc after SIGINT, expected 0"
grep -q "emulation ended" "$emulate_log" || fail "cellctl emulate did not say the emulation ended"
for device in scu spindle encoder; do
  for dir in RX TX; do
    grep -Eq "^trace +[0-9]+\.[0-9]{6} s [0-9:]{8}\.[0-9]{6} $device $dir ([0-9a-f]{2} ?)+$" "$emulate_log" ||
      fail "cellctl --trace emulate wrote no $dir trace of the $device"
  done
done
for l in "${links[@]}"; do
  [[ ! -e $l && ! -L $l ]] || fail "cellctl emulate left $l behind"
done
# With no emulation running, a command on an emulated device says to start one.
run_exits 4 "SCU status with no emulation" scu status
expect "SCU status with no emulation" "SCU: serial port $work/scu does not exist \\(the cell config says the SCU is emulated: start \`cellctl emulate\` first"

echo "PASS: emulate + scu/spindle/encoder commissioning over published pseudo-terminals"
