#!/bin/bash
# A real-time emulated job beside a load that keeps every core busy: proves that a dry run on a
# loaded machine has no fault of its own (issue 9, part 4; the routines: issue 22, item 4). Each run
# starts LOAD busy loops per core (plain shell loops at normal priority, like a compiler or another
# user's job), runs the job with --emulate, stops its own loops (by their PIDs) and reads the result.
# Passes when every run completes with no fault. Prints per run the load average and, per device,
# the worst reply round trip and the longest silence between good replies.
#
#   tools/demo_under_load.sh [-j run|home|teach-in] [-n RUNS] [-l LOOPS_PER_CORE] [-c CELLCTL]
#                            [-r RECIPE] [-f CONFIG] [-o DIR]
#
# Defaults: the job `run` of recipes/demo.yaml (about 91 s a run; `home`: every axis with homing,
# about 10 s; `teach-in`: the encoder on x over 100 mm from 5 mm, about 45 s), 5 runs, 2 loops per
# core, build/release/cellctl, run records under /tmp/cellctl-under-load (its state/ folder is the
# dry runs' emulated plant, kept from run to run). Run from the repository root.
set -u
runs=5 per_core=2 cellctl=build/release/cellctl recipe=recipes/demo.yaml out=/tmp/cellctl-under-load
config=config/cell.yaml job=run
while getopts "j:n:l:c:r:o:f:" opt; do
  case $opt in
    j) job=$OPTARG ;;
    n) runs=$OPTARG ;;
    l) per_core=$OPTARG ;;
    c) cellctl=$OPTARG ;;
    r) recipe=$OPTARG ;;
    o) out=$OPTARG ;;
    f) config=$OPTARG ;;
    *) sed -n '2,15p' "$0"; exit 2 ;;
  esac
done
[ -x "$cellctl" ] || { echo "no cellctl at $cellctl (build it: cmake --build --preset release)" >&2; exit 2; }
case $job in
  run) what="$recipe" ;;
  home) what="homing" ;;
  teach-in) what="Teach-In of x" ;;
  *) echo "-j: run, home or teach-in" >&2; exit 2 ;;
esac
# One job, its record in $1.
run_job() {
  case $job in
    run) "$cellctl" -c "$config" run "$recipe" --emulate --journal "$1" --state-dir "$out/state" ;;
    home) "$cellctl" -c "$config" home --yes --emulate --journal "$1" --state-dir "$out/state" ;;
    teach-in)
      "$cellctl" -c "$config" teach-in x --distance 100 --from 5 --yes --emulate --journal "$1" \
        --state-dir "$out/state" ;;
  esac
}
cores=$(nproc)
loops=()
stop_load() {
  for p in "${loops[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${loops[@]}"; do wait "$p" 2>/dev/null; done
  loops=()
}
trap 'stop_load; exit 130' INT TERM
rm -rf "$out" && mkdir -p "$out"
failed=0
echo "cellctl under load: $runs run(s) of $what --emulate beside $((cores * per_core)) busy loops on $cores cores"
for i in $(seq 1 "$runs"); do
  for _ in $(seq 1 $((cores * per_core))); do
    sh -c 'while :; do :; done' &
    loops+=($!)
  done
  run_job "$out/run$i" >"$out/run$i.txt" 2>&1
  rc=$?
  stop_load
  faults=$(grep -c '^  fault:' "$out/run$i.txt")
  outcome=$(grep -m1 '^outcome:' "$out/run$i.txt")
  read_max=$(grep -m1 'stage read sessions' "$out/run$i.txt" | sed 's/.*max //')
  period_max=$(grep -m1 'period error:' "$out/run$i.txt" | sed 's/.*max //')
  load=$(cut -d' ' -f1-3 /proc/loadavg)
  echo "run $i: exit $rc, $outcome, $faults fault(s), read-sessions stage max $read_max, period error max $period_max, load average $load"
  # Per device: the worst reply round trip and the longest silence between good replies (the
  # encoder's limit is lost_after_ms, 100 ms in config/cell.yaml).
  grep -E '^  fault:|^device:|^link ' "$out/run$i.txt" | sed 's/^ */    /'
  if [ "$rc" -ne 0 ] || [ "$faults" -ne 0 ]; then failed=$((failed + 1)); fi
done
worst=$(grep -h '^link encoder' "$out"/run*.txt | sed 's/.*longest silence \([0-9.]*\) ms.*/\1/' | sort -g | tail -1)
echo "encoder: longest silence between good replies over all runs ${worst:-?} ms"
echo "$((runs - failed)) of $runs run(s) complete with no fault (records in $out)"
[ "$failed" -eq 0 ]
