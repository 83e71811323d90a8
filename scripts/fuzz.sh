#!/usr/bin/env bash
# Coverage-guided fuzzing of the FMU's C API (fuzz/): builds the libFuzzer harnesses with clang,
# ASan and UBSan in build-asan/ (scripts/build-asan.sh: the build whose FMUs the sanitizer stage
# runs, the same object files) and runs each on a working copy of its seed corpus
# (fuzz/corpus/<harness>). Any crash, leak, timeout or sanitizer report fails the run; the
# input that caused it is left in build-asan/findings/ (copy it into fuzz/corpus/<harness> as a
# regression case once fixed).
#
#   bash scripts/fuzz.sh                       # 60 s per harness (test.sh: --seconds 20 --parallel)
#   bash scripts/fuzz.sh --seconds 600         # longer
#   bash scripts/fuzz.sh --runs 1000000        # a number of executions per harness
#   bash scripts/fuzz.sh --parallel ...        # the three harnesses at once (one process each)
#   bash scripts/fuzz.sh --harness parameters  # one harness only (repeatable)
#   bash scripts/fuzz.sh --build-only          # build the harnesses, run nothing
#   bash scripts/fuzz.sh --coverage            # replay the corpora with source-based coverage:
#                                              # line coverage of fmu/ and solver/ (build-cov/)
#   bash scripts/fuzz.sh --merge               # minimize the working corpora into fuzz/corpus/
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
harnesses=(call_sequence deserialize_state parameters)
limit=(-max_total_time=60)
mode=run
parallel=0
chosen=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) limit=(-max_total_time="$2"); shift 2 ;;
    --runs) limit=(-runs="$2"); shift 2 ;;
    --coverage) mode=coverage; shift ;;
    --merge) mode=merge; shift ;;
    --parallel) parallel=1; shift ;;
    --build-only) mode=build; shift ;;
    --harness) chosen+=("$2"); shift 2 ;;
    *) echo "fuzz.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if [ ${#chosen[@]} -gt 0 ]; then harnesses=("${chosen[@]}"); fi

bash "$repo/scripts/packages.sh" fuzz  # when missing

if [ "$mode" = coverage ]; then
  bash "$repo/scripts/build-asan.sh" --coverage fuzzers
  profiles="$repo/build-cov/profiles"
  rm -rf "$profiles" && mkdir -p "$profiles"
  objects=()
  for h in "${harnesses[@]}"; do
    corpus="$repo/build-asan/corpus/$h"
    [ -d "$corpus" ] || corpus="$repo/fuzz/corpus/$h"
    LLVM_PROFILE_FILE="$profiles/$h.profraw" ASAN_OPTIONS=detect_leaks=0 \
      "$repo/build-cov/fuzz/fuzz_$h" -runs=0 "$corpus" >/dev/null 2>&1
    objects+=(-object "$repo/build-cov/fuzz/fuzz_$h")
  done
  llvm-profdata merge -sparse "$profiles"/*.profraw -o "$profiles/all.profdata"
  llvm-cov report "${objects[@]:1}" -instr-profile="$profiles/all.profdata" \
    "$repo/fmu" "$repo/solver" > "$profiles/report.txt"
  cat "$profiles/report.txt"
  # Line coverage per directory (columns: lines, missed lines of llvm-cov's report)
  awk '/^(fmu|solver)\// && $8 ~ /^[0-9]+$/ { d = substr($1, 1, index($1, "/") - 1); L[d] += $8; M[d] += $9 }
       END { for (d in L) printf "fuzz.sh: coverage of %s/: %d of %d lines (%.1f %%)\n", d, L[d] - M[d], L[d], 100 * (L[d] - M[d]) / L[d] }' \
    "$profiles/report.txt"
  exit 0
fi

bash "$repo/scripts/build-asan.sh" fuzzers
[ "$mode" = build ] && exit 0
findings="$repo/build-asan/findings"
mkdir -p "$findings"

fuzz_one() {  # fuzz_one <harness>: runs it, prints its verdict, returns non-zero on a finding
  local h="$1" corpus="$repo/build-asan/corpus/$1" log="$repo/build-asan/$1.log"
  mkdir -p "$corpus"
  # The seed corpus first (regressions included), then new inputs into the working copy.
  if "$repo/build-asan/fuzz/fuzz_$h" "${limit[@]}" -timeout=30 -rss_limit_mb=4096 -print_final_stats=1 \
       -artifact_prefix="$findings/$h-" "$corpus" "$repo/fuzz/corpus/$h" >"$log" 2>&1; then
    local runs
    runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$' || true)
    echo "fuzz.sh: $h: ${runs:-?} executions, no finding"
  else
    echo "fuzz.sh: $h: FINDING (log $log, input in $findings):" >&2
    grep -E "ERROR|SUMMARY|runtime error|#[0-9]+ " "$log" | head -n 30 >&2
    return 1
  fi
}

status=0
if [ "$mode" = merge ]; then
  for h in "${harnesses[@]}"; do
    corpus="$repo/build-asan/corpus/$h"
    mkdir -p "$corpus"
    rm -rf "$repo/fuzz/corpus/$h.new" && mkdir -p "$repo/fuzz/corpus/$h.new"
    "$repo/build-asan/fuzz/fuzz_$h" -merge=1 "$repo/fuzz/corpus/$h.new" "$repo/fuzz/corpus/$h" "$corpus" 2>/dev/null
    rm -rf "$repo/fuzz/corpus/$h" && mv "$repo/fuzz/corpus/$h.new" "$repo/fuzz/corpus/$h"
    echo "fuzz.sh: $h: $(ls "$repo/fuzz/corpus/$h" | wc -l) inputs in fuzz/corpus/$h"
  done
elif [ "$parallel" = 1 ]; then
  pids=()
  for h in "${harnesses[@]}"; do fuzz_one "$h" & pids+=($!); done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
else
  for h in "${harnesses[@]}"; do fuzz_one "$h" || status=1; done
fi
exit "$status"
