#!/usr/bin/env bash
# The build of the other precision (cmake -DSPH_PRECISION=double | mixed;
# mixed stores the density rate, pressure, sound speed and mass in float:
# sph::Narrow in include/sph/types.hpp) builds, says what it is, refuses a
# case asking for the precision it is not, and meets two of the validation
# figures the default build meets, with validate.py's own tolerances (its
# header says why): the hydrostatic tank's pressure against rho0 g (H - y),
# and the dam break's front against Martin & Moyce; and it runs the two
# splashing flows of the ctests leaks.* without a leak or a regime stop (the
# obstacle dam break failed in the mixed build before the clamped diffusion
# of 2026-12-07: docs/methods/boundaries.md). The double build also keeps
# the seed digests (tests/reference/seed_bitwise_digests.csv, which only a
# double build can hold): the default build's seed_bitwise suite run
# against it (SPH_TEST_EXECUTABLE, tests/cli_support.hpp).
#   other_precision_build.sh PRECISION SOURCE_DIR WORK_DIR PYTHON SPH_TESTS [SPH_NATIVE]
# PYTHON: one with numpy and VTK (Debian's /usr/bin/python3); SPH_TESTS: the
# default build's test program; SPH_NATIVE: the outer build's (ON by
# default). About 6 minutes on 2 cores, most of it the build.
set -euo pipefail
precision=$1 src=$2 work=$3 py=$4 tests=$5 native=${6:-ON}
case "$precision" in
  double) other=mixed ;;
  mixed) other=double ;;
  *) echo "FAILED: precision '$precision'"; exit 1 ;;
esac
"$py" -c "import numpy, vtkmodules" 2> /dev/null ||
  { echo "FAILED: $py lacks numpy or VTK (Debian's python3: scripts/setup.sh)"; exit 1; }
mkdir -p "$work"
cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DSPH_PRECISION="$precision" -DSPH_NATIVE="$native" \
  > "$work/configure.log" 2>&1 || { echo "FAILED: configuring the $precision build"; tail -20 "$work/configure.log"; exit 1; }
cmake --build "$work/build" -j2 --target sph > "$work/build.log" 2>&1 ||
  { echo "FAILED: building the $precision sph"; tail -40 "$work/build.log"; exit 1; }
version=$("$work/build/sph" --version)
echo "$version"
case "$version" in *"(precision $precision)"*) ;; *) echo "FAILED: the $precision build says '$version'"; exit 1 ;; esac
# A case asking for the other precision is refused by this build, naming the option.
if "$work/build/sph" check "$src/cases/dam_break.case" --precision "$other" > "$work/refused.log" 2>&1; then
  echo "FAILED: the $precision build ran a case asking for precision = $other"; exit 1
fi
grep -q "cmake -DSPH_PRECISION=$other" "$work/refused.log" || { echo "FAILED: $(cat "$work/refused.log")"; exit 1; }
if [ "$precision" = double ]; then
  SPH_TEST_EXECUTABLE="$work/build/sph" "$tests" --run_test=seed_bitwise --log_level=test_suite ||
    { echo "FAILED: the seed digests with the double build"; exit 1; }
fi
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
    echo "FAILED: the $precision build's $name run ($*): $(grep -m1 'error' "$work/leaks_$name.log")"
    exit 1
  fi
  grep "wall guard" "$work/leaks_$name.log"
done
