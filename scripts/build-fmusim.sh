#!/usr/bin/env bash
# Builds fmusim, the command-line simulator of the modelica Reference-FMUs (the FMI 1/2/3
# reference master), into .deps/fmusim/bin/fmusim, for tools/fmusim_matrix.py (issue 31).
# On demand only: not part of setup.sh or the test suite.
#
#   REFERENCE_FMUS_SRC=/path/to/Reference-FMUs bash scripts/build-fmusim.sh
#   bash scripts/build-fmusim.sh /path/to/Reference-FMUs-0.0.39.tar.gz
#
# The source (tag v0.0.39, the last with fmusim/) is the user's to give: a git clone of
# modelica/Reference-FMUs (bare or not) holding the tag, a directory with the tag's files, or a
# .tar.gz/.tgz/.zip of them. Nothing is downloaded but Debian packages (only those missing).
# fmusim's own CMakeLists expects zlib, libxml2 and SUNDIALS built by its build scripts into
# fixed folders; instead this script compiles its sources directly against Debian's libxml2,
# minizip (which also replaces the zlib contrib copy) and SUNDIALS 6.
# One patch at build time: FMIUtil.c hands fmi2FreeFMUstate / fmi3FreeFMUState the state instead
# of its address, so --initial-fmu-state-file / --final-fmu-state-file crash in fmusim itself.
# Quick when already built from the same source by this same script (a stamp beside the binary).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tag=v0.0.39
dest="$repo/.deps/fmusim"
bin="$dest/bin/fmusim"
src_arg="${1:-${REFERENCE_FMUS_SRC:-}}"
script_sum="$(sha256sum "${BASH_SOURCE[0]}" | cut -d' ' -f1)"

need_source() {
  cat >&2 <<EOF
build-fmusim: $*
It needs the source of the modelica Reference-FMUs at tag $tag, given as
  REFERENCE_FMUS_SRC=PATH bash scripts/build-fmusim.sh     (or: bash scripts/build-fmusim.sh PATH)
where PATH is one of
  - a git clone of modelica/Reference-FMUs (bare or with a work tree) that has the tag $tag,
  - a directory holding the files of that tag (fmusim/, include/, src/),
  - an archive of them (.tar.gz, .tgz or .zip), e.g. the release's source archive.
This script downloads nothing itself (Debian packages only).
EOF
  exit 2
}

# -- already built? ----------------------------------------------------------------------------
if [ -z "$src_arg" ]; then
  if [ -x "$bin" ] && grep -qx "script=$script_sum" "$dest/stamp" 2>/dev/null; then
    echo "build-fmusim: $bin is built ($(grep '^source=' "$dest/stamp"))"
    exit 0
  fi
  need_source "no source given (REFERENCE_FMUS_SRC is unset) and fmusim is not built yet."
fi
[ -e "$src_arg" ] || need_source "$src_arg does not exist."
src_arg="$(cd "$(dirname "$src_arg")" && pwd)/$(basename "$src_arg")"

# -- Debian packages, only the missing ones ----------------------------------------------------
need_apt=()
for pkg in gcc libc6-dev pkg-config libxml2-dev libminizip-dev zlib1g-dev libsundials-dev git; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || need_apt+=("$pkg")
done
case "$src_arg" in *.zip) command -v unzip >/dev/null || need_apt+=(unzip) ;; esac
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "build-fmusim: installing Debian packages: ${need_apt[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi

# -- which source: its identity decides whether to rebuild ------------------------------------
git_dir=""
if git --git-dir="$src_arg" rev-parse -q --verify "refs/tags/$tag^{commit}" >/dev/null 2>&1; then
  git_dir="$src_arg"
elif [ -d "$src_arg/.git" ] && git -C "$src_arg" rev-parse -q --verify "refs/tags/$tag^{commit}" >/dev/null 2>&1; then
  git_dir="$(git -C "$src_arg" rev-parse --absolute-git-dir)"
fi
if [ -n "$git_dir" ]; then
  source_id="git $(git --git-dir="$git_dir" rev-parse "$tag^{commit}") ($tag)"
elif [ -f "$src_arg" ]; then
  source_id="archive $(sha256sum "$src_arg" | cut -d' ' -f1)"
elif [ -d "$src_arg" ]; then
  source_id="directory $( (cd "$src_arg" && find fmusim include src -type f -print0 2>/dev/null | sort -z \
    | xargs -0 sha256sum) | sha256sum | cut -d' ' -f1)"
else
  need_source "$src_arg is neither a git clone with $tag, a directory nor an archive."
fi
if [ -x "$bin" ] && [ "$(cat "$dest/stamp" 2>/dev/null)" = "$(printf 'script=%s\nsource=%s' "$script_sum" "$source_id")" ]; then
  echo "build-fmusim: $bin is up to date (source=$source_id)"
  exit 0
fi

# -- a fresh copy of the tag's fmusim/, include/, src/ in .deps/fmusim/src --------------------
work="$dest/src"
rm -rf "$work" "$dest/unpack"
mkdir -p "$work" "$dest/bin"
if [ -n "$git_dir" ]; then
  # (stderr aside: a clone without its largest blobs complains about files outside these folders)
  if ! git --git-dir="$git_dir" archive "$tag" -- fmusim/ include/ src/ 2>"$dest/archive.log" | tar -x -C "$work"; then
    cat "$dest/archive.log" >&2
    exit 1
  fi
else
  top="$src_arg"
  if [ -f "$src_arg" ]; then
    mkdir -p "$dest/unpack"
    case "$src_arg" in
      *.zip) unzip -q "$src_arg" -d "$dest/unpack" ;;
      *.tar.gz | *.tgz | *.tar) tar -xf "$src_arg" -C "$dest/unpack" ;;
      *) need_source "$src_arg: not a .tar.gz, .tgz, .tar or .zip archive." ;;
    esac
    top="$(dirname "$(find "$dest/unpack" -maxdepth 3 -path '*/fmusim/FMI3CSSimulation.c' | head -n1)")/.."
  fi
  [ -f "$top/fmusim/FMI3CSSimulation.c" ] || need_source "$src_arg holds no fmusim/ folder (fmusim exists up to $tag)."
  cp -r "$top/fmusim" "$top/include" "$top/src" "$work/"
  rm -rf "$dest/unpack"
  # Not a tagged git source: say when the two files the matrix depends on differ from the tag's.
  [ "$(git hash-object "$work/fmusim/FMI3CSSimulation.c" 2>/dev/null)" = 8b2a36f4156bb2f13ba3570fe9c3c2963c61841f ] \
    || echo "build-fmusim: warning: fmusim/FMI3CSSimulation.c is not the one of $tag" >&2
fi

# -- the one patch: FreeFMUstate/FreeFMUState take the address of the state -------------------
util="$work/fmusim/FMIUtil.c"
sed -i -E 's/(FMI[23]FreeFMU[Ss]tate\(S, )FMUState\)/\1\&FMUState)/' "$util"
patched="$(grep -cE 'FMI[23]FreeFMU[Ss]tate\(S, &FMUState\)' "$util" || true)"
if [ "$patched" != 4 ]; then
  echo "build-fmusim: the FreeFMUState patch applied to $patched of the 4 calls in $util (not the $tag source?)" >&2
  exit 1
fi

# -- compile against Debian's libraries --------------------------------------------------------
cflags=(-O2 -std=gnu11 -w -DFMUSIM_VERSION='"0.0.39+plateimpact"' -I"$work/fmusim" -I"$work/include")
read -ra pc <<<"$(pkg-config --cflags libxml-2.0 minizip)"
cflags+=("${pc[@]}")
# SUNDIALS 7 names the null communicator SUN_COMM_NULL; Debian 12 ships 6.4, where it is NULL.
grep -rqs SUN_COMM_NULL /usr/include/sundials/ || cflags+=(-DSUN_COMM_NULL=NULL)
libs=(-lxml2 -lminizip -lz -lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense
  -lsundials_sunlinsoldense -ldl -lm)
# the sources of fmusim/CMakeLists.txt: fmusim/*.c but FMIBuildDescription.c, minizip from Debian
sources=()
for f in "$work"/fmusim/*.c; do [ "${f##*/}" = FMIBuildDescription.c ] || sources+=("$f"); done
sources+=("$work"/src/FMI.c "$work"/src/FMI1.c "$work"/src/FMI2.c "$work"/src/FMI3.c
  "$work"/src/structured_variable_name.yy.c "$work"/src/structured_variable_name.tab.c)
echo "build-fmusim: compiling fmusim ($tag, patched) against Debian's libxml2, minizip and SUNDIALS"
nice -n 10 cc "${cflags[@]}" "${sources[@]}" "${libs[@]}" -o "$bin.tmp"
mv "$bin.tmp" "$bin"
printf 'script=%s\nsource=%s' "$script_sum" "$source_id" >"$dest/stamp"
"$bin" --version
echo "build-fmusim: built $bin"
