#!/usr/bin/env bash
# The FMI 3.0 FMU with binaries/x86_64-linux (the normal build) and binaries/aarch64-linux
# (cross-compiled with Debian's g++-aarch64-linux-gnu, CHOLMOD from the same pinned SuiteSparse
# source), packaged by scripts/package-dist.sh into build/dist/fmi3/PlateImpact.fmu with every
# other platform's binary that exists (x86_64-windows once scripts/build-win64.sh ran, either order).
# python_tests/test_aarch64.py runs the C master python_tests/fmu3_driver.c for aarch64 under
# qemu-aarch64 against the x86-64 one (build/fmu3_driver); the aarch64 one is compiled by the test,
# in one process with the experiment driver (test_experiments_platforms.py's aarch64_chain).
#
#   bash scripts/build-aarch64.sh
#
# Installs Debian's g++-aarch64-linux-gnu and qemu-user when missing. test.sh calls this as its
# aarch64 stage (PLATEIMPACT_AARCH64_STAGE=0 skips it).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

bash "$repo/scripts/packages.sh" aarch64 qemu  # when missing

# x86_64-linux (modelDescription.xml, documentation/, the binary): the normal build, whole
# (setup.sh configures only once and builds every target: nothing here rebuilds a subset).
bash "$repo/scripts/setup.sh"
cmake --build build -j"$(nproc)" --target fmu3_driver -- --no-print-directory >/dev/null

# A unity build, each target one batch (CMAKE_UNITY_BUILD_BATCH_SIZE=0: the solver one source,
# Eigen parsed and instantiated once; this build shares two cores with two others, so a target's
# own parallelism buys nothing); the arithmetic is the same (-ffp-contract=off, no fast-math).
if ! grep -q '^CMAKE_UNITY_BUILD_BATCH_SIZE:STRING=0$' build-aarch64/CMakeCache.txt 2>/dev/null; then
  cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DPLATEIMPACT_TESTS=OFF \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0 >/dev/null
fi
cmake --build build-aarch64 -j"$(nproc)" --target PlateImpact3 -- --no-print-directory >/dev/null

# The distributed FMUs, with every platform's binary that exists (win64 too when built).
bash "$repo/scripts/package-dist.sh"
