#!/usr/bin/env bash
# Main job: build, simulate the default scene through fmpy, write out/default_scene.{csv,png}.
# It builds only what it runs and what the README promises after it: the FMI 2.0 and 3.0 FMUs and
# plate_bench (not the unit tests, the demonstration FMUs, the reference experiments or the source
# FMU: test.sh and a plain `bash scripts/setup.sh` build every target).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bash "$repo/scripts/setup.sh" run_sh  # both FMUs and plate_bench (CMakeLists.txt)
echo "run.sh: simulating the default scene through fmpy (examples/default_scene.py) into out/"
exec "$repo/.venv/bin/python" "$repo/examples/default_scene.py" --fmu "$repo/build/PlateImpact.fmu" \
  --bench "$repo/build/solver/bench/plate_bench" --out "$repo/out" "$@"
