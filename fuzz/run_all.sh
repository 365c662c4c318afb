#!/usr/bin/env bash
# Runs the libFuzzer targets one after the other on one core, each for a number of executions,
# and prints each one's executions, executions per second and findings.
#
#   cmake --preset fuzz && cmake --build --preset fuzz
#   fuzz/run_all.sh                        # every target, 10 million executions each (the long run)
#   fuzz/run_all.sh 1000000 fdl_frames     # one target, a million executions
#   FUZZ_MAX_SECONDS=300 fuzz/run_all.sh     # at most 5 minutes each (a short run)
#
# New inputs go to build/fuzz/corpus/<target> (the seeds in fuzz/corpus are only read); a crash,
# leak or hang is written to build/fuzz/findings/<target>/ — copy it to fuzz/findings/<target>/
# so that the replay test (tests/fuzz) keeps checking it, then fix the cause.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-10000000}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scu_request_stream scu_reply_stream spindle_frames fdl_frames encoder_cyclic dp_diagnosis
           dp_parameters yaml_config yaml_recipe)
fi

# Known open findings (FUZZ_CHECK_OPEN, recorded in fuzz/findings/open/) are reported, not fatal, so
# that one known defect does not stop the search for others.
export CELLCTL_FUZZ_TOLERATE_OPEN=1
status=0
for t in "${targets[@]}"; do
  exe=$root/build/fuzz/fuzz/fuzz_$t
  [ -x "$exe" ] || { echo "$t: $exe missing: cmake --preset fuzz && cmake --build --preset fuzz" >&2; exit 2; }
  work=$root/build/fuzz/corpus/$t
  findings=$root/build/fuzz/findings/$t
  log=$root/build/fuzz/$t.log
  mkdir -p "$work" "$findings"
  # Inputs up to about two of the longest telegrams (a stream decoder holds two), or a config-sized
  # YAML text: longer inputs only repeat what shorter ones explore, at a fraction of the speed.
  case $t in
    scu_*) max_len=1400 ;;
    fdl_frames | dp_*) max_len=600 ;;
    spindle_frames | encoder_cyclic) max_len=200 ;;
    *) max_len=4096 ;;
  esac
  # -timeout: an input that takes 10 s is a hang; -rss_limit_mb: a leak or a runaway allocation.
  if "$exe" -runs="$runs" -max_total_time="${FUZZ_MAX_SECONDS:-0}" -timeout=10 -rss_limit_mb=2048 -max_len=$max_len -print_final_stats=1 \
       -artifact_prefix="$findings/" "$work" "$root/fuzz/corpus/$t" >"$log" 2>&1; then
    result=ok
  else
    result="FINDING (see $log and $findings)"
    status=1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  open=$(grep -c "open finding" "$log" || true)
  [ "${open:-0}" = 0 ] && open="" || open=", open findings hit (reported once per place): $open"
  echo "$t: ${execs:-?} executions, ${rate:-?} per second: $result$open"
done
exit $status
