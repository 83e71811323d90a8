#!/usr/bin/env bash
# All tests: the C++ unit tests (ctest) and the Python suite through fmpy (pytest).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$repo/scripts/setup.sh"
cd "$repo/build"
ctest --output-on-failure -j"$(nproc)"
cd "$repo"
exec "$repo/.venv/bin/python" -m pytest -q python_tests "$@"
