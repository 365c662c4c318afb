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
echo "fault rehearsal: journal names the injected faults; bad text and hardware refused with exit 2"
