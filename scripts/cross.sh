#!/usr/bin/env bash
# The same bits on another target: builds the core and hsr_identity (tests/identity) for
# TARGET, runs it there, and compares every line (each render's hashes of its ids, depth
# and colour, or a drawing's) with this machine's x86-64 build of the same program.
#   bash scripts/cross.sh arm64             every shipped scene and hard case at the goldens'
#                                           width (320) and 100 random scenes, under qemu-user
#   bash scripts/cross.sh arm64 --quick     the hard cases and 10 random scenes at 48 pixels
#                                           wide, built at -O1 (what CI runs)
#   bash scripts/cross.sh windows [--quick] the same for 64-bit Windows, under wine
# arm64: Debian's g++-aarch64-linux-gnu and qemu-user; windows: Debian's MinGW-w64 (POSIX
# threads) and wine; installed here when missing. The core needs no compiled library but
# the standard one (CMakeLists.txt, HSR_CORE_ONLY), so no package of the target's
# besides the compiler's own is needed. Exit status 0 when every line is the same, 1
# otherwise (the differing lines printed).
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/cross.sh arm64|windows [--quick]}
arguments=(scenes --width 320 --random 100)
build="build-$target"
optimize=()
if [ "${2:-}" = --quick ]; then
  # The hard cases and 10 random scenes at 48 pixels wide (under emulation the shipped
  # scenes' large meshes take most of a full run's 20 minutes), built at -O1, which
  # compiles in about half the time: the bits do not depend on it (no optimization level
  # reorders or fuses floating-point operations under -ffp-contract=off).
  arguments=(scenes --width 48 --random 10 --only hard/)
  build="build-$target-quick"
  optimize=(-DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG")
fi

program=hsr_identity
case $target in
  arm64)
    toolchain=cmake/toolchains/aarch64-linux-gnu.cmake
    run=(qemu-aarch64 -L /usr/aarch64-linux-gnu)
    ;;
  windows)
    toolchain=cmake/toolchains/x86_64-w64-mingw32.cmake
    run=(/usr/lib/wine/wine64)  # Debian's wine64 package; its "wine" launcher is another package
    program=hsr_identity.exe
    export WINEDEBUG=-all WINEPREFIX="$PWD/build-windows-wine"  # a prefix of its own, quiet
    ;;
  *) echo "cross.sh: unknown target '$target'; expected arm64 or windows" >&2; exit 2 ;;
esac
bash scripts/setup.sh tests "$target"

# This machine's build of the same program, as the reference line by line.
cmake --preset release >/dev/null
cmake --build build -j"$(nproc)" --target hsr_identity
cmake -S . -B "$build" -DCMAKE_TOOLCHAIN_FILE="$toolchain" -DCMAKE_BUILD_TYPE=Release -DHSR_CORE_ONLY=ON "${optimize[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" --target hsr_identity

out=out/cross
mkdir -p "$out"
started=$SECONDS
./build/tests/identity/hsr_identity "${arguments[@]}" >"$out/x86-64.txt"
native=$(( SECONDS - started ))
started=$SECONDS
"${run[@]}" "$build/tests/identity/$program" "${arguments[@]}" | tr -d '\r' >"$out/$target.txt"
echo "x86-64: ${native} s; $target (${run[0]}): $(( SECONDS - started )) s"
renders=$(wc -l <"$out/x86-64.txt")
if diff "$out/x86-64.txt" "$out/$target.txt" >"$out/$target.diff"; then
  echo "$target: all $renders renders (ids, depth and colour, or drawings) bit-identical to x86-64 (${arguments[*]:1})"
else
  echo "$target: $(grep -c '^<' "$out/$target.diff") of $renders renders differ from x86-64 (< x86-64, > $target):" >&2
  head -40 "$out/$target.diff" >&2
  exit 1
fi
