#!/usr/bin/env bash
# Brings a fresh Debian machine (root) to a built PlateImpact: Debian packages for the C++
# side, a venv for the Python side, then an incremental CMake build. Quick when already done.
#
#   bash scripts/setup.sh            # every target (test.sh)
#   bash scripts/setup.sh run_sh     # only these targets (run.sh: run_sh is both FMUs and
#                                    # plate_bench, CMakeLists.txt; name one target standing for
#                                    # several: make builds several named ones one at a time)
#
# PLATEIMPACT_BUILD_TARGET (space-separated) names the targets too; PLATEIMPACT_BUILD_DIR the
# build folder (default build/); PLATEIMPACT_CMAKE_ARGS the first configure's extra arguments.
#
# When the venv has to be (re)made, pip runs in the background (downloads, unpacking,
# byte-compiling: 37 s wall, 35 s of CPU here without its cache; it fills the build's serial
# tails) while CMake configures and compiles what needs no Python (the target `compiled`: all but
# the reference experiments and the source FMU); its output goes to .venv/pip.log, printed if it
# fails. The targets that run Python in the build (the reference experiments of
# fmu/cmake/References.cmake, the source FMU) are built once pip is done.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"
targets=("$@")
[ ${#targets[@]} -gt 0 ] || read -r -a targets <<<"${PLATEIMPACT_BUILD_TARGET:-}"

# One line per stage, and the build's progress: a first run on a fresh machine takes minutes (README).
stage() { echo "setup: [$1/4] $2"; }
stage 1 "Debian packages (only what is missing)"
bash "$repo/scripts/packages.sh" build  # the Debian packages of the build, when missing (test.sh adds base)

venv="$repo/.venv"
stamp="$venv/.requirements.sha256"
pip_log="$venv/pip.log"
pip_pid=""
# A failed configure or build stops the background pip too (its own session: pip's children as well).
trap '[ -z "$pip_pid" ] || kill -- "-$pip_pid" 2>/dev/null || true' EXIT
stage 2 "the Python venv in .venv (pip installs requirements.txt when it changed)"
want="$(cat requirements.txt python/pyproject.toml | sha256sum | cut -d' ' -f1)"
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating the Python venv in .venv; pip installs into it beside the build (log: .venv/pip.log)"
  rm -f "$stamp"
  python3 -m venv "$venv"
  # The project's own package (python/plateimpact) editable: tests and examples import it.
  setsid bash -c 'set -e; py="$1/bin/python"
    "$py" -m pip install -q --upgrade pip
    "$py" -m pip install -q -r requirements.txt
    "$py" -m pip install -q -e python' pip "$venv" >"$pip_log" 2>&1 &
  pip_pid=$!
  pip_start=$(date +%s)
fi
wait_pip() {  # wait_pip: the background pip's end; fails (its log printed) if it failed
  [ -n "$pip_pid" ] || return 0
  local pip_status=0
  wait "$pip_pid" || pip_status=$?
  pip_pid=""
  if [ "$pip_status" != 0 ]; then
    cat "$pip_log" >&2
    echo "setup: pip install FAILED (exit $pip_status; log above, also in .venv/pip.log)" >&2
    return 1
  fi
  echo "$want" >"$stamp"
  echo "setup: the venv is ready (pip: $(($(date +%s) - pip_start)) s, beside the build)"
}

build="${PLATEIMPACT_BUILD_DIR:-$repo/build}"
stage 3 "configuring the CMake build in $build"
if [ ! -f "$build/CMakeCache.txt" ]; then
  # References.cmake only checks that .venv/bin/python exists; it runs it at build time
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release ${PLATEIMPACT_CMAKE_ARGS:-} >/dev/null
fi
stage 4 "building the solver, the FMUs and the tests (only what changed)"
# Debian's awk, mawk, reads a pipe a buffer at a time: without -W interactive the count below came
# all at once at the end of the build (run.sh measured end to end); gawk and others read lines.
awk() { if command awk -W version 2>/dev/null | grep -q mawk; then command awk -W interactive "$@"; else command awk "$@"; fi; }
compile() {  # compile [targets...]: cmake --build (all targets without one); make's "[ 42%]" lines
  # become a count, one line each time it passes a tenth (compiler messages still go to stderr)
  cmake --build "$build" -j"$(nproc)" ${1:+--target "$@"} -- --no-print-directory |
    awk 'match($0, /^\[ *[0-9]+%\]/) { p = substr($0, 2, RLENGTH - 3) + 0;
       if (int(p / 10) > shown) { shown = int(p / 10); printf "setup:       built %3d%%\n", p; fflush() } }'
}
if [ -n "$pip_pid" ]; then
  # While pip runs, what needs no Python (CMakeLists.txt's `compiled`: all but the reference
  # experiments and the source FMU; of those two, their FMUs: run_sh); then the rest.
  early=("${targets[@]}")
  if [ ${#targets[@]} -eq 0 ] || [[ " ${targets[*]} " == *" all "* ]]; then
    early=(compiled)
  elif [[ " ${targets[*]} " == *" PlateImpactReferences "* || " ${targets[*]} " == *" PlateImpactSourceFmu "* ]]; then
    early=(run_sh)
  fi
  echo "setup:   while pip installs: ${early[*]}"
  compile "${early[@]}"
  wait_pip
  [ "${early[*]}" = "${targets[*]}" ] || { echo "setup:   then: ${targets[*]:-every target}"; compile "${targets[@]}"; }
else
  compile "${targets[@]}"
fi
echo "setup: built $build/PlateImpact.fmu"
