#!/usr/bin/env bash
# The one packaging step of the distributed FMUs: build/dist/PlateImpact.fmu (FMI 2.0) and
# build/dist/fmi3/PlateImpact.fmu (FMI 3.0), each assembled from the native build's staged FMU
# (modelDescription.xml, documentation/, the host binary) plus every other platform's binary that
# exists and was built from the same sources (its compiled-in GUID equals the description's):
#   FMI 2.0  binaries/linux64 (build/)  + binaries/win64 (build-win64/)
#   FMI 3.0  binaries/x86_64-linux (build/) + x86_64-windows (build-win64/) + aarch64-linux (build-aarch64/source-fmu/)
# A binary from older sources is left out with a message, never shipped stale. scripts/build-win64.sh
# and scripts/build-aarch64.sh both end here, so either order of the two ships every platform.
#
#   bash scripts/package-dist.sh
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo"

# guid_of <modelDescription.xml>: the GUID (FMI 2.0) or instantiationToken (FMI 3.0).
guid_of() { sed -n 's/.*\(guid\|instantiationToken\)="\([^"]*\)".*/\2/p' "$1" | head -n 1; }

# add_binary <stage> <platform> <file> <name in binaries/>: copies it when it carries the GUID.
add_binary() {
  local stage="$1" platform="$2" file="$3" name="$4" guid
  [ -f "$file" ] || return 0
  guid="$(guid_of "$stage/modelDescription.xml")"
  if ! grep -qaF "$guid" "$file"; then
    echo "package-dist.sh: $file is from other sources (no GUID $guid): $platform left out; rebuild it" >&2
    return 0
  fi
  mkdir -p "$stage/binaries/$platform"
  cp "$file" "$stage/binaries/$platform/$name"
  if [ "${platform#*win}" != "$platform" ]; then
    # what the Windows binary links statically: the GCC runtime (GPL-3.0 with the GCC Runtime
    # Library Exception) and mingw-w64's runtime and winpthreads (ZPL/MIT)
    cp /usr/share/doc/g++-mingw-w64-x86-64-posix/copyright "$stage/documentation/licenses/GCC-runtime-mingw-w64.txt"
    cp /usr/share/doc/mingw-w64-common/copyright "$stage/documentation/licenses/mingw-w64-runtime-winpthreads.txt"
  fi
}

# package <native staged FMU folder> <output .fmu> <platform file name>...: the zip.
package() {
  local native="$1" out="$2" stage="$2.d.$$"
  shift 2
  [ -f "$native/modelDescription.xml" ] || { echo "package-dist.sh: $native missing: run scripts/setup.sh first" >&2; exit 1; }
  rm -rf "$stage" && mkdir -p "$(dirname "$out")"
  cp -r "$native" "$stage"
  while [ $# -gt 0 ]; do
    add_binary "$stage" "$1" "$2" "$3"
    shift 3
  done
  # extra/: the reference experiments; terminalsAndIcons/: FMI 3.0 terminals (both staged by the build).
  # Zipped beside and renamed into place: a test reading the FMU meanwhile (pytest -n) sees a whole file.
  rm -f "$out.part.$$"
  (cd "$stage" && cmake -E tar cf "$out.part.$$" --format=zip modelDescription.xml binaries documentation \
    $(ls -d extra terminalsAndIcons 2>/dev/null))
  mv -f "$out.part.$$" "$out"
  echo "package-dist.sh: wrote ${out#"$repo"/} ($(ls "$stage/binaries" | tr '\n' ' ')$(($(stat -c %s "$out") / 1024)) KiB)"
  rm -rf "$stage"
}

package build/fmu/PlateImpact.fmu.d "$repo/build/dist/PlateImpact.fmu" \
  win64 build-win64/fmu/PlateImpact.dll PlateImpact.dll
package build/fmu/fmi3/PlateImpact.fmu.d "$repo/build/dist/fmi3/PlateImpact.fmu" \
  x86_64-windows build-win64/fmu/fmi3/PlateImpact.dll PlateImpact.dll \
  aarch64-linux build-aarch64/source-fmu/binaries/aarch64-linux/PlateImpact.so PlateImpact.so
