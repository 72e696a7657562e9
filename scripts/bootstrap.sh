#!/usr/bin/env bash
# Sets up a Debian 12 machine for surfvp and builds it (Release, into build/), then:
#   run   simulates the default scenario
#   test  runs the whole test suite through ctest
#   calibrate  re-measures the software stage's PPC440 prices (surfvp calibrate: qemu-ppc on
#         the cross-compiled stage), writes them to sw/cpu_cost/calibration.json, rebuilds
# Installing is idempotent: only missing Debian packages are installed, so a second call
# goes straight to the (incremental) build. Run as root or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

readonly DEFAULT_SCENARIO=scenarios/budget_1024x768.yaml
readonly PACKAGES=(
  build-essential cmake pkg-config
  libsystemc-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libopencv-dev libeigen3-dev libgtest-dev libbenchmark-dev
  libxml2-dev                   # tests read report.html as XML
  zlib1g-dev                    # CRC-32 of the cache folder's entries
  libsqlite3-dev                # surfvp sweep: one row per point in the sweep folder's database
  opencv-doc visp-images-data   # real images for tests and scenarios
  g++-powerpc-linux-gnu qemu-user  # surfvp calibrate: the software stage built for the PPC440, run on an ISS
  clang libclang-rt-14-dev      # scripts/fuzz.sh: libFuzzer targets with ASan/UBSan (tests/fuzz)
  slurm-wlm munge               # a one-node Slurm cluster in a test: surfvp sweep --slurm end to end
)

usage() { echo "usage: $0 run|test|calibrate" >&2; exit 2; }
[ $# -eq 1 ] || usage
case "$1" in run|test|calibrate) ;; *) usage ;; esac

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  echo "surfvp: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

install_missing
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2

case "$1" in
  run) ./build/surfvp run "$DEFAULT_SCENARIO" || [ $? -eq 1 ] ;;  # 1: the budget verdict, reported, not a failure to run
  test)
    (cd build && ctest --output-on-failure -j2)
    ./scripts/sanitize.sh  # the suite again under ASan + UBSan (build-asan)
    ./scripts/fuzz.sh ;;   # the libFuzzer targets (tests/fuzz): regressions, seeds, then 20 s each
  calibrate)
    ./build/surfvp calibrate --table sw/cpu_cost/calibration.json --out traces/calibration
    cp traces/calibration/calibration.md sw/cpu_cost/calibration.md
    cmake --build build -j2 ;;  # the build embeds the new table
esac
