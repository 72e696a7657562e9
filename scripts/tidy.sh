#!/usr/bin/env bash
# clang-tidy with the project's .clang-tidy over every project source file of build/ (which
# must have been configured; CMAKE_EXPORT_COMPILE_COMMANDS is on). About as long as a build.
#   scripts/tidy.sh [FILE...]     (default: every .cpp of models, sw, platform and tests)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh
install_missing "${RUN_PACKAGES[@]}" clang-tidy
[ -f build/compile_commands.json ] || { echo "tidy.sh: configure build/ first (scripts/bootstrap.sh test)" >&2; exit 2; }
# The build precompiles headers with GCC, which clang cannot read: the commands clang-tidy
# takes are the build's without them.
mkdir -p build/tidy
sed -e 's| -Winvalid-pch||g' -e 's| -include [^ ]*cmake_pch.hxx||g' build/compile_commands.json > build/tidy/compile_commands.json
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files 'models/*.cpp' 'sw/*.cpp' 'platform/*.cpp' 'tests/*.cpp' | grep -v '^tests/fuzz/'); fi
printf '%s\n' "${files[@]}" | xargs -P 2 -n 8 clang-tidy -p build/tidy --quiet
