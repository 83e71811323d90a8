#!/usr/bin/env bash
# All tests, in stages (docs/contributing.md lists them; each prints "test.sh: [time] <stage>: N s"):
#  1. setup: venv and the incremental build of build/ (scripts/setup.sh); style (clang-format, ruff);
#  2. ctest, beside one apt-get call for the packages of every other stage (scripts/packages.sh);
#  3. builds in two lanes: the cross builds (scripts/build-win64.sh, mingw-w64, for Wine;
#     scripts/build-aarch64.sh, for qemu-aarch64; both packaged into build/dist/) beside the
#     AddressSanitizer + UBSan build of the FMUs in build-asan/ and the libFuzzer harnesses in
#     build-fuzz/ (scripts/fuzz.sh --build-only); logs in build/logs/;
#  4. the Python suite through fmpy (pytest -n auto, pytest-xdist: one worker per core);
#  5. sanitizers: the tests marked `sanitizer` but not `repeats_paths` against build-asan/'s FMU;
#     any sanitizer report fails the stage;
#  6. fuzz: the harnesses of fuzz/, 20 s each, at once (PLATEIMPACT_FUZZ_SECONDS; longer campaigns:
#     scripts/fuzz.sh on demand); any finding fails it.
# Arguments go to both pytest runs. PLATEIMPACT_WIN64_STAGE=0 / PLATEIMPACT_AARCH64_STAGE=0 /
# PLATEIMPACT_SANITIZER_STAGE=0 / PLATEIMPACT_FUZZ_STAGE=0 skip a stage; PLATEIMPACT_PYTEST_WORKERS
# sets the workers (default auto; 0: one process).
#
#   bash test.sh --quick   # the developer loop: the build, the fast unit tests and the Python
#                          # tests not marked `slow` (python_tests/conftest.py), no other stage
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$repo"
py="$repo/.venv/bin/python"
workers=(-n "${PLATEIMPACT_PYTEST_WORKERS:-auto}")
start=$(date +%s) last=$(date +%s)
took() {  # took <stage>: the wall time since the last call, and in all
  local now
  now=$(date +%s)
  echo "test.sh: [time] $1: $((now - last)) s (total $((now - start)) s)"
  last=$now
}
on() { [ "${!1:-1}" != 0 ]; }  # on <PLATEIMPACT_*_STAGE>: is the stage wanted

if [ "${1:-}" = --quick ]; then
  shift
  bash scripts/setup.sh
  took setup
  # the unit tests but the long runs (a million steps, the convergence orders): ctest -L would need labels
  (cd build && ctest --output-on-failure -j"$(nproc)" -E 'LongRun|ImpactLaws.PerStepEnergyIdentityWithContact|Converges')
  took "ctest (fast)"
  "$py" -m pytest -q "${workers[@]}" python_tests -m "not slow" "$@"
  took "pytest (not slow)"
  exit 0
fi

# The packages of build/ first (a no-op after run.sh); those of the other stages in one apt-get
# call in the background while the unit tests run (downloads and dpkg beside the CPU).
bash scripts/packages.sh base
bash scripts/setup.sh
bash scripts/check-format.sh
took "setup and style"
groups=(qemu)  # qemu-user: test_golden.py runs the golden under emulated x86-64 CPUs
on PLATEIMPACT_WIN64_STAGE && groups+=(win64)
on PLATEIMPACT_AARCH64_STAGE && groups+=(aarch64)
on PLATEIMPACT_FUZZ_STAGE && groups+=(fuzz)
mkdir -p build/logs
bash scripts/packages.sh "${groups[@]}" >build/logs/packages.log 2>&1 &
packages_pid=$!
ctest_status=0
(cd build && ctest --output-on-failure -j"$(nproc)") || ctest_status=$?
took "ctest (beside the packages)"
packages_status=0
wait "$packages_pid" || packages_status=$?
cat build/logs/packages.log
[ "$packages_status" = 0 ] || { echo "test.sh: installing packages FAILED (log above)" >&2; exit 1; }
took packages
[ "$ctest_status" = 0 ] || { echo "test.sh: ctest FAILED" >&2; exit 1; }

# --- Builds ---------------------------------------------------------------------------------
# Two lanes, each building with every core: on two cores the configure steps, the SuiteSparse
# downloads, the links and the serial tails of one lane fill the other's gaps.
# The ASan+UBSan build: only the FMUs, FMI 2.0 and 3.0, at -O1 (what ASan recommends: half the
# compile time of -O3 and the same arithmetic, -ffp-contract=off) as one unity build (each target's
# sources compiled a few at a time: Eigen parsed and instantiated once per batch) plus line tables
# for the reports.
asan_build() {
  if [ ! -f build-asan/CMakeCache.txt ]; then
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" \
      "-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS=-g1 -DCMAKE_UNITY_BUILD=ON \
      -DPLATEIMPACT_SANITIZE=ON -DPLATEIMPACT_TESTS=OFF >/dev/null
  fi
  cmake --build build-asan -j"$(nproc)" --target PlateImpactFmu PlateImpactFmu3 -- --no-print-directory >/dev/null
  echo "test.sh: built build-asan/PlateImpact.fmu"
}
cross_lane() {
  if on PLATEIMPACT_WIN64_STAGE; then
    echo "test.sh: win64: build/dist/PlateImpact.fmu (linux64 + win64), build/dist/fmi3/PlateImpact.fmu (+ x86_64-windows), for test_win64.py under Wine"
    bash scripts/build-win64.sh
  fi
  if on PLATEIMPACT_AARCH64_STAGE; then
    echo "test.sh: aarch64: build/dist/fmi3/PlateImpact.fmu (+ aarch64-linux), for test_aarch64.py under qemu-aarch64"
    bash scripts/build-aarch64.sh
  fi
}
cross_lane >build/logs/cross.log 2>&1 &
cross_pid=$!
local_status=0
{
  if on PLATEIMPACT_SANITIZER_STAGE; then asan_build; fi
  if on PLATEIMPACT_FUZZ_STAGE; then bash scripts/fuzz.sh --build-only; fi
} >build/logs/local.log 2>&1 || local_status=$?
cross_status=0
wait "$cross_pid" || cross_status=$?
cat build/logs/cross.log build/logs/local.log
took "builds (win64, aarch64 | asan, fuzz)"
[ "$cross_status" = 0 ] || { echo "test.sh: a cross build FAILED (log above)" >&2; exit 1; }
[ "$local_status" = 0 ] || { echo "test.sh: the asan or fuzz build FAILED (log above)" >&2; exit 1; }

# --- The Python suite -----------------------------------------------------------------------
"$py" -m pytest -q "${workers[@]}" python_tests "$@"
took pytest

status=0
# --- Sanitizer stage ------------------------------------------------------------------------
# A sanitized shared object needs the sanitizer runtimes loaded first: preload them into Python
# (and so into the catalogue's child processes). No leak check here: CPython leaks by design;
# test_valgrind.py checks the FMU's leaks. halt_on_error: the first report ends the process
# with exit code 1 (a failed child in the catalogue, pytest itself otherwise). Reports go to
# files (pytest would swallow the stderr of a process that dies under its capture): any report
# fails the stage and is printed, whatever pytest says.
if on PLATEIMPACT_SANITIZER_STAGE; then
  runtimes=""
  for name in libasan.so libubsan.so; do
    path="$(gcc -print-file-name=$name)"
    [ -f "$path" ] || { echo "test.sh: $name not found (gcc -print-file-name=$name)" >&2; exit 1; }
    runtimes="$runtimes $path"
  done
  reports="$repo/build-asan/sanitizer-reports"
  rm -rf "$reports" && mkdir -p "$reports"
  # What runs: the files marked `sanitizer` (pytest.ini) — the FMI layer, the port, the physics,
  # a second importer, inputs without derivatives, damaged states, random call sequences, the
  # stability cases — but the tests marked `repeats_paths` (convergence studies and the stability
  # cases that repeat a covered path at more cost). Markers, not name substrings: a renamed test
  # keeps its place. Not here: valgrind (test_valgrind.py) and the packaging checks (a sanitizer
  # build's packaging is not the product's).
  sanitizer_marks="sanitizer and not repeats_paths"
  echo "test.sh: sanitizer stage: pytest -m \"$sanitizer_marks\" against build-asan/PlateImpact.fmu"
  LD_PRELOAD="${runtimes# }${LD_PRELOAD:+ $LD_PRELOAD}" \
  ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:log_path=$reports/asan${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
  UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}" \
  PLATEIMPACT_FMU="$repo/build-asan/PlateImpact.fmu" \
    "$py" -m pytest -q "${workers[@]}" python_tests -m "$sanitizer_marks" "$@" || status=$?
  if [ -n "$(ls -A "$reports")" ]; then
    for report in "$reports"/*; do
      echo "test.sh: sanitizer report $report:" >&2
      cat "$report" >&2
    done
    echo "test.sh: sanitizer stage FAILED: $(ls "$reports" | wc -l) report(s) in $reports" >&2
    exit 1
  fi
  [ "$status" = 0 ] || echo "test.sh: sanitizer stage FAILED (pytest exit code $status)" >&2
  took sanitizer
fi

if on PLATEIMPACT_FUZZ_STAGE; then
  echo "test.sh: fuzz stage: fuzz/ harnesses, ${PLATEIMPACT_FUZZ_SECONDS:-20} s each, at once (scripts/fuzz.sh)"
  bash scripts/fuzz.sh --parallel --seconds "${PLATEIMPACT_FUZZ_SECONDS:-20}" || status=1
  took fuzz
fi
exit "$status"
