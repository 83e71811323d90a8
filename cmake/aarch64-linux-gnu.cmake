# Cross-compiling the FMI 3.0 FMU's aarch64-linux binary on Debian (g++-aarch64-linux-gnu):
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake
# (scripts/build-aarch64.sh gives it to the source FMU's sources/CMakeLists.txt instead: -S <fmu>/sources).
# Run under qemu-user: qemu-aarch64 -L /usr/aarch64-linux-gnu <program>.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
# GCC contracts a*b + c into one fused multiply-add on aarch64 by default (one rounding instead
# of two); x86-64's baseline has no FMA. Off, both round every operation alike: the results are
# the same bits (python_tests/test_aarch64.py).
set(CMAKE_C_FLAGS_INIT "-ffp-contract=off")
set(CMAKE_CXX_FLAGS_INIT "-ffp-contract=off")
# Eigen is header-only: the host's headers serve the target.
set(Eigen3_DIR /usr/share/eigen3/cmake)
