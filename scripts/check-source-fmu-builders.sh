#!/usr/bin/env bash
# On demand (minutes: the whole solver is compiled): builds the source FMU
# (build/dist/PlateImpact-source.fmu) with fmpy's generic builder, fmpy.build.build_platform_binary
# (it reads the buildDescription.xml's first SourceFileSet and puts only sources/ on the include
# path), and replays the smoke experiment through the validator on the result; then the same with
# fmu-manipulation-toolbox's compile (`fmutool -compile-sources`) when fmutool is on the PATH or at
# $FMUTOOL (pip install fmu-manipulation-toolbox, in a venv of its own). Prints each build's wall time. The suite checks the same reading without compiling (python_tests/test_source_fmu_fmpy.py);
# the plain CMake build of sources/CMakeLists.txt is python_tests/test_source_fmu.py.
#   bash scripts/check-source-fmu-builders.sh [WORK_DIR]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
fmu="$repo/build/dist/PlateImpact-source.fmu"
[ -f "$fmu" ] || { echo "check-source-fmu-builders: $fmu not built (bash scripts/setup.sh)" >&2; exit 2; }
work="${1:-$(mktemp -d)}"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
rm -rf "$work/fmpy" && mkdir -p "$work/fmpy/build"
"$repo/.venv/bin/python" -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])' "$fmu" "$work/fmpy/PlateImpact"
start=$(date +%s)
CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}" nice -n 10 "$repo/.venv/bin/python" -c '
import sys
from fmpy.build import build_platform_binary
build_platform_binary(sys.argv[1], sys.argv[2])
' "$work/fmpy/PlateImpact" "$work/fmpy/build" > "$work/fmpy/build.log" 2>&1 \
  || { tail -30 "$work/fmpy/build.log" >&2; echo "check-source-fmu-builders: fmpy's build_platform_binary failed (log: $work/fmpy/build.log)" >&2; exit 1; }
echo "check-source-fmu-builders: fmpy build_platform_binary: $(( $(date +%s) - start )) s"
"$repo/.venv/bin/python" -m plateimpact.validate "$work/fmpy/PlateImpact" --master fmpy --experiment smoke
fmutool="${FMUTOOL:-$(command -v fmutool || true)}"
if [ -z "$fmutool" ]; then
  echo "check-source-fmu-builders: fmutool not found (PATH, \$FMUTOOL): fmu-manipulation-toolbox skipped"
  exit 0
fi
rm -rf "$work/fmutool" && mkdir -p "$work/fmutool"
start=$(date +%s)
nice -n 10 "$fmutool" -input "$fmu" -compile-sources -output "$work/fmutool/PlateImpact.fmu" > "$work/fmutool/build.log" 2>&1 \
  || { tail -30 "$work/fmutool/build.log" >&2; echo "check-source-fmu-builders: fmutool -compile-sources failed (log: $work/fmutool/build.log)" >&2; exit 1; }
echo "check-source-fmu-builders: fmutool -compile-sources: $(( $(date +%s) - start )) s"
"$repo/.venv/bin/python" -m plateimpact.validate "$work/fmutool/PlateImpact.fmu" --master fmpy --experiment smoke
