#!/usr/bin/env bash
# Issue 22 item 5: a Teach-In asks before it moves, as `cellctl home` does. The plan is said first
# (the axis, from where to where and back, the speed, the file the result goes to); without a
# terminal and without --yes it refuses (exit 2) and nothing moves; a "no" typed on a terminal moves
# nothing (exit 1); --yes runs it. "Nothing moved": no run record, no emulated plant saved, nothing
# taught into the dry run's config copy.
#
# usage: teach_in_asks_test.sh <cellctl binary> <cell config>
set -euo pipefail
cellctl=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/cellctl-teach-in-asks.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# The shipped cell with its encoder EEPROM and its state folder in $work.
sed -E "s|^(    state_file:).*|\1 $work/encoder.eeprom|" "$2" >"$work/cell.yaml"
printf '\nstate_dir: %s/state\n' "$work" >>"$work/cell.yaml"
teach=(teach-in x --distance 100 --from 5 --virtual-time)

out=""
# run_exits <code> <what> <how stdin is given: null|no> <cellctl arguments…>
run_exits() {
  local expected=$1 what=$2 stdin=$3 rc=0
  shift 3
  if [[ $stdin == null ]]; then
    out=$("$cellctl" -c "$work/cell.yaml" "$@" 2>&1 </dev/null) || rc=$?
  else
    # A terminal that answers "no": stdin a pseudo-terminal with that line already typed.
    out=$(python3 -c '
import os, subprocess, sys
master, slave = os.openpty()
os.write(master, b"no\n")
p = subprocess.run(sys.argv[1:], stdin=slave, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
sys.stdout.write(p.stdout.decode(errors="replace"))
sys.exit(p.returncode)' "$cellctl" -c "$work/cell.yaml" "$@") || rc=$?
  fi
  printf '$ cellctl %s   (exit %d)\n%s\n' "$*" "$rc" "$out"
  [[ $rc -eq $expected ]] || fail "$what: \`cellctl $*\` exited $rc, expected $expected"
}
expect() { grep -Fq -- "$2" <<<"$out" || fail "$1: the output does not say \"$2\""; }
nothing_moved() {
  [[ ! -e $work/$2 ]] || fail "$1: a run record was made in $work/$2"
  [[ ! -e $work/state/plant.dry-run.json ]] || fail "$1: the emulated plant was run and saved"
  [[ ! -e $work/state/config.dry-run.yaml ]] || fail "$1: something was taught"
}

plan="the SCU MOVES x to 5 mm, then from 5 mm to 105 mm and back at 5 mm/s"
copy="written into $work/state/config.dry-run.yaml (a dry run's copy: the cell's config is left as it is)"

run_exits 2 "no terminal, no --yes" null "${teach[@]}" --journal "$work/refused"
expect "the plan" "$plan"
expect "the file" "$copy"
expect "the reason" "confirmation needed and no terminal to ask on: add --yes"
nothing_moved "no terminal, no --yes" refused

run_exits 1 "answered no" no "${teach[@]}" --journal "$work/declined"
expect "the question" "Start the Teach-In now?"
expect "the answer" "not confirmed: nothing moved, nothing written"
nothing_moved "answered no" declined

run_exits 0 "--yes" null "${teach[@]}" --journal "$work/taught" --yes
expect "the plan, with --yes too" "$plan"
grep -Eq "^  measuring_units: [0-9]+$" "$work/state/config.dry-run.yaml" || fail "--yes: nothing taught"
echo "teach-in asks before it moves: OK"
