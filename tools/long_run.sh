#!/usr/bin/env bash
# The long run of the default sine scene at full length: 10^6 internal steps (10 s) through the
# checks of solver/tests/test_long_run.cpp (every output finite, energy bounded by E0 + input,
# dissipation never decreasing, the ledger closed to 1e-9, every QP's KKT residual <= 1e-10);
# ctest runs the same test over 10^5 steps (issue 54: the campaign out of the suite's time).
# Prints the test's summary line (engine, steps, CPU per step, energies, worst residuals).
#
#   bash tools/long_run.sh            # 10^6 steps (~10 s of CPU)
#   bash tools/long_run.sh 10000000   # any multiple of 10
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tests="$repo/build/solver/tests/plate_unit_tests"
[ -x "$tests" ] || { echo "long_run.sh: $tests missing: bash scripts/setup.sh" >&2; exit 1; }
PLATEIMPACT_LONG_RUN_STEPS="${1:-1000000}" "$tests" --gtest_filter='LongRun.*'
