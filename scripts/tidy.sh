#!/usr/bin/env bash
# clang-tidy with the project's .clang-tidy over the project's source files, each compiled alone as a
# configuration of its own in build/tidy says (never built). About as long as a build.
#   scripts/tidy.sh [FILE...]     (default: every .cpp of models, sw, platform and tests)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh
install_missing "${RUN_PACKAGES[@]}" clang-tidy
# The build's commands compile several files at once (unity builds) and precompile headers with
# GCC, which clang cannot read: clang-tidy takes those of a configuration of its own (never
# built), each file alone, without the precompiled headers.
cmake -S . -B build/tidy -DCMAKE_BUILD_TYPE=Release -DSURFVP_TESTS=ON -DSURFVP_UNITY_BUILD=OFF \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > /dev/null
sed -i -e 's| -Winvalid-pch||g' -e 's| -include [^ ]*cmake_pch.hxx||g' build/tidy/compile_commands.json
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files 'models/*.cpp' 'sw/*.cpp' 'platform/*.cpp' 'tests/*.cpp' | grep -v '^tests/fuzz/'); fi
printf '%s\n' "${files[@]}" | xargs -P 2 -n 8 clang-tidy -p build/tidy --quiet
