#!/bin/sh
# The speed table of docs/performance.md in one command: builds sph and the
# two yardsticks (Release, in build/ unless BUILD is set), then runs
# bench/speed_table.py (water 2D, seed 2D, water 3D against the yardstick,
# interleaved, 1 and 2 threads, medians of 3). Extra arguments go to
# speed_table.py, e.g. `bench/run.sh --threads 1 --repeats 5`.
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
[ -f "$build/CMakeCache.txt" ] || cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j"$(nproc)" --target sph sph-yardstick sph-yardstick-3d > /dev/null
exec python3 "$root/bench/speed_table.py" --build "$build" "$@"
