#!/usr/bin/env bash
# All tests: the style check (clang-format, ruff), the C++ unit tests (ctest) and the Python
# suite through fmpy (pytest); then the
# sanitizer stage: an AddressSanitizer + UndefinedBehaviorSanitizer build of the FMU in
# build-asan/ and the part of the Python suite that reaches every code path of the FMU, run
# against it. Any sanitizer report fails the stage. Then the fuzz stage: the libFuzzer
# harnesses of fuzz/ for 20 s each (scripts/fuzz.sh; longer campaigns: PLATEIMPACT_FUZZ_SECONDS or scripts/fuzz.sh on demand), any finding fails it. Before the Python
# suite, the win64 stage builds the dual-platform FMU (scripts/build-win64.sh, mingw-w64) so
# that python_tests/test_win64.py runs it under Wine. Arguments go to both pytest runs;
# Then the aarch64 stage: the FMI 3.0 FMU with aarch64-linux (scripts/build-aarch64.sh), run under
# qemu-aarch64 by python_tests/test_aarch64.py.
# PLATEIMPACT_WIN64_STAGE=0 / PLATEIMPACT_AARCH64_STAGE=0 / PLATEIMPACT_SANITIZER_STAGE=0 /
# PLATEIMPACT_FUZZ_STAGE=0 skip a stage.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$repo/scripts/setup.sh"
bash "$repo/scripts/check-format.sh"
cd "$repo/build"
ctest --output-on-failure -j"$(nproc)"
cd "$repo"
if [ "${PLATEIMPACT_WIN64_STAGE:-1}" != 0 ]; then
  echo "test.sh: win64 stage: build/dist/PlateImpact.fmu (linux64 + win64) and build/dist/fmi3/PlateImpact.fmu (+ x86_64-windows), tested under Wine by test_win64.py"
  bash "$repo/scripts/build-win64.sh"
fi
if [ "${PLATEIMPACT_AARCH64_STAGE:-1}" != 0 ]; then
  echo "test.sh: aarch64 stage: build/dist/fmi3/PlateImpact.fmu (+ aarch64-linux), run under qemu-aarch64 by test_aarch64.py"
  bash "$repo/scripts/build-aarch64.sh"
fi
# qemu-x86_64 (Debian's qemu-user): test_golden.py runs the golden under emulated CPUs
# (Nehalem: no AVX, no FMA; Haswell: AVX2 and FMA) beside the native run.
if ! command -v qemu-x86_64 >/dev/null; then
  echo "test.sh: installing Debian packages: qemu-user (the golden on other CPUs)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq qemu-user >/dev/null
fi
"$repo/.venv/bin/python" -m pytest -q python_tests "$@"

fuzz_stage() {
  [ "${PLATEIMPACT_FUZZ_STAGE:-1}" = 0 ] && return 0
  echo "test.sh: fuzz stage: fuzz/ harnesses, ${PLATEIMPACT_FUZZ_SECONDS:-20} s each (scripts/fuzz.sh)"
  bash "$repo/scripts/fuzz.sh" --seconds "${PLATEIMPACT_FUZZ_SECONDS:-20}"
}

if [ "${PLATEIMPACT_SANITIZER_STAGE:-1}" = 0 ]; then
  fuzz_stage
  exit 0
fi

# --- Sanitizer stage ------------------------------------------------------------------------
# Only the FMUs, FMI 2.0 and 3.0 (no unit tests, no benchmark), optimized as shipped plus line
# tables for the reports; incremental like build/.
PLATEIMPACT_BUILD_DIR="$repo/build-asan" PLATEIMPACT_BUILD_TARGET="PlateImpactFmu PlateImpactFmu3" \
PLATEIMPACT_CMAKE_ARGS="-DPLATEIMPACT_SANITIZE=ON -DPLATEIMPACT_TESTS=OFF -DCMAKE_CXX_FLAGS=-g1" \
  bash "$repo/scripts/setup.sh"
# A sanitized shared object needs the sanitizer runtimes loaded first: preload them into Python
# (and so into the catalogue's child processes). No leak check here: CPython leaks by design;
# test_valgrind.py checks the FMU's leaks. halt_on_error: the first report ends the process
# with exit code 1 (a failed child in the catalogue, pytest itself otherwise). Reports go to
# files (pytest would swallow the stderr of a process that dies under its capture): any report
# fails the stage and is printed, whatever pytest says.
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
status=0
LD_PRELOAD="${runtimes# }${LD_PRELOAD:+ $LD_PRELOAD}" \
ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:log_path=$reports/asan${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}" \
PLATEIMPACT_FMU="$repo/build-asan/PlateImpact.fmu" \
  "$repo/.venv/bin/python" -m pytest -q python_tests -m "$sanitizer_marks" "$@" || status=$?
if [ -n "$(ls -A "$reports")" ]; then
  for report in "$reports"/*; do
    echo "test.sh: sanitizer report $report:" >&2
    cat "$report" >&2
  done
  echo "test.sh: sanitizer stage FAILED: $(ls "$reports" | wc -l) report(s) in $reports" >&2
  exit 1
fi
[ "$status" = 0 ] || echo "test.sh: sanitizer stage FAILED (pytest exit code $status)" >&2
fuzz_stage || status=1
exit "$status"
