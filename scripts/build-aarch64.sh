#!/usr/bin/env bash
# The FMI 3.0 FMU with binaries/x86_64-linux (the normal build) and binaries/aarch64-linux
# (cross-compiled with Debian's g++-aarch64-linux-gnu from the source FMU's sources/, CHOLMOD
# from the same pinned SuiteSparse source), packaged by scripts/package-dist.sh into build/dist/fmi3/PlateImpact.fmu with every
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

# aarch64-linux: the binary compiled from the source FMU's own sources/ (build/dist/
# PlateImpact-source.fmu, which setup.sh has just made) by its plain CMake call, the way a user
# builds it, with the cross toolchain: so this one compile ships the aarch64 binary and checks that
# the source FMU builds (python_tests/test_source_fmu.py then compiles nothing more; issue 54: the
# source FMU's own compile was ~51 s of the pytest stage's CPU). The same sources and flags as the
# repository's build (-O3, -ffp-contract=off, libstdc++ linked in, only fmi3* exported): the same
# bits (the C master's printout over the default scene byte-identical, docs/contributing.md).
# Extracted into build-aarch64/source-fmu/ file by file, only what changed rewritten, so that the
# build stays incremental; build-aarch64/source-build/ is the CMake build of it.
src=build-aarch64/source-fmu
if [ -f build-aarch64/CMakeCache.txt ]; then
  rm -rf build-aarch64  # the layout before issue 54: the repository's CMake build
fi
mkdir -p "$src"
python3 - build/dist/PlateImpact-source.fmu "$src" <<'PY'
import pathlib, sys, zipfile
dest = pathlib.Path(sys.argv[2])
kept = set()
with zipfile.ZipFile(sys.argv[1]) as z:
    for info in z.infolist():
        if info.is_dir():
            continue
        target = dest / info.filename
        kept.add(target)
        data = z.read(info)
        if not target.is_file() or target.read_bytes() != data:
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
for path in list(dest.rglob("*")):  # what an earlier source FMU had and this one has not
    if path.is_file() and path not in kept and path.relative_to(dest).parts[0] != "binaries":
        path.unlink()
PY
# A unity build of one batch (CMAKE_UNITY_BUILD_BATCH_SIZE=0: Eigen parsed and instantiated once;
# this build shares two cores with two others, so its own parallelism buys nothing); the
# arithmetic is the same (-ffp-contract=off, no fast-math).
if ! grep -q '^CMAKE_UNITY_BUILD_BATCH_SIZE:STRING=0$' build-aarch64/source-build/CMakeCache.txt 2>/dev/null; then
  cmake -S "$src/sources" -B build-aarch64/source-build -DCMAKE_TOOLCHAIN_FILE="$repo/cmake/aarch64-linux-gnu.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=0 >/dev/null
fi
cmake --build build-aarch64/source-build -j"$(nproc)" -- --no-print-directory >/dev/null

# The distributed FMUs, with every platform's binary that exists (win64 too when built).
bash "$repo/scripts/package-dist.sh"
