#!/bin/bash
# cellctl run --fault as a process engineer uses it: a virtual-time dry run of the demo with the SCU's
# port pulled for a second and the encoder's alarm raised, then the journal read back — it names each
# injected fault (start and end) and the fault the monitor found; bad --fault text is exit 2 with the
# reason, and --fault without an emulated run is refused the same way.
# usage: fault_rehearsal_test.sh CELLCTL CONFIG RECIPE WORKDIR
set -u
cellctl=$1 config=$2 recipe=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$cellctl" -c "$config" run "$recipe" --virtual-time --journal "$work/run" \
  --fault scu:disconnect@3+1 --fault encoder:error@20 >"$work/out.txt" 2>&1
rc=$?
[ "$rc" -eq 1 ] || fail "a run stopped by a rehearsed fault exits 1, got $rc"
grep -q "fault to rehearse: scu:disconnect@3+1" "$work/out.txt" || fail "the terminal does not list the fault"
journal="$work/run/journal.jsonl"  # one JSON object a line, keys in alphabetical order
grep -q '"device":"scu","event":"fault_injected","kind":"disconnect","spec":"scu:disconnect@3+1","t":3.0,' \
  "$journal" || fail "the journal does not record the injected fault's start: $(grep fault_inj "$journal")"
grep -q '"device":"scu","event":"fault_injection_ended","kind":"disconnect","spec":"scu:disconnect@3+1"' \
  "$journal" || fail "the journal does not record its end"
grep -q '"detail":"scu link lost[^"]*","event":"fault","rule":"link_silent"' "$journal" ||
  fail "the monitor's fault names no scu link loss"
grep -q 'fault encoder:error@20 was not injected: the run ended first' "$journal" ||
  fail "a fault whose time never came is not said"
tail -1 "$journal" | grep -q '"event":"summary"' || fail "the journal is not closed by its summary"

# The spindle's line goes silent for good while it turns at 400 Hz: the stop is never confirmed, the
# converter has no watchdog, so the run says the spindle may still be turning and exits 5.
"$cellctl" -c "$config" run "$recipe" --virtual-time --journal "$work/lost" --fault spindle:silent@8 \
  >"$work/lost.txt" 2>&1
rc=$?
[ "$rc" -eq 5 ] || fail "a spindle whose stop was never confirmed exits 5, got $rc"
grep -q "WARNING: spindle safe state UNKNOWN: .*may still be turning at 400 Hz" "$work/lost.txt" ||
  fail "the terminal does not say the spindle may still turn: $(grep -i spindle "$work/lost.txt")"
tail -1 "$work/lost/journal.jsonl" | grep -q '"spindle":{"evidence":"[^"]*may still be turning at 400 Hz[^"]*","safe":"unknown"}' ||
  fail "the summary's devices.spindle is not unknown with the last set frequency"
tail -1 "$work/lost/journal.jsonl" | grep -q '"ended_by":{"device":"spindle","kind":"link"' ||
  fail "the summary does not name the spindle's link as what ended the run"

"$cellctl" -c "$config" run "$recipe" --virtual-time --journal "$work/bad" --fault 'spindle:delay=fast@1' \
  >"$work/bad.txt" 2>&1
rc=$?
[ "$rc" -eq 2 ] || fail "bad --fault text exits 2, got $rc"
grep -q "delay 'fast': MS must be a number of milliseconds" "$work/bad.txt" || fail "no reason: $(cat "$work/bad.txt")"
[ ! -e "$work/bad" ] || fail "a refused command line still made a run record"

"$cellctl" -c "$config" run "$recipe" --journal "$work/hw" --fault scu:silent@1 >"$work/hw.txt" 2>&1
rc=$?
[ "$rc" -eq 2 ] || fail "--fault on the hardware path exits 2, got $rc"
grep -q "add --emulate or --virtual-time" "$work/hw.txt" || fail "no reason: $(cat "$work/hw.txt")"
echo "fault rehearsal: journal names the injected faults; an unconfirmed spindle stop exits 5; bad text and hardware refused with exit 2"
