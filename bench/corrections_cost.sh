#!/usr/bin/env bash
# Cost of each kernel correction and surface term when on (docs/methods/corrections.md
# and docs/methods/surface-tension.md): the 2D
# dam break at dx = 3.5 mm (cases/dam_break_mm.case, ~10 000 fluid + ~3 400
# wall particles), STEPS steps, 1 and 2 threads, REPEATS repetitions with
# the settings interleaved (so that a change of the machine's load hits all
# of them alike). Each figure is the median over the repetitions of sph's
# summary throughput (stepping time only; no snapshots but the first and
# last), printed as microseconds per step and nanoseconds per particle-step
# (over all particles, walls included), and the ratio to "none".
# Re-initialisations run every step here (density_reinit_every 1): their
# cost per step at every N is 1/N of the figure. `uptime` is printed before
# and after: the machine is shared, and figures under load are noisy.
#
#   bench/corrections_cost.sh [SPH]      (default build/sph)
#   REPEATS=3 STEPS=100 THREADS="1 2" bench/corrections_cost.sh
set -euo pipefail
sph=${1:-build/sph}
repeats=${REPEATS:-3}
steps=${STEPS:-100}
read -r -a threads <<< "${THREADS:-1 2}"
case_file=$(dirname "$0")/../cases/dam_break_mm.case
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
dt=1.75e-5
end=$(awk -v dt="$dt" -v s="$steps" 'BEGIN { printf "%.6g", dt * s }')

names=(none shepard mls cspm artificial_pressure surface_tension)
flags=(""
       "--density_reinit shepard --density_reinit_every 1"
       "--density_reinit mls --density_reinit_every 1"
       "--gradient_correction cspm"
       "--artificial_pressure 0.2"
       "--surface_tension morris --sigma 0.0728")

run_one() {  # flags threads -> "throughput particles"
  rm -rf "$out/run"
  # shellcheck disable=SC2086
  "$sph" run "$case_file" --output "$out/run" --spacing 0.0035 --h 0.00525 --dt "$dt" --end_time "$end" \
      --output_every 100000000 --no-progress --threads "$2" $1 > "$out/log" 2>&1 || {
    echo "sph failed ($1):" >&2
    cat "$out/log" >&2
    exit 1
  }
  awk '/^  throughput/ { rate = $2 } /^  particles/ { n = $2 } END { print rate, n }' "$out/log"
}

median() { tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "before: $(uptime)"
declare -A rates
particles=0
for ((r = 0; r < repeats; r++)); do
  for k in "${!names[@]}"; do
    for t in "${threads[@]}"; do
      line=$(run_one "${flags[$k]}" "$t")
      rates[$k,$t]+=" ${line%% *}"
      particles=${line##* }
    done
  done
done
echo "after:  $(uptime)"
echo "particles: $particles (all, walls included), $steps steps, medians of $repeats"
printf "| %-20s |" "term on"
for t in "${threads[@]}"; do printf " %s thr: us/step | ns/particle-step | x none |" "$t"; done
echo
for k in "${!names[@]}"; do
  printf "| %-20s |" "${names[$k]}"
  for t in "${threads[@]}"; do
    m=$(echo "${rates[$k,$t]}" | median)
    m0=$(echo "${rates[0,$t]}" | median)
    awk -v m="$m" -v m0="$m0" -v n="$particles" 'BEGIN { printf " %.0f | %.1f | %.2f |", 1e6 * n / m, 1e9 / m, m0 / m }'
  done
  echo "   (runs:${rates[$k,1]:-} /${rates[$k,2]:-})"
done
