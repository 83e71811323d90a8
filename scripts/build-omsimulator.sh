#!/usr/bin/env bash
# Builds OMSimulator (OpenModelica's FMI/SSP co-simulation engine: its command line and its Python
# package) into .deps/omsimulator/install, for docs/masters.md and python_tests/test_master_omsimulator.py
# (issue 48). On demand only: not part of setup.sh or the test suite.
#
#   OMSIMULATOR_SRC=/path/to/OMSimulator OMSIMULATOR_3RDPARTY_SRC=/path/to/OMSimulator-3rdParty \
#     bash scripts/build-omsimulator.sh
#
# Why from sources: Debian has no package, and PyPI's `omsimulator` sdist downloads prebuilt
# binaries while it builds. The sources are the user's to give, as git clones (bare or not) of
# OpenModelica/OMSimulator holding the commit $commit below and of OpenModelica/OMSimulator-3rdParty
# holding the commit that commit pins as its 3rdParty submodule. Nothing is downloaded but Debian
# packages (only those missing). About 6 minutes of a 2-core machine (it runs under nice).
# Quick when already built from the same commits by this same script (a stamp beside the install).
#
# Then:  .deps/omsimulator/install/bin/OMSimulator model.ssp ...                (the command line)
#        PYTHONPATH=.deps/omsimulator/install/lib/x86_64-linux-gnu python ...   (import OMSimulator)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
commit=acb56d9d9c8ecbe4408fcee0f2a548daf3d7573b # v3.0.0-114-gacb56d9d: "propagate export name to all connectors"
version=v3.0.0-114-gacb56d9d
dest="$repo/.deps/omsimulator"
install="$dest/install"
bin="$install/bin/OMSimulator"
script_sum="$(sha256sum "${BASH_SOURCE[0]}" | cut -d' ' -f1)"
oms="${OMSIMULATOR_SRC:-}"
third="${OMSIMULATOR_3RDPARTY_SRC:-}"

need_source() {
  cat >&2 <<EOF
build-omsimulator: $*
It needs two git clones (bare or with a work tree):
  OMSIMULATOR_SRC=PATH           OpenModelica/OMSimulator, holding commit $commit ($version)
  OMSIMULATOR_3RDPARTY_SRC=PATH  OpenModelica/OMSimulator-3rdParty, holding the commit it pins as 3rdParty
This script downloads nothing itself (Debian packages only).
EOF
  exit 2
}

git_dir_of() { # the git directory of a clone, bare or not
  if git --git-dir="$1" rev-parse -q --git-dir >/dev/null 2>&1 && [ -d "$1/objects" ]; then
    (cd "$1" && pwd)
  elif [ -d "$1/.git" ]; then
    git -C "$1" rev-parse --absolute-git-dir
  else
    return 1
  fi
}

# -- already built? ----------------------------------------------------------------------------
if [ -z "$oms" ] && [ -z "$third" ]; then
  if [ -x "$bin" ] && grep -qx "script=$script_sum" "$dest/stamp" 2>/dev/null; then
    echo "build-omsimulator: $bin is built ($(grep '^source=' "$dest/stamp"))"
    exit 0
  fi
  need_source "no source given and OMSimulator is not built yet."
fi
[ -n "$oms" ] && [ -n "$third" ] || need_source "give both OMSIMULATOR_SRC and OMSIMULATOR_3RDPARTY_SRC."
command -v git >/dev/null || { echo "build-omsimulator: git is needed to read the clones (apt-get install git)" >&2; exit 2; }
oms_git="$(git_dir_of "$oms")" || need_source "$oms is not a git clone."
third_git="$(git_dir_of "$third")" || need_source "$third is not a git clone."
git --git-dir="$oms_git" cat-file -e "$commit^{commit}" 2>/dev/null || need_source "$oms does not hold commit $commit."
third_commit="$(git --git-dir="$oms_git" ls-tree "$commit" 3rdParty | awk '{print $3}')"
git --git-dir="$third_git" cat-file -e "$third_commit^{commit}" 2>/dev/null \
  || need_source "$third does not hold commit $third_commit (the 3rdParty that $commit pins)."
source_id="OMSimulator $commit, 3rdParty $third_commit"
if [ -x "$bin" ] && [ "$(cat "$dest/stamp" 2>/dev/null)" = "$(printf 'script=%s\nsource=%s' "$script_sum" "$source_id")" ]; then
  echo "build-omsimulator: $bin is up to date ($source_id)"
  exit 0
fi

# -- Debian packages (cmake, g++, make, python3: the base group), only the missing ones ----------
bash "$repo/scripts/packages.sh" base

# -- the two trees: OMSimulator at $commit with its 3rdParty in place --------------------------
src="$dest/src"
rm -rf "$src" "$dest/build" "$install"
mkdir -p "$src/3rdParty" "$dest/build"
# (not testsuite/: its largest files, which a shallow or partial clone may lack, and the build does not use it)
mapfile -t top < <(git --git-dir="$oms_git" ls-tree --name-only "$commit" | grep -vx testsuite)
git --git-dir="$oms_git" archive "$commit" -- "${top[@]}" 2>"$dest/archive.log" | tar -x -C "$src"
git --git-dir="$third_git" archive "$third_commit" | tar -x -C "$src/3rdParty"
# No .git in an archive: the version its CMake would take from `git describe`.
echo "$version" >"$src/version.txt"

# -- configure, build, install (the command line, the shared library, the Python package) ------
echo "build-omsimulator: building OMSimulator $version (3rdParty ${third_commit:0:7}) with $(nproc) jobs"
start=$SECONDS
cmake -S "$src" -B "$dest/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$install" \
  -DOMS_ENABLE_TESTSUITE=OFF -DOMS_ENABLE_OMSimulatorGui=OFF >"$dest/configure.log" 2>&1 \
  || { tail -n 30 "$dest/configure.log" >&2; exit 1; }
nice -n 10 cmake --build "$dest/build" --target install -j"$(nproc)" >"$dest/build.log" 2>&1 \
  || { tail -n 40 "$dest/build.log" >&2; exit 1; }
printf 'script=%s\nsource=%s' "$script_sum" "$source_id" >"$dest/stamp"
"$bin" --version
echo "build-omsimulator: built $bin in $((SECONDS - start)) s; Python: PYTHONPATH=$(dirname "$(find "$install/lib" -maxdepth 2 -name OMSimulator -type d | head -n1)")"
