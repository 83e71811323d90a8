#!/usr/bin/env bash
# Main job: build, simulate the default scene through fmpy, write out/default_scene.{csv,png}.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$repo/scripts/setup.sh"
echo "run.sh: simulating the default scene through fmpy (examples/default_scene.py) into out/"
exec "$repo/.venv/bin/python" "$repo/examples/default_scene.py" --fmu "$repo/build/PlateImpact.fmu" \
  --bench "$repo/build/solver/bench/plate_bench" --out "$repo/out" "$@"
