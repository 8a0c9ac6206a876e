#!/usr/bin/env bash
# Where the seed scheme works and where it fails: runs a case over a range of
# h/dx (particle spacing dx = h / ratio) and of time steps, and prints for each
# run whether it reached end_time or at which step it blew up (NaN when two
# particles coincide, detected by sph's state check).
#
#   bench/stability_sweep.sh [SPH] [CASE] [END_TIME]
# Defaults: build/sph, cases/dam_break_seed.case, 2 s.
set -u
sph=${1:-build/sph}
case_file=${2:-cases/dam_break_seed.case}
end_time=${3:-2}
h=0.01
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

run() {  # ratio dt
  local ratio=$1 dt=$2
  local dx
  dx=$(awk -v h=$h -v r="$ratio" 'BEGIN { printf "%.6g", h / r }')
  local log="$out/log"
  "$sph" run "$case_file" --output "$out/run" --h $h --spacing "$dx" --dt "$dt" \
      --end_time "$end_time" --output_every 1000000 --no-progress > "$log" 2>&1
  local rc=$?
  local n nbrs result
  n=$(awk '/^  particles/ { print $2 }' "$log")
  nbrs=$(awk '/^  neighbours/ { print $2 }' "$log")
  if [ $rc -eq 0 ]; then
    result="stable to t = $end_time s"
  elif [ $rc -eq 3 ]; then
    result=$(sed -n 's/.*blew up at step \([0-9]*\), t = \([0-9.e-]*\) s.*/blew up at step \1 (t = \2 s)/p' "$log")
  else
    result="error $rc: $(head -1 "$log")"
  fi
  printf '%6s %9s %8s %7s %6s  %s\n' "$ratio" "$dx" "$dt" "${n:--}" "${nbrs:--}" "$result"
  rm -rf "$out/run"
}

echo "# $case_file, h = $h, end_time = $end_time s; nbrs = mean neighbours at the end (stable runs)"
printf '%6s %9s %8s %7s %6s  %s\n' "h/dx" "dx" "dt" "N" "nbrs" "result"
for ratio in 1.0 1.2 1.33 1.5 1.6 1.75 2.0 2.5; do run "$ratio" 1e-4; done
for dt in 5e-4 1e-3 2e-3 3e-3 5e-3; do run 1.33 "$dt"; done
