#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang into build-fuzz/ and runs each one:
# first every input of its regressions/ and corpus/ folders once, then fuzzing for
# SURFVP_FUZZ_SECONDS (default 20) from a fresh working corpus copied from those seeds into
# build-fuzz/fuzz/work/ (the committed corpus is never modified). Prints one summary line per
# target and writes the table to build-fuzz/fuzz-summary.md. A crash, sanitizer report, leak,
# timeout or out-of-memory fails the script; the input that caused it stays in
# build-fuzz/fuzz/artifacts/<target>/, to be copied into tests/fuzz/regressions/<target>/.
#   scripts/fuzz.sh [TARGET...]      (default: every target; tests/fuzz/README.md lists them)
set -euo pipefail
cd "$(dirname "$0")/.."

readonly BUILD=build-fuzz
readonly SOURCE=tests/fuzz
readonly SECONDS_PER_TARGET=${SURFVP_FUZZ_SECONDS:-20}
# Per input: 10 s is a hang; no single allocation above 512 MiB and no more than 2 GiB in all
# (direct mode's DDR is at most 256 MiB, calloc'd once per input).
readonly LIMITS=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 -max_len=4096)

CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DSURFVP_FUZZ=ON -DCMAKE_BUILD_TYPE=Debug >/dev/null
nice -n 10 cmake --build "$BUILD" -j2 --target fuzzers

if [ $# -gt 0 ]; then targets=("$@"); else read -r -a targets < "$BUILD/fuzz/targets.txt"; fi

summary="$BUILD/fuzz-summary.md"
{
  echo "# Fuzzing: ${SECONDS_PER_TARGET} s per target"
  echo
  echo "| target | executions | seconds | exec/s | coverage | corpus (seeds -> end) | result |"
  echo "|---|---|---|---|---|---|---|"
} > "$summary"
failed=0

stat() { sed -n "s/^stat::$1: *//p" "$2" | tail -1; }

for t in "${targets[@]}"; do
  exe="$BUILD/fuzz/${t}_fuzz"
  log="$BUILD/fuzz/logs/$t.log"
  artifacts="$BUILD/fuzz/artifacts/$t/"
  work="$BUILD/fuzz/work/$t"
  rm -rf "$work" "$artifacts"
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  # libsystemc.so has a main() too: the fuzzer's must be the one that runs.
  [[ "$("$exe" -help=1 2>&1)" == Usage:* ]] || { echo "fuzz: $exe does not run libFuzzer's main()" >&2; exit 1; }

  mapfile -t seeds < <(find "$SOURCE/regressions/$t" "$SOURCE/corpus/$t" -type f ! -name '.*' | sort)
  result=ok
  if ! "$exe" "${LIMITS[@]}" -artifact_prefix="$artifacts" "${seeds[@]}" > "$log.seeds" 2>&1; then
    result="FAILS ON A COMMITTED INPUT"
  else
    cp "${seeds[@]}" "$work/"
    start=$(find "$work" -type f | wc -l)
    began=$(date +%s)
    # A fixed seed (SURFVP_FUZZ_SEED, default 1) so that CI does not turn red by chance; fuzz
    # longer or with other seeds by hand.
    if ! "$exe" "${LIMITS[@]}" -seed="${SURFVP_FUZZ_SEED:-1}" -max_total_time="$SECONDS_PER_TARGET" -print_final_stats=1 \
         -artifact_prefix="$artifacts" "$work" > "$log" 2>&1; then
      result=FOUND
    fi
    took=$(( $(date +%s) - began ))
  fi

  if [ "$result" = ok ]; then
    runs=$(stat number_of_executed_units "$log")
    rate=$(stat average_exec_per_sec "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    line="| $t | $runs | $took | $rate | $cov | $start -> $(find "$work" -type f | wc -l) | ok |"
  else
    failed=1
    found=$(find "$artifacts" -type f | head -1)
    kind=$(grep -m1 -oE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer): [a-z-]+|runtime error|surfvp fuzz: BUG' "$log" "$log.seeds" 2>/dev/null | head -1 | cut -d: -f2- || true)
    line="| $t | | | | | | $result: ${kind:-see the log} |"
    echo "fuzz: $t: $result (${kind:-see $log}); log $log${found:+; input $found}" >&2
    [ -n "$found" ] && echo "fuzz: fix the cause, then copy $found into $SOURCE/regressions/$t/ (kept forever, run by every CI run)" >&2
  fi
  echo "$line" >> "$summary"
  echo "fuzz: $line"
done

echo "fuzz: summary in $summary"
exit $failed
