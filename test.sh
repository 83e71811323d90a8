#!/usr/bin/env bash
# All tests, in stages (docs/contributing.md lists them; each prints "test.sh: [time] <stage>: N s,
# CPU M s" — wall and user + system time):
#  1. setup: venv and the incremental build of build/ (scripts/setup.sh: every target, the unit
#     tests too; run.sh builds only the FMUs and plate_bench); style (clang-format, ruff) — beside
#     the apt-get calls for the packages of every other stage (scripts/packages.sh: clang first,
#     then the cross compilers and emulators) and, once clang is in, the instrumented build;
#  2. ctest, beside the same;
#  3. builds in three lanes: the one clang build with AddressSanitizer + UBSan of the FMUs and
#     the libFuzzer harnesses in build-asan/ (scripts/build-asan.sh; it starts once clang is
#     installed) beside the cross builds (scripts/build-win64.sh, mingw-w64, for Wine;
#     scripts/build-aarch64.sh, for qemu-aarch64; packaged into build/dist/); logs in build/logs/;
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
start=$(date +%s) last=$(date +%s) cpu_last=0
times_file="$(mktemp)"
trap 'rm -f "$times_file"' EXIT
took() {  # took <stage>: the wall time since the last call, and in all; the same for the CPU
  # time (user + system) of every process test.sh has waited for (a background job's when it ends)
  local now cpu
  now=$(date +%s)
  times >"$times_file"
  cpu=$(awk '{ for (i = 1; i <= 2; i++) { split($i, p, "m"); s += p[1] * 60 + p[2] } } END { printf "%d", s }' "$times_file")
  echo "test.sh: [time] $1: $((now - last)) s, CPU $((cpu - cpu_last)) s (total $((now - start)) s, CPU $cpu s)"
  last=$now cpu_last=$cpu
}
on() { [ "${!1:-1}" != 0 ]; }  # on <PLATEIMPACT_*_STAGE>: is the stage wanted

if [ "${1:-}" = --quick ]; then
  shift
  bash scripts/packages.sh base  # valgrind and clang-format too (run.sh installs only build's)
  bash scripts/setup.sh
  took setup
  # the unit tests but the long ones (the per-step energy identity, the convergence orders)
  (cd build && ctest --output-on-failure -j"$(nproc)" -E 'ImpactLaws.PerStepEnergyIdentityWithContact|Converges')
  took "ctest (fast)"
  "$py" -m pytest -q "${workers[@]}" python_tests -m "not slow" "$@"
  took "pytest (not slow)"
  exit 0
fi

# The packages of build/ first (a no-op after run.sh); those of the other stages in the
# background while build/ is completed and the unit tests run (downloads and dpkg beside the
# CPU): clang with valgrind and clang-format first (base: clang-format shares clang's libllvm14),
# so that the instrumented build and the style check can start, then the cross compilers and the
# emulators, each in one apt-get call (scripts/packages.sh).
bash scripts/packages.sh build
groups=(qemu)  # qemu-user: test_golden_emulated.py runs the golden under emulated x86-64 CPUs
on PLATEIMPACT_WIN64_STAGE && groups+=(win64)
on PLATEIMPACT_AARCH64_STAGE && groups+=(aarch64)
asan_targets=()  # the instrumented build (scripts/build-asan.sh): clang, scripts/packages.sh fuzz
on PLATEIMPACT_SANITIZER_STAGE && asan_targets+=(PlateImpactFmu PlateImpactFmu3)
on PLATEIMPACT_FUZZ_STAGE && asan_targets+=(fuzzers)
mkdir -p build/logs
clang_ready=build/logs/packages-clang.done
rm -f "$clang_ready"
(
  set -e
  if [ ${#asan_targets[@]} -gt 0 ]; then bash scripts/packages.sh base fuzz; else bash scripts/packages.sh base; fi
  touch "$clang_ready"
  bash scripts/packages.sh "${groups[@]}"
) >build/logs/packages.log 2>&1 &
packages_pid=$!
lane() {  # lane <name> <command...>: in the background, its log in build/logs/<name>.log
  local name="$1"
  shift
  "$@" >"build/logs/$name.log" 2>&1 &
  lanes+=("$name:$!")
}
wait_lanes() {  # wait_lanes: prints each lane's log; fails if any lane failed
  local entry name lane_status failed=0
  for entry in "${lanes[@]}"; do
    name="${entry%%:*}" lane_status=0
    wait "${entry#*:}" || lane_status=$?
    echo "test.sh: --- build/logs/$name.log"
    cat "build/logs/$name.log"
    [ "$lane_status" = 0 ] || { echo "test.sh: the $name build FAILED (log above)" >&2; failed=1; }
  done
  lanes=()
  return "$failed"
}
after_clang() {  # after_clang <command...>: runs it once clang is installed (fails if that failed)
  while [ ! -e "$clang_ready" ]; do
    kill -0 "$packages_pid" 2>/dev/null || [ -e "$clang_ready" ] || return 1
    sleep 1
  done
  "$@"
}
lanes=()
# The instrumented build starts as soon as clang is there: beside the rest of build/, the unit
# tests and the packages.
[ ${#asan_targets[@]} -eq 0 ] || lane asan after_clang bash scripts/build-asan.sh "${asan_targets[@]}"
# build/'s every target (scripts/setup.sh): after run.sh, what it left out — the unit tests (a
# unity build in four groups), the demonstration FMUs, the reference experiments, the source FMU;
# on a fresh machine all of it, pip beside the compile.
setup_status=0
{ bash scripts/setup.sh && after_clang bash scripts/check-format.sh; } || setup_status=$?
took "setup and style (beside the packages and the instrumented build)"
if [ "$setup_status" != 0 ]; then
  wait "$packages_pid" || true
  wait_lanes || true
  echo "test.sh: setup or style FAILED" >&2
  exit 1
fi
ctest_status=0
(cd build && ctest --output-on-failure -j"$(nproc)") || ctest_status=$?
took "ctest (beside the packages and the instrumented build)"
if [ "$ctest_status" != 0 ]; then
  wait "$packages_pid" || true
  wait_lanes || true
  echo "test.sh: ctest FAILED" >&2
  exit 1
fi

# --- Builds ---------------------------------------------------------------------------------
# Three lanes, each building with every core, so that the configure steps, the SuiteSparse
# downloads, the links and the serial tails of one lane (a unity batch is one process) fill the
# others' gaps on two cores:
#  - the instrumented build (scripts/build-asan.sh): one clang build, ASan + UBSan + libFuzzer's
#    coverage hooks, at -O1 as a unity build: the FMUs of the sanitizer stage and the harnesses
#    of the fuzz stage from the same object files; it starts (above) once clang is installed,
#    beside the unit tests and the other packages;
#  - win64 (scripts/build-win64.sh: for test_win64.py under Wine);
#  - aarch64 (scripts/build-aarch64.sh: for test_aarch64.py under qemu-aarch64).
# The C masters of build/ that both cross scripts build first are built here once, and
# build/dist/ is packaged once all are done (scripts/package-dist.sh: every platform's binary).
packages_status=0
wait "$packages_pid" || packages_status=$?
cat build/logs/packages.log
if [ "$packages_status" != 0 ]; then
  wait_lanes || true
  echo "test.sh: installing packages FAILED (log above)" >&2
  exit 1
fi
took "packages (beside the instrumented build)"
cmake --build build -j"$(nproc)" --target fmu_driver fmu3_driver -- --no-print-directory >/dev/null
on PLATEIMPACT_WIN64_STAGE && lane win64 bash scripts/build-win64.sh
on PLATEIMPACT_AARCH64_STAGE && lane aarch64 bash scripts/build-aarch64.sh
wait_lanes || exit 1
bash scripts/package-dist.sh
took "builds (asan + fuzz | win64 | aarch64)"

# --- The Python suite -----------------------------------------------------------------------
# --durations: the slowest tests in the log, where the stage's time goes on the machine it ran on.
"$py" -m pytest -q "${workers[@]}" --durations=15 python_tests "$@"
took pytest

status=0
# --- Sanitizer stage ------------------------------------------------------------------------
# The tests marked `sanitizer` but not `repeats_paths` against build-asan/'s FMUs, the sanitizer
# runtime preloaded; any report fails it (scripts/sanitizer-stage.sh, which runs it alone too).
if on PLATEIMPACT_SANITIZER_STAGE; then
  bash scripts/sanitizer-stage.sh "$@" || status=1
  took sanitizer
fi

if on PLATEIMPACT_FUZZ_STAGE; then
  echo "test.sh: fuzz stage: fuzz/ harnesses, ${PLATEIMPACT_FUZZ_SECONDS:-20} s each, at once (scripts/fuzz.sh)"
  bash scripts/fuzz.sh --parallel --seconds "${PLATEIMPACT_FUZZ_SECONDS:-20}" || status=1
  took fuzz
fi
exit "$status"
