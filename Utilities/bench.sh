#!/usr/bin/env bash
# Utilities/bench.sh [--quick] [--build DIR] [--out DIR] [--publish] [--only SECTION...]
# One command for speed against accuracy: builds (Release, benchmarks on) if needed, runs every
# benchmark (centerlines vs scikit-image, haptic loop timing, force error vs loop rate, stability
# maps, agent frame rate), writes OUT/results.json (flat keys, units in the names), checks it, and
# draws the PNG charts in OUT.
#   --quick    smaller volumes, fewer points, shorter runs (< 2 min); every key still written,
#              meta.quick = 1
#   --build    build folder (default build/ beside Utilities)
#   --out      output folder (default BUILD/bench)
#   --publish  also copy the charts to Docs/performance/ (for Docs/PERFORMANCE.md)
#   --only     run only these sections (centerline rawcenterline haptic force stability render gui
#              scaling); the others'
#              keys are kept from the previous results.json
# Needs /usr/bin/python3 with numpy, scipy, matplotlib and scikit-image, pvpython and Xvfb.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=0
publish=0
build="$root/build"
out=""
only=()
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --publish) publish=1 ;;
    --build) build=$(realpath -m "$2"); shift ;;
    --out) out=$(realpath -m "$2"); shift ;;
    --only)
      shift
      while (($#)) && [[ "$1" != --* ]]; do only+=("$1"); shift; done
      continue ;;
    -h|--help) sed -n '2,15p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
out=${out:-"$build/bench"}
py=/usr/bin/python3
start=$(date +%s)

# Build (fast when nothing changed). An existing build keeps its settings; benchmarks are forced on.
if [[ -f "$build/CMakeCache.txt" ]] && grep -q "^VESSELTOUCH_BUILD_BENCHMARKS:BOOL=ON" "$build/CMakeCache.txt"; then
  "$root/Utilities/build.sh" "$build" || { echo "bench.sh: the build failed" >&2; exit 1; }
else
  "$root/Utilities/build.sh" "$build" -DVESSELTOUCH_BUILD_BENCHMARKS=ON \
    || { echo "bench.sh: the build failed" >&2; exit 1; }
fi
built=$(date +%s)

mkdir -p "$out"
args=(--build "$build" --out "$out")
((quick)) && args+=(--quick)
((${#only[@]})) && args+=(--only "${only[@]}")
"$py" "$root/Utilities/bench/run_bench.py" "${args[@]}" 2>&1 | tee "$out/bench.log"
run_status=${PIPESTATUS[0]}
"$py" "$root/Utilities/bench/charts.py" "$out" || run_status=1
"$py" "$root/Utilities/bench/check_results.py" "$out/results.json" || run_status=1
if ((publish)); then
  mkdir -p "$root/Docs/performance"
  cp "$out"/*.png "$root/Docs/performance/"
  cp "$out/results.json" "$out/summary.md" "$root/Docs/performance/"
  echo "bench.sh: charts copied to Docs/performance/"
fi
end=$(date +%s)
echo "bench.sh: build $((built - start)) s, benchmarks and charts $((end - built)) s; results in $out"
exit $run_status
