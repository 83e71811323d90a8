#!/usr/bin/env bash
# Brings a fresh Debian machine (root) to a built PlateImpact: Debian packages for the C++
# side, a venv for the Python side, then an incremental CMake build. Quick when already done.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

bash "$repo/scripts/packages.sh" base  # the Debian packages, when missing (scripts/packages.sh)

venv="$repo/.venv"
stamp="$venv/.requirements.sha256"
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
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release ${PLATEIMPACT_CMAKE_ARGS:-} >/dev/null
fi
# PLATEIMPACT_BUILD_TARGET: these targets (space-separated) instead of all (test.sh: the sanitizer FMUs only)
cmake --build "$build" -j"$(nproc)" ${PLATEIMPACT_BUILD_TARGET:+--target $PLATEIMPACT_BUILD_TARGET} \
  -- --no-print-directory >/dev/null
echo "setup: built $build/PlateImpact.fmu"
