#!/usr/bin/env bash
# cellctl compare and report on real records: usage: compare_test.sh CELLCTL WORKDIR RUN_A RUN_B OTHER_RECIPE_RUN
# - compare A B: exit 0, a row per step of the short recipe (1..6) with both durations, the overlay written;
# - compare A OTHER: refused with exit 2 and the reason; with --force: exit 0;
# - report B --csv: the steps, the following error per axis and a CSV with a header and one row per sample.
set -u
cellctl=$1 work=$2 a=$3 b=$4 other=$5
out=$work/compare-out
rm -rf "$out"
fail() { echo "FAIL: $*"; exit 1; }

text=$("$cellctl" compare "$a" "$b" --out "$out") || fail "compare exited $?"
echo "$text"
for step in "1  check the cell" "2  go" "3  spindle up" "4  dwell" "5  back" "6  spindle down"; do
  grep -Eq "^ +${step} +[0-9]+\.[0-9]{2} +[0-9]+\.[0-9]{2} +[-+][0-9]+\.[0-9]{2}" <<<"$text" || fail "no row for step '$step'"
done
grep -q "virtual time" <<<"$text" || fail "run A's mode not named"
grep -q "emulated (every device" <<<"$text" || fail "run B's mode not named"
[ -s "$out/compare.svg" ] && [ -s "$out/compare.html" ] || fail "overlay not written"
grep -q ">A: x planned<" "$out/compare.svg" && grep -q ">B: x planned<" "$out/compare.svg" || fail "overlay lacks a run"

"$cellctl" compare "$a" "$other" --out "$out" 2>"$work/refused.txt"
code=$?
[ $code -eq 2 ] || fail "compare of different recipes exited $code, expected 2"
grep -q "the recipes differ" "$work/refused.txt" || fail "refusal does not say why: $(cat "$work/refused.txt")"
"$cellctl" compare "$a" "$other" --out "$out" --force >/dev/null 2>&1 || fail "--force did not compare"

report=$("$cellctl" report "$b" --csv "$work/samples.csv") || fail "report exited $?"
echo "$report"
grep -Eq "^ +5  back \(line [0-9]+\) +[0-9]+\.[0-9]{2} +[0-9]+\.[0-9]{2} +done" <<<"$report" || fail "report lacks step 5 planned/actual"
grep -Eq "^  x +[-+][0-9]+\.[0-9]{3} mm" <<<"$report" || fail "report lacks x's following error"
grep -q "wake-up jitter p99" <<<"$report" || fail "report lacks the loop's jitter"
head -1 "$work/samples.csv" | grep -q "^t_s,step,x_planned_mm,x_scu_mm,z_planned_mm,z_scu_mm,encoder_mm,spindle_set_hz,spindle_hz$" ||
  fail "CSV header: $(head -1 "$work/samples.csv")"
rows=$(($(wc -l <"$work/samples.csv") - 1))
[ "$rows" -gt 200 ] || fail "CSV has $rows rows"
echo "compare_test: ok ($rows samples)"
