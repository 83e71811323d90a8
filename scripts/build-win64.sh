#!/usr/bin/env bash
# The win64 binaries: PlateImpact.dll (FMI 2.0 and 3.0, cross-compiled with mingw-w64) and the C
# masters as .exe, then scripts/package-dist.sh: build/dist/PlateImpact.fmu (linux64 + win64) and
# build/dist/fmi3/PlateImpact.fmu (x86_64-linux + x86_64-windows, + aarch64-linux when
# scripts/build-aarch64.sh has built it, in either order). run.sh builds linux64 only; test.sh calls this as its own stage
# (PLATEIMPACT_WIN64_STAGE=0 skips it) and runs python_tests/test_win64.py under Wine.
#
#   bash scripts/build-win64.sh
#
# Installs Debian's g++-mingw-w64-x86-64-posix and wine64 when missing. The win64 binary uses
# the same sparse factor (CHOLMOD simplicial from the pinned SuiteSparse source) and links the
# GCC runtime and winpthreads statically: it imports only KERNEL32.dll and msvcrt.dll.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

bash "$repo/scripts/packages.sh" win64  # when missing

# linux64 (modelDescription.xml, documentation/, binaries/linux64): the normal build, whole
# (setup.sh configures only once and builds every target: nothing here rebuilds a subset).
bash "$repo/scripts/setup.sh"
cmake --build build -j"$(nproc)" --target fmu_driver fmu3_driver -- --no-print-directory >/dev/null

# win64: the DLL and the C master as an .exe.
# A unity build, each target one batch (CMAKE_UNITY_BUILD_BATCH_SIZE=0: the solver one source,
# Eigen parsed and instantiated once; this build shares two cores with two others, so a target's
# own parallelism buys nothing); the arithmetic is the same (-ffp-contract=off, no fast-math).
if ! grep -q '^CMAKE_UNITY_BUILD_BATCH_SIZE:STRING=0$' build-win64/CMakeCache.txt 2>/dev/null; then
  cmake -S . -B build-win64 -DCMAKE_TOOLCHAIN_FILE=cmake/mingw-w64.cmake -DPLATEIMPACT_TESTS=OFF \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0 >/dev/null
fi
cmake --build build-win64 -j"$(nproc)" --target PlateImpact PlateImpact3 fmu_driver fmu3_driver -- --no-print-directory >/dev/null

# The distributed FMUs, with every platform's binary that exists (aarch64 too when built).
bash "$repo/scripts/package-dist.sh"
