#!/usr/bin/env bash
# The one instrumented build, build-asan/ (clang, AddressSanitizer + UBSan, libFuzzer's coverage
# instrumentation): its FMUs serve test.sh's sanitizer stage (build-asan/PlateImpact.fmu,
# build-asan/fmi3/PlateImpact.fmu), its harnesses the fuzz stage (build-asan/fuzz/fuzz_<harness>,
# scripts/fuzz.sh). The solver, CHOLMOD and the FMI layer are compiled once for both: the
# harnesses link the FMU's own object files (fuzz/CMakeLists.txt).
#
#   bash scripts/build-asan.sh                 # the two FMUs and the three harnesses
#   bash scripts/build-asan.sh fuzzers         # only these targets (scripts/fuzz.sh)
#   bash scripts/build-asan.sh --coverage fuzzers  # the same in build-cov/ with source-based
#                                              # coverage as well (scripts/fuzz.sh --coverage)
#
# -O1 (what ASan recommends: half the compile time of -O3, the same arithmetic with
# -ffp-contract=off), line tables for the reports (-g1), and a unity build, each target one batch
# (the solver one source: Eigen parsed and instantiated once, not once per group; this build
# shares two cores with two others). Installs clang and llvm when missing (scripts/packages.sh fuzz).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
dir="$repo/build-asan" extra=()
if [ "${1:-}" = --coverage ]; then
  # a folder of its own: the profile instrumentation would slow every other use of build-asan/
  dir="$repo/build-cov" extra=(-DPLATEIMPACT_COVERAGE=ON)
  shift
fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(PlateImpactFmu PlateImpactFmu3 fuzzers)

bash "$repo/scripts/packages.sh" base fuzz  # when missing

# A build-asan/ of GCC (before issue 54 the sanitizer stage had a build of its own): made again.
if [ -f "$dir/CMakeCache.txt" ] && ! grep -q '^PLATEIMPACT_FUZZ:BOOL=ON' "$dir/CMakeCache.txt"; then
  echo "build-asan.sh: $dir is not the clang build: configuring it again"
  rm -rf "$dir"
fi
if ! grep -q '^CMAKE_UNITY_BUILD_BATCH_SIZE:STRING=0$' "$dir/CMakeCache.txt" 2>/dev/null; then
  CC=clang CXX=clang++ cmake -S "$repo" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DPLATEIMPACT_FUZZ=ON \
    "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG" -DCMAKE_CXX_FLAGS=-g1 \
    -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0 -DPLATEIMPACT_TESTS=OFF "${extra[@]}" >/dev/null
fi
cmake --build "$dir" -j"$(nproc)" --target "${targets[@]}" -- --no-print-directory >/dev/null
echo "build-asan.sh: built ${targets[*]} in ${dir#"$repo"/}/"
