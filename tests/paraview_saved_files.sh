#!/bin/bash
# ctest paraview.saved_particle_files: an sph snapshot (the default dam
# break after 2 steps, with walls), saved by pvpython's SaveData in every
# data mode (paraview_save_modes.py), then read back by sph
# (sph_tests --run_test=paraview_files, tests/test_io.cpp).
#   paraview_saved_files.sh SPH SPH_TESTS PVPYTHON SOURCE_DIR WORK_DIR
set -euo pipefail
sph=$1 tests=$2 pvpython=$3 src=$4 work=$5
rm -rf "$work"
mkdir -p "$work"
"$sph" run "$src/cases/dam_break.case" --output "$work/run" --end_time 0.0001 --output_every 2 \
  --threads 1 --no-progress > "$work/run.log"
cp "$work/run/dam_break_00001.vtp" "$work/original.vtp"
"$pvpython" "$src/tests/paraview_save_modes.py" "$work/original.vtp" "$work/saved"
SPH_PARAVIEW_FILES="$work" "$tests" --run_test=paraview_files --log_level=test_suite
