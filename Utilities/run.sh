#!/usr/bin/env bash
# Utilities/run.sh [--headless] [--output DIR] [--build DIR] [--no-build]
# The main job: installs what is missing, builds in Release, and opens ParaView with the VesselTouch
# plugin loaded, the built-in vessel phantom (a tree) shown as a maximum-intensity projection, its
# centerline extracted with VesselCenterline and the VesselTouch session (vesseltouch.logic(), the
# proxy "VesselTouchSession" the panel shows) bound to it with the pointer device and the view's
# camera. --headless runs on a virtual display (Xvfb) a deterministic scripted trace with the
# simulated device and ~1 s of the real-time loop, and writes into DIR (default build/run):
# screenshot.png (agent cone over the MIP), force.png, trace.npz, loop_statistics.json, report.txt.
# --build DIR uses that build tree (default build/); --no-build skips install-deps and build.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build"
headless=0
compile=1
output=""
while (($# > 0)); do
  case "$1" in
    --headless) headless=1 ;;
    --output) output=$2; shift ;;
    --build) build=$(cd "$2" && pwd); shift ;;
    --no-build) compile=0 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
output=${output:-"$build/run"}

if ((compile)); then
  "$root/Utilities/install-deps.sh"
  "$root/Utilities/build.sh" "$build"
fi

plugin_dir="$build/lib/paraview-5.11/plugins/VesselTouch"
startup="$root/Utilities/vesseltouch_startup.py"
export VESSELTOUCH_SOURCE_DIR="$root"
if ((headless)); then
  mkdir -p "$output"
  output=$(cd "$output" && pwd)
  export VESSELTOUCH_PLUGIN="$plugin_dir/VesselTouch.so"
  export VESSELTOUCH_OUTPUT_DIR="$output"
  export VESSELTOUCH_TRACE=1
  start=$(date +%s%N)
  "$root/Testing/Utilities/vtouch-xvfb-run" pvpython "$startup"
  elapsed_ms=$((($(date +%s%N) - start) / 1000000))
  printf 'run.sh: wrote %s/{screenshot.png,force.png,trace.npz,loop_statistics.json,report.txt} in %d.%03d s\n' \
    "$output" $((elapsed_ms / 1000)) $((elapsed_ms % 1000))
else
  if [[ -z "${DISPLAY:-}" && -z "${WAYLAND_DISPLAY:-}" ]]; then
    echo "run.sh: no display; use 'Utilities/run.sh --headless' on machines without one" >&2
    exit 1
  fi
  exec paraview --plugin-search-paths="$plugin_dir" --plugins=VesselTouch --script="$startup"
fi
