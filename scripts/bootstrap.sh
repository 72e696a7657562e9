#!/usr/bin/env bash
# Sets up a Debian 12 machine for surfvp and builds it (Release, into build/), then:
#   run   simulates the default scenario
#   test  builds the tests too and runs the whole suite through ctest (under 10 minutes from a
#         fresh clone on 2 cores; the sanitizer suite and fuzzing are scripts/sanitize.sh and
#         scripts/fuzz.sh, which CI runs after it)
#   calibrate  re-measures the software stage's PPC440 prices (surfvp calibrate: qemu-ppc on
#         the cross-compiled stage), writes them to sw/cpu_cost/calibration.json, rebuilds
# Installing is idempotent: only missing Debian packages are installed, so a second call
# goes straight to the (incremental) build. Run as root or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

readonly DEFAULT_SCENARIO=scenarios/budget_1024x768.yaml
source scripts/packages.sh

usage() { echo "usage: $0 run|test|calibrate" >&2; exit 2; }
[ $# -eq 1 ] || usage
case "$1" in run|test|calibrate) ;; *) usage ;; esac

# `run` needs the simulator alone: no test packages, no test binaries, no firmware.
if [ "$1" = run ]; then
  install_missing "${RUN_PACKAGES[@]}"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSURFVP_TESTS=OFF >/dev/null
  cmake --build build -j2 --target surfvp
else
  install_missing "${RUN_PACKAGES[@]}" "${TEST_PACKAGES[@]}"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSURFVP_TESTS=ON >/dev/null
  cmake --build build -j2
fi

case "$1" in
  run) ./build/surfvp run "$DEFAULT_SCENARIO" || [ $? -eq 1 ] ;;  # 1: the budget verdict, reported, not a failure to run
  test) (cd build && ctest --output-on-failure -j2) ;;
  calibrate)
    ./build/surfvp calibrate --table sw/cpu_cost/calibration.json --out traces/calibration
    cp traces/calibration/calibration.md sw/cpu_cost/calibration.md
    cmake --build build -j2 ;;  # the build embeds the new table
esac
