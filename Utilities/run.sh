#!/usr/bin/env bash
# Utilities/run.sh [--headless] [--output DIR]
# The main job: installs what is missing, builds in Release, and opens ParaView with the VesselTouch
# plugin loaded, the built-in vessel phantom shown as a maximum-intensity projection and the
# VesselTouch panel open. --headless renders the same scene on a virtual display (Xvfb) and writes
# DIR/screenshot.png and DIR/report.txt (DIR defaults to build/run).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build"
headless=0
output="$build/run"
while (($# > 0)); do
  case "$1" in
    --headless) headless=1 ;;
    --output) output=$2; shift ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "run.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

"$root/Utilities/install-deps.sh"
"$root/Utilities/build.sh" "$build"

plugin_dir="$build/lib/paraview-5.11/plugins/VesselTouch"
startup="$root/Utilities/vesseltouch_startup.py"
if ((headless)); then
  export VESSELTOUCH_PLUGIN="$plugin_dir/VesselTouch.so"
  export VESSELTOUCH_OUTPUT_DIR="$output"
  "$root/Testing/Utilities/vtouch-xvfb-run" pvpython "$startup"
  echo "run.sh: wrote $output/screenshot.png and $output/report.txt"
else
  if [[ -z "${DISPLAY:-}" && -z "${WAYLAND_DISPLAY:-}" ]]; then
    echo "run.sh: no display; use 'Utilities/run.sh --headless' on machines without one" >&2
    exit 1
  fi
  exec paraview --plugin-search-paths="$plugin_dir" --plugins=VesselTouch --script="$startup"
fi
