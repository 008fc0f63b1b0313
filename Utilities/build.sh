#!/usr/bin/env bash
# Utilities/build.sh [BUILD_DIR] [extra cmake arguments...]
# Configures (once) and builds VesselTouch in Release. Fast when nothing changed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-"$root/build"}
shift || true
jobs=${VESSELTOUCH_JOBS:-$(nproc)}
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
elif (($# > 0)); then
  cmake "$build" "$@"
fi
cmake --build "$build" -j "$jobs"
