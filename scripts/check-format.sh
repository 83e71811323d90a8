#!/usr/bin/env bash
# The code style, checked (test.sh runs it; fix with --fix): clang-format (.clang-format) on the
# C++ and C sources but the vendored FMI headers (fmu/headers/), ruff (ruff.toml) on the Python.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
mapfile -t sources < <(git ls-files '*.cpp' '*.h' '*.c' | grep -v -e '^fmu/headers/')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${sources[@]}"
  .venv/bin/ruff check --fix --quiet .
  .venv/bin/ruff format --quiet .
  exit 0
fi
status=0
clang-format --dry-run --Werror "${sources[@]}" || { echo "check-format: C++ style differs (bash scripts/check-format.sh --fix)" >&2; status=1; }
.venv/bin/ruff check --quiet . || status=1
.venv/bin/ruff format --check --quiet . || { echo "check-format: Python formatting differs (bash scripts/check-format.sh --fix)" >&2; status=1; }
[ "$status" = 0 ] && echo "check-format: C++ (clang-format) and Python (ruff) in style"
exit "$status"
