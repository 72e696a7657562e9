# Debian 12 packages by what needs them, and the one function that installs those missing.
# Sourced by bootstrap.sh and fuzz.sh. Installing is idempotent: a second call installs
# nothing. Run as root or as a user with sudo.

# Building surfvp and running its scenarios.
readonly RUN_PACKAGES=(
  build-essential cmake pkg-config
  libsystemc-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libopencv-dev libeigen3-dev
  zlib1g-dev                    # CRC-32 of the cache folder's entries
  libsqlite3-dev                # surfvp sweep: one row per point in the sweep folder's database
  opencv-doc visp-images-data   # real images: the shipped scenarios and the tests read them
)
# The test suite and the benchmarks, on top of RUN_PACKAGES.
readonly TEST_PACKAGES=(
  libgtest-dev libbenchmark-dev
  clang-format                  # tests/platform/style_test.cpp: the layout .clang-format gives
  libxml2-dev                   # tests read report.html as XML
  g++-powerpc-linux-gnu qemu-user  # surfvp calibrate: the software stage built for the PPC440, run on an ISS
  slurm-wlm munge               # a one-node Slurm cluster in a test: surfvp sweep --slurm end to end
  verilator                     # the FHG datapath in Verilog (models/fhg/rtl): verilated, co-simulated, fhg.model=rtl
  yosys                         # the same Verilog synthesized for the FPGA (docs/rtl.md), beside the resource model
)
# scripts/fuzz.sh: libFuzzer targets with ASan/UBSan (tests/fuzz).
readonly FUZZ_PACKAGES=(clang libclang-rt-14-dev)

install_missing() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  echo "surfvp: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}
