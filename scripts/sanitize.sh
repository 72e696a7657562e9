#!/usr/bin/env bash
# The whole test suite again, built with AddressSanitizer and UndefinedBehaviorSanitizer
# (float-cast-overflow included; any report aborts the process, so a test cannot pass over
# one) into build-asan/. The CLI tests run the sanitized surfvp, error paths included.
# Called by `bootstrap.sh test` after the Release suite; run it alone after a bootstrap.
set -euo pipefail
cd "$(dirname "$0")/.."

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DSURFVP_SANITIZE=ON >/dev/null
cmake --build build-asan -j2
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:detect_stack_use_after_return=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd build-asan && ctest --output-on-failure -j2
