#!/usr/bin/env bash
# test.sh's sanitizer stage, also alone: the Python tests marked `sanitizer` but not
# `repeats_paths` (python_tests/pytest.ini) against the FMUs of build-asan/ (clang, ASan + UBSan:
# scripts/build-asan.sh makes them), any sanitizer report fails it.
#
#   bash scripts/sanitizer-stage.sh                                   # the stage as test.sh runs it
#   bash scripts/sanitizer-stage.sh python_tests/test_port.py -k work # those tests only (any
#                                                                     # pytest arguments; a path
#                                                                     # under python_tests/ replaces
#                                                                     # the marker selection)
#
# A sanitized shared object needs the sanitizer runtime loaded first: it is preloaded into Python
# (and so into the catalogue's child processes); clang's ASan runtime holds its UBSan runtime. No
# leak check here: CPython leaks by design; test_valgrind.py checks the FMU's leaks.
# halt_on_error: the first report ends the process with exit code 1 (a failed child in the
# catalogue, pytest itself otherwise). Reports go to files (pytest would swallow the stderr of a
# process that dies under its capture): any report fails the stage and is printed, whatever
# pytest says. PLATEIMPACT_PYTEST_WORKERS sets the workers (default auto; 0: one process).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
fmu="$repo/build-asan/PlateImpact.fmu"
[ -f "$fmu" ] || { echo "sanitizer-stage.sh: $fmu missing: bash scripts/build-asan.sh" >&2; exit 1; }
runtime="$(clang -print-runtime-dir)/libclang_rt.asan-x86_64.so"
[ -f "$runtime" ] || { echo "sanitizer-stage.sh: $runtime not found (clang -print-runtime-dir)" >&2; exit 1; }
reports="$repo/build-asan/sanitizer-reports"
rm -rf "$reports" && mkdir -p "$reports"

# What runs: the files marked `sanitizer` — the FMI layer, every engine's stepping and FMU states,
# reset and threads, the port, inputs without derivatives, damaged states, random call sequences,
# stability cases — but the tests marked `repeats_paths` (studies, and runs that repeat the code
# paths of a test here at more cost: each names the tests here, or the fuzz harness, that run
# them; python_tests/test_sanitizer_selection.py checks the names). Markers, not name
# substrings: a renamed test keeps its place. Not here: valgrind (test_valgrind.py) and the
# packaging checks (a sanitizer build's packaging is not the product's).
# --dist loadfile: a file's tests in one worker. Under ASan + UBSan a plate's setup costs 2–4 s of
# CPU (0.6 s in the release build; 12–22 s before Eigen's dense eigensolver was left uninstrumented,
# solver/CMakeLists.txt) and is made once per worker and plate (the FMU's cache):
# spread test by test over the workers, every plate a file shares between its tests was built in
# both (issue 54, measured: 367 s of CPU with the tests spread, see docs/contributing.md).
marks="sanitizer and not repeats_paths"
selection=(python_tests -m "$marks")
for arg in "$@"; do
  case "$arg" in python_tests/*) selection=() ;; esac
done
echo "sanitizer-stage.sh: pytest ${selection[*]:+${selection[0]} -m \"$marks\" }$* against build-asan/PlateImpact.fmu"
status=0
LD_PRELOAD="$runtime${LD_PRELOAD:+ $LD_PRELOAD}" \
ASAN_OPTIONS="detect_leaks=0:halt_on_error=1:log_path=$reports/asan${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}" \
PLATEIMPACT_FMU="$fmu" \
  "$repo/.venv/bin/python" -m pytest -q -n "${PLATEIMPACT_PYTEST_WORKERS:-auto}" --dist loadfile "${selection[@]}" "$@" || status=$?
if [ -n "$(ls -A "$reports")" ]; then
  for report in "$reports"/*; do
    echo "sanitizer-stage.sh: sanitizer report $report:" >&2
    cat "$report" >&2
  done
  echo "sanitizer-stage.sh: FAILED: $(ls "$reports" | wc -l) report(s) in $reports" >&2
  exit 1
fi
[ "$status" = 0 ] || echo "sanitizer-stage.sh: FAILED (pytest exit code $status)" >&2
exit "$status"
