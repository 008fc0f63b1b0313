#!/usr/bin/env bash
# Utilities/build.sh [BUILD_DIR] [extra cmake arguments...]
# Configures (once) and builds VesselTouch in Release. Fast when nothing changed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-"$root/build"}
shift || true
jobs=${VESSELTOUCH_JOBS:-$(nproc)}
launcher=()
if command -v ccache >/dev/null; then
  # Rebuilds of the three trees (Release, ASan, TSan) share compiled objects where they can.
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
elif (($# > 0)); then
  cmake "$build" "$@"
fi
cmake --build "$build" -j "$jobs"
