#!/usr/bin/env bash
# Main job: build, simulate the default scene through fmpy, write out/default_scene.{csv,png}.
# It builds only what it runs and what the README promises after it: the FMI 2.0 and 3.0 FMUs with
# their reference experiments (the product as shipped: `plateimpact.validate` replays them) and
# plate_bench (not the unit tests, the demonstration FMUs or the source FMU: test.sh and a plain
# `bash scripts/setup.sh` build every target).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$repo/scripts/setup.sh" run_sh PlateImpactReferences  # both FMUs, plate_bench; then the references (pip done)
echo "run.sh: simulating the default scene through fmpy (examples/default_scene.py) into out/"
exec "$repo/.venv/bin/python" "$repo/examples/default_scene.py" --fmu "$repo/build/PlateImpact.fmu" \
  --bench "$repo/build/solver/bench/plate_bench" --out "$repo/out" "$@"
