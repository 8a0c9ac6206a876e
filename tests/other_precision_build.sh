#!/usr/bin/env bash
# The mixed-precision build (cmake -DSPH_PRECISION=mixed: the density rate,
# pressure, sound speed and mass stored in float, sph::Narrow in
# include/sph/types.hpp) builds, says what it is, and meets two of the
# validation figures the double build meets, with validate.py's own
# tolerances (its header says why): the hydrostatic tank's pressure against
# rho0 g (H - y), and the dam break's front against Martin & Moyce; and it
# runs the two splashing flows of the ctests leaks.* without a leak or a
# regime stop (the obstacle dam break failed in this build before the
# clamped diffusion of 2026-12-07: docs/methods/boundaries.md).
#   mixed_precision_build.sh SOURCE_DIR WORK_DIR PYTHON [SPH_NATIVE]
# PYTHON: one with numpy and VTK (Debian's /usr/bin/python3); SPH_NATIVE:
# the outer build's (ON by default). About 5 minutes on 2 cores, most of it
# the build.
set -euo pipefail
src=$1 work=$2 py=$3 native=${4:-ON}
"$py" -c "import numpy, vtkmodules" 2> /dev/null ||
  { echo "FAILED: $py lacks numpy or VTK (Debian's python3: scripts/setup.sh)"; exit 1; }
mkdir -p "$work"
cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DSPH_PRECISION=mixed -DSPH_NATIVE="$native" \
  > "$work/configure.log"
cmake --build "$work/build" -j2 --target sph > "$work/build.log"
version=$("$work/build/sph" --version)
echo "$version"
case "$version" in *"(precision mixed)"*) ;; *) echo "FAILED: the mixed build says '$version'"; exit 1 ;; esac
# A case asking for double is refused by this build, naming the option.
if "$work/build/sph" check "$src/cases/dam_break.case" --precision double > "$work/refused.log" 2>&1; then
  echo "FAILED: the mixed build ran a case asking for precision = double"; exit 1
fi
grep -q "cmake -DSPH_PRECISION=double" "$work/refused.log" || { echo "FAILED: $(cat "$work/refused.log")"; exit 1; }
"$py" "$src/validation/validate.py" hydrostatic --sph "$work/build/sph" --case "$src/cases/hydrostatic_tank.case" \
  --workdir "$work/hydrostatic"
"$py" "$src/validation/validate.py" dam_break --sph "$work/build/sph" --case "$src/cases/dam_break_mm.case" \
  --workdir "$work/dam_break_mm"
# The leaks.* runs (tests/CMakeLists.txt): sph exits 3 on a leak or a regime
# stop, so its exit status is the test (about 40 s).
for run in "dam_break_obstacle --end_time 1.5" "dam_break --lid --end_time 3"; do
  set -- $run
  name=$1
  shift
  if ! "$work/build/sph" run "$src/cases/$name.case" "$@" --output_interval 0.5 --threads 1 --output "$work/leaks_$name" \
    --overwrite --no-progress > "$work/leaks_$name.log" 2>&1; then
    echo "FAILED: the mixed build's $name run ($*): $(grep -m1 'error' "$work/leaks_$name.log")"
    exit 1
  fi
  grep "wall guard" "$work/leaks_$name.log"
done
