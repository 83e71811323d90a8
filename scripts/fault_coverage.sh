#!/usr/bin/env bash
# Does a changed test suite still catch what the old one caught? (issue 54: "the same checks pass or
# fail on the same faults"). One FMU is built with a deliberate fault in the contact solve (BoxQP
# returns multipliers 0.1 % too large once its KKT residual is taken: every law, every scene with
# contact gets slightly wrong forces, the ledger and the port slightly wrong); then the Python test
# files that differ between OLD and NEW run against it, once as OLD has them and once as NEW has
# them, and the failing tests of each are listed. The files that did not change would give the same
# answers against the same FMU and are not run.
#
#   bash scripts/fault_coverage.sh OLD [NEW=HEAD]     # ~10 min on 2 cores; writes build/fault-coverage/
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
old="$(git rev-parse --short "${1:?usage: fault_coverage.sh OLD [NEW]}")"
new="$(git rev-parse --short "${2:-HEAD}")"
out="$repo/build/fault-coverage"
rm -rf "$out" && mkdir -p "$out"
trap 'git worktree remove --force "$out/tree-faulty" 2>/dev/null || true;
      git worktree remove --force "$out/tree-$old" 2>/dev/null || true;
      git worktree remove --force "$out/tree-$new" 2>/dev/null || true' EXIT

# The faulty FMU, from NEW's solver.
git worktree add -q --detach "$out/tree-faulty" "$new"
python3 - "$out/tree-faulty/solver/plate/BoxQP.cpp" <<'PY'
import sys
path = sys.argv[1]
text = open(path).read()
line = "    result.kktResidual = kktResidual(yFree, lower, upper, state, mu, y);\n"
assert text.count(line) == 1, "the fault's anchor moved: update scripts/fault_coverage.sh"
open(path, "w").write(text.replace(line, line + "    mu *= 1.001;  // the deliberate fault\n"))
PY
cmake -S "$out/tree-faulty" -B "$out/build-faulty" -DCMAKE_BUILD_TYPE=Release -DPLATEIMPACT_TESTS=OFF \
  -DCMAKE_UNITY_BUILD=ON -DSUITESPARSE_CACHE="$repo/.deps" -DPLATEIMPACT_REFERENCES=OFF >/dev/null
cmake --build "$out/build-faulty" -j"$(nproc)" --target PlateImpactFmu PlateImpactFmu3 -- --no-print-directory >/dev/null
export PLATEIMPACT_FMU="$out/build-faulty/PlateImpact.fmu" PLATEIMPACT_FMU3="$out/build-faulty/fmi3/PlateImpact.fmu"

mapfile -t changed < <(git diff --name-only "$old" "$new" -- 'python_tests/test_*.py' python_tests/conftest.py)
echo "fault_coverage: ${#changed[@]} changed test files between $old and $new; the faulty FMU: $PLATEIMPACT_FMU"
[ ${#changed[@]} -gt 0 ] || { echo "fault_coverage: no test file changed: nothing to compare"; exit 0; }
for rev in "$old" "$new"; do
  git worktree add -q --detach "$out/tree-$rev" "$rev"
  files=()
  for f in "${changed[@]}"; do [ -f "$out/tree-$rev/$f" ] && [[ "$f" == */test_*.py ]] && files+=("$f"); done
  [ ${#files[@]} -gt 0 ] || files=(python_tests/conftest.py)  # (conftest alone changed: collects nothing)
  # The tests of the revision, the package and tools of the checkout they run from (NEW's build/).
  (cd "$out/tree-$rev" && ln -s "$repo/build" build 2>/dev/null || true
   "$repo/.venv/bin/python" -m pytest -q -n "$(nproc)" -p no:cacheprovider -rfE "${files[@]}" \
     >"$out/pytest-$rev.log" 2>&1) || true
  grep -E '^(FAILED|ERROR) ' "$out/pytest-$rev.log" | awk '{print $2}' | sort >"$out/failed-$rev.txt" || true
  echo "fault_coverage: $rev: $(wc -l <"$out/failed-$rev.txt") failing of $(grep -Eo '[0-9]+ (passed|failed)' "$out/pytest-$rev.log" | awk '{s+=$1} END {print s}') run ($out/failed-$rev.txt)"
done
echo "fault_coverage: failing only with $old's tests:"
comm -23 "$out/failed-$old.txt" "$out/failed-$new.txt" | sed 's/^/  /'
echo "fault_coverage: failing only with $new's tests:"
comm -13 "$out/failed-$old.txt" "$out/failed-$new.txt" | sed 's/^/  /'
