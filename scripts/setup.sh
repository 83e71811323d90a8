#!/usr/bin/env bash
# Brings a fresh Debian machine (root) to a built PlateImpact: Debian packages for the C++
# side, a venv for the Python side, then an incremental CMake build. Quick when already done.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

# One line per stage, and the build's progress: a first run on a fresh machine takes minutes (README).
stage() { echo "setup: [$1/4] $2"; }
stage 1 "Debian packages (only what is missing)"
bash "$repo/scripts/packages.sh" base  # the Debian packages, when missing (scripts/packages.sh)

venv="$repo/.venv"
stamp="$venv/.requirements.sha256"
stage 2 "the Python venv in .venv (pip installs requirements.txt when it changed)"
want="$(cat requirements.txt python/pyproject.toml | sha256sum | cut -d' ' -f1)"
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating the Python venv in .venv"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --upgrade pip
  "$venv/bin/python" -m pip install -q -r requirements.txt
  # The project's own package (python/plateimpact), editable: tests and examples import it.
  "$venv/bin/python" -m pip install -q -e python
  echo "$want" > "$stamp"
fi

build="${PLATEIMPACT_BUILD_DIR:-$repo/build}"
stage 3 "configuring the CMake build in $build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release ${PLATEIMPACT_CMAKE_ARGS:-} >/dev/null
fi
# PLATEIMPACT_BUILD_TARGET: these targets (space-separated) instead of all (test.sh: the sanitizer FMUs only)
stage 4 "building the solver, the FMUs and the tests (only what changed)"
# make's "[ 42%]" lines, one each time the count passes a tenth (compiler messages still go to stderr)
cmake --build "$build" -j"$(nproc)" ${PLATEIMPACT_BUILD_TARGET:+--target $PLATEIMPACT_BUILD_TARGET} \
  -- --no-print-directory |
  awk 'match($0, /^\[ *[0-9]+%\]/) { p = substr($0, 2, RLENGTH - 3) + 0;
       if (int(p / 10) > shown) { shown = int(p / 10); printf "setup:       built %3d%%\n", p; fflush() } }'
echo "setup: built $build/PlateImpact.fmu"
