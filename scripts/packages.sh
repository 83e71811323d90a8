#!/usr/bin/env bash
# The Debian packages of every stage, in one place, installed in ONE apt-get call (one
# `apt-get update`, one dpkg run): the groups named on the command line, only what is missing.
#
#   bash scripts/packages.sh build                           # scripts/setup.sh (run.sh): build/ and the venv
#   bash scripts/packages.sh base win64 aarch64 qemu fuzz    # test.sh: every stage
#
#   build    cmake g++ make binutils Eigen Spectra GoogleTest xxhash python3-venv: what run.sh needs
#   base     build, and what only the tests need: valgrind, clang-format (libllvm14 and
#            libclang-cpp14, which clang shares: 47 of the ~60 MB more than build; test.sh installs
#            them in the background with clang)
#   win64    mingw-w64 (posix threads) and wine64: scripts/build-win64.sh, test_win64.py
#   aarch64  the aarch64 cross compiler: scripts/build-aarch64.sh (qemu-user runs it)
#   qemu     qemu-user: test_aarch64.py (qemu-aarch64), test_golden.py (qemu-x86_64 CPUs)
#   fuzz     clang and llvm: libFuzzer, its sanitizers and coverage (scripts/fuzz.sh); the
#            sanitizer and libFuzzer runtimes (libclang-rt-dev), which clang only recommends
#
# Without the packages' recommendations (--no-install-recommends): they brought 209 packages no
# stage uses (Mesa's drivers and LLVM 15 for wine, gdb and valgrind-dbg, llvm-14-dev, systemd,
# qemu-user-binfmt, ...; 231 MB of downloads). Measured in a chroot of the fresh machine's minimal
# Debian 12 (issue 54): every group's install 62 s of CPU, 54 s wall; the recommendations on top
# 31 s of CPU, 34 s wall. Only libclang-rt-dev was needed of them (named above).
set -euo pipefail
need=()
have_cmd() { command -v "$1" >/dev/null; }
for group in "$@"; do
  case "$group" in
    build | base)
      have_cmd cmake || need+=(cmake)
      have_cmd g++ || need+=(g++)
      have_cmd make || need+=(make)
      have_cmd readelf || need+=(binutils)
      [ -f /usr/include/eigen3/Eigen/Core ] || need+=(libeigen3-dev)
      [ -f /usr/include/Spectra/SymEigsSolver.h ] || need+=(libspectra-dev)  # the condensed plate's modes
      [ -f /usr/include/gtest/gtest.h ] || need+=(libgtest-dev)
      [ -f /usr/include/xxhash.h ] || need+=(libxxhash-dev)  # the FMU-state checksum (header-only)
      have_cmd python3 || need+=(python3)
      python3 -c 'import venv, ensurepip' 2>/dev/null || need+=(python3-venv)
      if [ "$group" = base ]; then
        have_cmd valgrind || need+=(valgrind)                # python_tests/test_valgrind.py
        have_cmd clang-format || need+=(clang-format)        # scripts/check-format.sh
      fi ;;
    win64)
      have_cmd x86_64-w64-mingw32-g++-posix || need+=(g++-mingw-w64-x86-64-posix)
      [ -x /usr/lib/wine/wine64 ] || need+=(wine64) ;;
    aarch64) have_cmd aarch64-linux-gnu-g++ || need+=(g++-aarch64-linux-gnu) ;;
    qemu) have_cmd qemu-aarch64 && have_cmd qemu-x86_64 || need+=(qemu-user) ;;
    fuzz)
      have_cmd clang++ || need+=(clang)
      have_cmd llvm-cov || need+=(llvm)
      compgen -G "/usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a" >/dev/null || need+=(libclang-rt-dev)
      [ -f /usr/include/xxhash.h ] || need+=(libxxhash-dev) ;;
    *) echo "packages.sh: unknown group $group" >&2; exit 2 ;;
  esac
done
[ ${#need[@]} -eq 0 ] && exit 0
mapfile -t need < <(printf '%s\n' "${need[@]}" | sort -u)
echo "packages.sh: installing Debian packages: ${need[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
