#!/usr/bin/env bash
# Threads: throughput of `sph run` with --threads 1, --threads 2 and
# --threads auto on the seed dam break at about 10 000 and 100 000
# particles (cases/dam_break_seed.case with spacing, h and dt scaled, h/dx = 1.33
# as shipped), first on the machine as it is, then with one competing
# CPU-bound process (a shell busy loop) running. Each figure is the median
# particle-steps per second (sph's summary: stepping time only, no output)
# of REPEATS runs, the three thread settings interleaved. Prints the ratios
# the thread requirements name: 2 threads / 1 thread and auto / the better
# of the two on the machine as it is (aims: >= 1.7 from 10k particles up,
# >= 0.9), and auto / 1 thread with the competing process (aim >= 0.8), and
# `uptime` before and after. Timing only: nothing here is asserted.
#
#   bench/threads_bench.sh [SPH]      (default build/sph)
#   REPEATS=5 SIZES="10000 100000" STEPS="2000 200" bench/threads_bench.sh
set -euo pipefail
sph=${1:-build/sph}
repeats=${REPEATS:-5}
read -r -a sizes <<< "${SIZES:-10000 100000}"
read -r -a steps <<< "${STEPS:-2000 200}"
case_file=$(dirname "$0")/../cases/dam_break_seed.case
out=$(mktemp -d)
busy=""
cleanup() {
  if [ -n "$busy" ]; then kill "$busy" 2> /dev/null || true; fi
  rm -rf "$out"
}
trap cleanup EXIT

# One run: prints its particle-steps per second and the thread counts used.
run_one() {  # particles steps threads
  local n=$1 nsteps=$2 threads=$3
  # The block is 0.25 x 0.5: n = 0.125 / dx^2. h = 1.33 dx, dt = 1e-4 h / 0.01.
  local dx h dt end
  dx=$(awk -v n="$n" 'BEGIN { printf "%.6g", sqrt(0.125 / n) }')
  h=$(awk -v dx="$dx" 'BEGIN { printf "%.6g", 1.3333 * dx }')
  dt=$(awk -v h="$h" 'BEGIN { printf "%.6g", 1e-4 * h / 0.01 }')
  end=$(awk -v dt="$dt" -v s="$nsteps" 'BEGIN { printf "%.6g", dt * s }')
  rm -rf "$out/run"
  "$sph" run "$case_file" --output "$out/run" --spacing "$dx" --h "$h" --dt "$dt" --end_time "$end" \
      --output_every 100000000 --no-progress --threads "$threads" > "$out/log" 2>&1 || {
    echo "sph failed:" >&2
    cat "$out/log" >&2
    exit 1
  }
  awk '/^  throughput/ { rate = $2 } /^  threads/ { $1 = ""; used = $0 } /^  particles/ { n = $2 }
       END { printf "%s %s |%s\n", rate, n, used }' "$out/log"
}

median() { tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# Medians of 1, 2 and auto for each size; prints a table row per size and
# the ratios. $1: label of the machine state; $2: divisor of the steps of
# the 2-thread runs (beside a competing process they are 10-30 times
# slower, and their throughput does not need whole runs).
measure() {
  local label=$1 slow2=${2:-1}
  echo
  echo "== $label (load average: $(cut -d' ' -f1-3 /proc/loadavg))"
  printf "%-9s %-14s %-14s %-14s %-8s %-8s %-8s  %s\n" particles "1 thread" "2 threads" auto "2/1" "auto/best" "auto/1" \
      "auto's threads (each run)"
  for k in "${!sizes[@]}"; do
    local n=${sizes[$k]} s=${steps[$k]}
    local r1="" r2="" ra="" used="" count=""
    for ((r = 0; r < repeats; r++)); do
      r1+=" $(run_one "$n" "$s" 1 | cut -d' ' -f1)"
      r2+=" $(run_one "$n" $((s / slow2)) 2 | cut -d' ' -f1)"
      local line
      line=$(run_one "$n" "$s" auto)
      ra+=" ${line%% *}"
      count=$(echo "$line" | cut -d' ' -f2)
      used+="${used:+;}$(echo "$line" | cut -d'|' -f2 | sed 's/ (auto)//; s/^ *//')"
    done
    local m1 m2 ma
    m1=$(echo "$r1" | median)
    m2=$(echo "$r2" | median)
    ma=$(echo "$ra" | median)
    awk -v n="$count" -v a="$m1" -v b="$m2" -v c="$ma" -v used="$used" 'BEGIN {
      best = a > b ? a : b
      printf "%-9s %-14s %-14s %-14s %-8.2f %-8.2f %-8.2f  %s\n", n, sprintf("%.3g M/s", a / 1e6),
             sprintf("%.3g M/s", b / 1e6), sprintf("%.3g M/s", c / 1e6), b / a, c / best, c / a, used }'
    echo "  runs (particle-steps/s): 1:$r1  2:$r2  auto:$ra"
  done
}

echo "sph threads benchmark: $($sph --version), $(nproc) CPUs for this process, $repeats runs per figure"
echo "uptime before: $(uptime)"
measure "the machine as it is"
( while :; do :; done ) &
busy=$!
sleep 2
measure "with one competing CPU-bound process (pid $busy); 2 threads run 1/10 of the steps" 10
kill "$busy"
busy=""
echo
echo "uptime after: $(uptime)"
echo "aims: as it is, 2/1 >= 1.7 from 10k particles up and auto/best >= 0.9; competing, auto/1 >= 0.8"
