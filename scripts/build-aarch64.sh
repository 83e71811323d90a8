#!/usr/bin/env bash
# The FMI 3.0 FMU with binaries/x86_64-linux (the normal build) and binaries/aarch64-linux
# (cross-compiled with Debian's g++-aarch64-linux-gnu, CHOLMOD from the same pinned SuiteSparse
# source, -ffp-contract=off), written to build/dist/fmi3/PlateImpact.fmu; with
# build-win64/fmu/fmi3/PlateImpact.dll present (scripts/build-win64.sh) also binaries/x86_64-windows.
# Also the C master python_tests/fmu3_driver.c for aarch64 (build-aarch64/fmu3_driver), which
# python_tests/test_aarch64.py runs under qemu-aarch64 against the x86-64 one.
#
#   bash scripts/build-aarch64.sh
#
# Installs Debian's g++-aarch64-linux-gnu and qemu-user when missing. test.sh calls this as its
# aarch64 stage (PLATEIMPACT_AARCH64_STAGE=0 skips it).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

need=()
command -v aarch64-linux-gnu-g++ >/dev/null || need+=(g++-aarch64-linux-gnu)
command -v qemu-aarch64 >/dev/null || need+=(qemu-user)
if [ ${#need[@]} -gt 0 ]; then
  echo "build-aarch64.sh: installing Debian packages: ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${need[@]}" >/dev/null
fi

# x86_64-linux (modelDescription.xml, documentation/, the binary) from the normal build.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null  # (re)configured: new targets appear
cmake --build build -j"$(nproc)" --target PlateImpactFmu3 PlateImpactReferences fmu3_driver -- --no-print-directory >/dev/null

if [ ! -f build-aarch64/CMakeCache.txt ]; then
  cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DPLATEIMPACT_TESTS=OFF \
    -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build-aarch64 -j"$(nproc)" --target PlateImpact3 fmu3_driver -- --no-print-directory >/dev/null

stage="$repo/build/dist/fmi3/PlateImpact.fmu.d"
rm -rf "$stage" && mkdir -p "$repo/build/dist/fmi3"
cp -r build/fmu/fmi3/PlateImpact.fmu.d "$stage"
mkdir -p "$stage/binaries/aarch64-linux"
cp build-aarch64/fmu/fmi3/PlateImpact.so "$stage/binaries/aarch64-linux/PlateImpact.so"
if [ -f build-win64/fmu/fmi3/PlateImpact.dll ]; then
  mkdir -p "$stage/binaries/x86_64-windows"
  cp build-win64/fmu/fmi3/PlateImpact.dll "$stage/binaries/x86_64-windows/PlateImpact.dll"
  # what the Windows binary links statically (as scripts/build-win64.sh ships it)
  cp /usr/share/doc/g++-mingw-w64-x86-64-posix/copyright "$stage/documentation/licenses/GCC-runtime-mingw-w64.txt"
  cp /usr/share/doc/mingw-w64-common/copyright "$stage/documentation/licenses/mingw-w64-runtime-winpthreads.txt"
fi
rm -f build/dist/fmi3/PlateImpact.fmu
# extra/: the reference experiments, terminalsAndIcons/: the terminals (both in the stage)
(cd "$stage" && cmake -E tar cf ../PlateImpact.fmu --format=zip modelDescription.xml binaries documentation \
  $(ls -d extra terminalsAndIcons 2>/dev/null))
size=$(stat -c %s build/dist/fmi3/PlateImpact.fmu)
echo "build-aarch64.sh: wrote build/dist/fmi3/PlateImpact.fmu ($(ls "$stage/binaries" | tr '\n' ' '), $((size / 1024)) KiB)"
