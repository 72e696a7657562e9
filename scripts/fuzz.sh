#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang into build-fuzz/ and runs each one:
# first every input of its regressions/ and corpus/ folders once, then fuzzing from a fresh
# working corpus copied from those seeds into build-fuzz/fuzz/work/ (the committed corpus is
# never modified). Fuzzing is bounded by executions (RUNS below, about 20 s each here), not by
# time, so that a slower or busier machine does the same amount of fuzzing, from a fixed seed
# (SURFVP_FUZZ_SEED, default 1). libFuzzer is still not exactly repeatable (two runs of one
# seed differ by a few corpus entries), so CI can find what a run here did not: such a finding
# is a real bug, kept as a regression input. SURFVP_FUZZ_SECONDS=N fuzzes N seconds a target
# instead (by hand, to look further). Prints one summary line per
# target and writes the table to build-fuzz/fuzz-summary.md. A crash, sanitizer report, leak,
# timeout or out-of-memory fails the script; the input that caused it stays in
# build-fuzz/fuzz/artifacts/<target>/, to be copied into tests/fuzz/regressions/<target>/.
#   scripts/fuzz.sh [TARGET...]      (default: every target; tests/fuzz/README.md lists them)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh
install_missing "${RUN_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"

readonly BUILD=build-fuzz
readonly SOURCE=tests/fuzz
readonly SEED=${SURFVP_FUZZ_SEED:-1}
# Executions per target: about 10-20 s each on the CI machine (2 cores).
declare -A RUNS=([scenario]=14000 [units]=1000000 [registers]=20000 [register_bank]=150000
                 [keypoint_file]=45000 [homography]=60000 [poses]=70000 [sweep_file]=25000 [sweep_db]=150000
                 [compare_json]=100000 [precision_axis]=100000)
# A cap, so that a much slower machine still ends; the summary says when it cut a target short.
readonly CAP_SECONDS=120
# Per input: 10 s is a hang; no single allocation above 512 MiB and no more than 2 GiB in all
# (direct mode's DDR is at most 256 MiB, calloc'd once per input).
readonly LIMITS=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 -max_len=4096)

CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DSURFVP_FUZZ=ON -DCMAKE_BUILD_TYPE=Debug >/dev/null
nice -n 10 cmake --build "$BUILD" -j2 --target fuzzers

if [ $# -gt 0 ]; then targets=("$@"); else read -r -a targets < "$BUILD/fuzz/targets.txt"; fi

summary="$BUILD/fuzz-summary.md"
bounded_by="the executions scripts/fuzz.sh sets per target"
[ -z "${SURFVP_FUZZ_SECONDS:-}" ] || bounded_by="$SURFVP_FUZZ_SECONDS s per target"
{
  echo "# Fuzzing: seed $SEED, $bounded_by"
  echo
  echo "| target | executions | seconds | exec/s | coverage | corpus (seeds -> end) | result |"
  echo "|---|---|---|---|---|---|---|"
} > "$summary"
failed=0

stat() { sed -n "s/^stat::$1: *//p" "$2" | tail -1; }

# One target: its seeds, then fuzzing; its summary row goes to rows/<target>.md. A target that
# finds something still writes its row; one that cannot run at all (not libFuzzer's main, no
# RUNS entry, a failing command under set -e) writes none, which the summary reports.
fuzz_one() {
  local t=$1
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
    if [ -n "${SURFVP_FUZZ_SECONDS:-}" ]; then
      bound=(-max_total_time="$SURFVP_FUZZ_SECONDS")
    else
      [ -n "${RUNS[$t]:-}" ] || { echo "fuzz: no RUNS entry for target $t in $0" >&2; exit 1; }
      bound=(-runs="${RUNS[$t]}" -max_total_time="$CAP_SECONDS")
    fi
    # -reload=0: the corpus folder is this process's own, nothing else adds to it.
    if ! "$exe" "${LIMITS[@]}" -seed="$SEED" "${bound[@]}" -reload=0 -print_final_stats=1 \
         -artifact_prefix="$artifacts" "$work" > "$log" 2>&1; then
      result=FOUND
    fi
    took=$(( $(date +%s) - began ))
  fi

  if [ "$result" = ok ]; then
    runs=$(stat number_of_executed_units "$log")
    if [ -z "${SURFVP_FUZZ_SECONDS:-}" ] && [ "$runs" -lt "${RUNS[$t]}" ]; then
      echo "fuzz: $t: cut short by the ${CAP_SECONDS} s cap after $runs of ${RUNS[$t]} executions" >&2
    fi
    rate=$(stat average_exec_per_sec "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    line="| $t | $runs | $took | $rate | $cov | $start -> $(find "$work" -type f | wc -l) | ok |"
  else
    found=$(find "$artifacts" -type f | head -1)
    kind=$(grep -m1 -oE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer): [a-z-]+|runtime error|surfvp fuzz: BUG' "$log" "$log.seeds" 2>/dev/null | head -1 | cut -d: -f2- || true)
    line="| $t | | | | | | $result: ${kind:-see the log} |"
    echo "fuzz: $t: $result (${kind:-see $log}); log $log${found:+; input $found}" >&2
    [ -n "$found" ] && echo "fuzz: fix the cause, then copy $found into $SOURCE/regressions/$t/ (kept forever, run by every CI run)" >&2
  fi
  echo "$line" > "$BUILD/fuzz/rows/$t.md"
  echo "fuzz: $line"
}

# Two targets at a time (the machine has 2 cores); each has its own folders and seed, so the
# executions and results are those of one at a time.
rm -rf "$BUILD/fuzz/rows"
mkdir -p "$BUILD/fuzz/rows"
for t in "${targets[@]}"; do
  fuzz_one "$t" &
  while [ "$(jobs -rp | wc -l)" -ge 2 ]; do wait -n || true; done
done
wait
for t in "${targets[@]}"; do
  row="$BUILD/fuzz/rows/$t.md"
  [ -f "$row" ] || { echo "fuzz: $t: no result (see above)" >&2; failed=1; continue; }
  cat "$row" >> "$summary"
  grep -q "| ok |$" "$row" || failed=1
done

echo "fuzz: summary in $summary"
exit $failed
