#!/usr/bin/env bash
# The dual-platform FMU: PlateImpact.fmu with binaries/linux64 (the normal build) and
# binaries/win64/PlateImpact.dll (cross-compiled with mingw-w64), written to
# build/dist/PlateImpact.fmu; and the FMI 3.0 FMU with binaries/x86_64-linux and
# binaries/x86_64-windows, written to build/dist/fmi3/PlateImpact.fmu (scripts/build-aarch64.sh
# adds aarch64-linux to it). run.sh builds linux64 only; test.sh calls this as its own stage
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

need=()
command -v x86_64-w64-mingw32-g++-posix >/dev/null || need+=(g++-mingw-w64-x86-64-posix)
[ -x /usr/lib/wine/wine64 ] || need+=(wine64)
if [ ${#need[@]} -gt 0 ]; then
  echo "build-win64.sh: installing Debian packages: ${need[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${need[@]}" >/dev/null
fi

# linux64 (modelDescription.xml, documentation/, binaries/linux64) from the normal build.
[ -f build/CMakeCache.txt ] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target PlateImpactFmu PlateImpactFmu3 PlateImpactReferences fmu_driver fmu3_driver -- --no-print-directory >/dev/null

# win64: the DLL and the C master as an .exe.
if [ ! -f build-win64/CMakeCache.txt ]; then
  cmake -S . -B build-win64 -DCMAKE_TOOLCHAIN_FILE=cmake/mingw-w64.cmake -DPLATEIMPACT_TESTS=OFF \
    -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build-win64 -j"$(nproc)" --target PlateImpact PlateImpact3 fmu_driver fmu3_driver -- --no-print-directory >/dev/null

stage="$repo/build/dist/PlateImpact.fmu.d"
rm -rf "$stage" && mkdir -p "$repo/build/dist"
cp -r build/fmu/PlateImpact.fmu.d "$stage"
mkdir -p "$stage/binaries/win64"
cp build-win64/fmu/PlateImpact.dll "$stage/binaries/win64/PlateImpact.dll"
# What the win64 binary links statically besides SuiteSparse: the GCC runtime libraries (GPL-3.0
# with the GCC Runtime Library Exception) and mingw-w64's runtime and winpthreads (ZPL/MIT).
cp /usr/share/doc/g++-mingw-w64-x86-64-posix/copyright "$stage/documentation/licenses/GCC-runtime-mingw-w64.txt"
cp /usr/share/doc/mingw-w64-common/copyright "$stage/documentation/licenses/mingw-w64-runtime-winpthreads.txt"
rm -f build/dist/PlateImpact.fmu
# extra/: the reference experiments (PlateImpactReferences adds them to the stage)
(cd "$stage" && cmake -E tar cf ../PlateImpact.fmu --format=zip modelDescription.xml binaries documentation $(ls -d extra 2>/dev/null))
size=$(stat -c %s build/dist/PlateImpact.fmu)
echo "build-win64.sh: wrote build/dist/PlateImpact.fmu (linux64 + win64, $((size / 1024)) KiB)"

# FMI 3.0: the same DLL's fmi3 twin as binaries/x86_64-windows, with the same runtime licences.
stage3="$repo/build/dist/fmi3/PlateImpact.fmu.d"
rm -rf "$stage3" && mkdir -p "$repo/build/dist/fmi3"
cp -r build/fmu/fmi3/PlateImpact.fmu.d "$stage3"
mkdir -p "$stage3/binaries/x86_64-windows"
cp build-win64/fmu/fmi3/PlateImpact.dll "$stage3/binaries/x86_64-windows/PlateImpact.dll"
cp "$stage/documentation/licenses/GCC-runtime-mingw-w64.txt" "$stage/documentation/licenses/mingw-w64-runtime-winpthreads.txt" \
  "$stage3/documentation/licenses/"
rm -f build/dist/fmi3/PlateImpact.fmu
(cd "$stage3" && cmake -E tar cf ../PlateImpact.fmu --format=zip modelDescription.xml binaries documentation \
  $(ls -d extra terminalsAndIcons 2>/dev/null))
size=$(stat -c %s build/dist/fmi3/PlateImpact.fmu)
echo "build-win64.sh: wrote build/dist/fmi3/PlateImpact.fmu (x86_64-linux + x86_64-windows, $((size / 1024)) KiB)"
