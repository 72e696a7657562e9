#!/usr/bin/env bash
# The whole test suite again, built with AddressSanitizer and UndefinedBehaviorSanitizer
# (float-cast-overflow included; any report aborts the process, so a test cannot pass over
# one) into build-asan/. The CLI tests run the sanitized surfvp, error paths included. Every
# test runs but six: Determinism.TheBudgetScenarioTwiceGivesTheSameBytes (the whole budget
# scenario, its ~310 verdict re-simulations and full traces, twice) and
# Correlate.TheDefaultsLieInTheRegionThatReproducesThePaper (145 re-simulations at 1024x768,
# 157 s here) take minutes under the sanitizers, and their code is all sanitized elsewhere
# (the Verdict.*, Correlate.AnotherFrameSize..., trace and run tests); the Release suite runs
# them. Environment.OutOfMemoryIsItsOwnOutcomeNamingTheAllocation runs surfvp under an
# address-space limit (ulimit -v), which AddressSanitizer's shadow memory exceeds before main().
# Synthesize.TheModelsEstimateOfEachPartIsWithinAFifthOfYosys and
# Synthesize.TheWholeLineFifoIsWithinAFifthOfTheModel are 30 and 45 s of yosys, no code of
# surfvp's beyond what Synthesize.AnUnknownFamilyIsBadInput and the export tests run.
# Verdict.TheDoubtIsTheUnknownsJointlyAndTheChangesApart (40 joint samples, 139 s here) runs
# the same doubt and band code as ReportHtml.TheReviewPageCarriesTheVerdictItsDoubtAndWhatCanChange
# (20 samples), which stays. The benchmarks and the second verilated build
# (test_rtl_narrow, tests/CMakeLists.txt) are not built.
# About 20 minutes with -j2.
# CI runs it after the README's test command (.ci/run); it installs what it needs itself.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh
install_missing "${RUN_PACKAGES[@]}" "${TEST_PACKAGES[@]}"

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DSURFVP_SANITIZE=ON -DSURFVP_BENCH=OFF >/dev/null
cmake --build build-asan -j2
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:detect_stack_use_after_return=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# detect_leaks=0: LeakSanitizer does not scan SystemC's coroutine stacks, so what a thread
# still waiting at the end of a simulation holds on its stack is reported as leaked.
# SystemC's switches between coroutine stacks are made known to ASan by
# platform/run/sanitizer_stacks.cpp (without it, an exception after a simulation gave false
# stack reports in ~Fhg / ~Tracer), so the error paths after a simulation run here too.
cd build-asan && ctest --output-on-failure -j2 \
  -E '^(Determinism\.TheBudgetScenarioTwiceGivesTheSameBytes|Correlate\.TheDefaultsLieInTheRegionThatReproducesThePaper|Environment\.OutOfMemoryIsItsOwnOutcomeNamingTheAllocation|Synthesize\.TheModelsEstimateOfEachPartIsWithinAFifthOfYosys|Synthesize\.TheWholeLineFifoIsWithinAFifthOfTheModel|Verdict\.TheDoubtIsTheUnknownsJointlyAndTheChangesApart)$'
