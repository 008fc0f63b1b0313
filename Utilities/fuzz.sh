#!/usr/bin/env bash
# Builds the HID libFuzzer targets with clang in their own build folder and runs each one for a
# bounded time from the committed seed corpus. Exits non-zero on any crash, leak, sanitizer report
# or build failure.
#
#   Utilities/fuzz.sh [seconds-per-target]        (default 30, or $VTOUCH_FUZZ_SECONDS)
#
# Environment: VTOUCH_FUZZ_BUILD_DIR (default <repo>/build-fuzz), VTOUCH_FUZZ_JOBS (default 2),
# CC/CXX (default clang/clang++).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VTOUCH_FUZZ_BUILD_DIR:-$repo/build-fuzz}"
seconds="${1:-${VTOUCH_FUZZ_SECONDS:-30}}"
jobs="${VTOUCH_FUZZ_JOBS:-2}"
corpus="$repo/Testing/HapticDevice/corpus"

if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "fuzz.sh: seconds must be a positive integer (got '$seconds')" >&2
  exit 2
fi
if ! command -v "${CXX:-clang++}" >/dev/null 2>&1; then
  echo "fuzz.sh: ${CXX:-clang++} not found (apt-get install clang libclang-rt-dev)" >&2
  exit 2
fi

echo "== configuring $build (clang, fuzzers only)"
mkdir -p "$build"
CC="${CC:-clang}" CXX="${CXX:-clang++}" cmake -S "$repo" -B "$build" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DVESSELTOUCH_BUILD_PLUGIN=OFF \
  -DVESSELTOUCH_BUILD_TESTING=OFF \
  -DVESSELTOUCH_BUILD_BENCHMARKS=OFF \
  -DVESSELTOUCH_BUILD_FUZZERS=ON >"$build/configure.log" 2>&1 || {
  cat "$build/configure.log" >&2
  echo "fuzz.sh: configure failed" >&2
  exit 1
}

targets=(vtouchHidDescriptorFuzzer vtouchHidInputReportFuzzer)
echo "== building ${targets[*]}"
cmake --build "$build" -j"$jobs" --target "${targets[@]}"

declare -A seeds=([vtouchHidDescriptorFuzzer]=descriptor [vtouchHidInputReportFuzzer]=input_report)
mkdir -p "$build/artifacts"
status=0
for target in "${targets[@]}"; do
  # New inputs go to a scratch corpus; the committed seeds are only read.
  scratch="$build/corpus/${seeds[$target]}"
  mkdir -p "$scratch"
  echo "== running $target for ${seconds}s"
  if ! "$build/Testing/HapticDevice/Fuzz/$target" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
      "$scratch" "$corpus/${seeds[$target]}"; then
    echo "fuzz.sh: $target FAILED; reproducer in $build/artifacts/" >&2
    status=1
  fi
done
if [ "$status" -eq 0 ]; then
  echo "fuzz.sh: ${#targets[@]} passed, 0 failed"
else
  echo "fuzz.sh: some targets failed"
fi
exit "$status"
