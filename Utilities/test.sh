#!/usr/bin/env bash
# Utilities/test.sh [--quick]
# Installs what is missing, builds and runs the whole test suite:
#   1. Release build with the plugin: unit (GoogleTest, QtTest), integration (pvpython) and gui
#      (the real ParaView under Xvfb) tests;
#   2. an ASan+UBSan build of the libraries and their unit tests;
#   3. a TSan build of the threaded code (haptic loop, exchanges, device watchdog) and its tests;
#   4. the libFuzzer targets of the HID parsers for a bounded time.
# After step 1, 'Utilities/bench.sh --quick' and its results checker count as one test (bench).
# --quick runs step 1 and the bench test only. Ends with the overall 'N passed, N failed' line.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=0
[[ "${1:-}" == "--quick" ]] && quick=1
jobs=${VESSELTOUCH_JOBS:-$(nproc)}
export CTEST_OUTPUT_ON_FAILURE=1

"$root/Utilities/install-deps.sh" || exit 1

passed=0
failed=0
status=0
summary=()
logs=()
# run_ctest LABEL BUILD_DIR [ctest args...]: runs ctest and adds its counts to the totals.
run_ctest() {
  local label=$1 dir=$2
  shift 2
  local log="$dir/ctest-$label.log"
  ctest --test-dir "$dir" -j "$jobs" --output-on-failure "$@" 2>&1 | tee "$log"
  local rc=${PIPESTATUS[0]}
  logs+=("$log")
  local line
  line=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$log" | tail -n1)
  local total fails
  total=$(sed -E 's/.*out of ([0-9]+).*/\1/' <<<"$line")
  fails=$(sed -E 's/.*, ([0-9]+) tests failed.*/\1/' <<<"$line")
  if [[ -z "$line" || "$total" == "0" ]]; then
    echo "test.sh: $label ran no test" >&2
    status=1
    summary+=("$label: no test ran")
    return
  fi
  passed=$((passed + total - fails))
  failed=$((failed + fails))
  ((rc != 0)) && status=1
  # Tests that failed an attempt and passed when repeated (--repeat until-pass): named, not hidden.
  local retried
  retried=$(grep -E '^ +Test +#[0-9]+: .*\*\*\*' "$log" | sed -E 's/^ +Test +#[0-9]+: ([^ ]+) .*/\1/' | sort -u |
    while read -r t; do grep -qE "^ *[0-9]+/[0-9]+ Test +#[0-9]+: $t .*Passed" "$log" && echo -n "$t "; done)
  summary+=("$label: $((total - fails)) passed, $fails failed${retried:+ (passed when repeated: ${retried% })}")
}

# 1. Release build with everything.
if ! "$root/Utilities/build.sh" "$root/build"; then
  echo "test.sh: the Release build failed" >&2
  exit 1
fi
# The GUI and client/server tests drive real windows, a 1 kHz loop and MPI servers on a shared
# machine: a test that fails is run once more, and the summary names every test that needed it.
run_ctest release "$root/build" --repeat until-pass:2

# Benchmarks, quick mode: every results.json key present and finite (one test).
if "$root/Utilities/bench.sh" --quick --build "$root/build" --out "$root/build/bench" &&
  /usr/bin/python3 "$root/Utilities/bench/check_results.py" "$root/build/bench/results.json"; then
  passed=$((passed + 1))
  summary+=("bench: passed")
else
  failed=$((failed + 1))
  status=1
  summary+=("bench: FAILED")
fi

if ((!quick)); then
  common=(-DVESSELTOUCH_BUILD_PLUGIN=OFF -DVESSELTOUCH_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo)
  # 2. Address and undefined-behaviour sanitizers on the unit tests.
  if "$root/Utilities/build.sh" "$root/build-asan" "${common[@]}" "-DVESSELTOUCH_SANITIZER=address;undefined"; then
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      LSAN_OPTIONS="suppressions=$root/Testing/Utilities/lsan.supp" \
      run_ctest asan-ubsan "$root/build-asan"
  else
    echo "test.sh: the ASan+UBSan build failed" >&2
    status=1
    summary+=("asan-ubsan: build failed")
  fi
  # 3. Thread sanitizer on the threaded code's tests (label 'threads').
  if "$root/Utilities/build.sh" "$root/build-tsan" "${common[@]}" -DVESSELTOUCH_SANITIZER=thread; then
    TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 run_ctest tsan "$root/build-tsan" -L threads
  else
    echo "test.sh: the TSan build failed" >&2
    status=1
    summary+=("tsan: build failed")
  fi
  # 4. Fuzzing the HID descriptor and input-report parsers for a bounded time.
  if [[ -x "$root/Utilities/fuzz.sh" ]]; then
    if "$root/Utilities/fuzz.sh"; then
      passed=$((passed + 1))
      summary+=("fuzz: passed")
    else
      failed=$((failed + 1))
      status=1
      summary+=("fuzz: FAILED")
    fi
  fi
fi

# What failed, with the end of its output, last: a CI that keeps only the tail still shows it.
for log in "${logs[@]}"; do
  "$root/Utilities/failed-test-output.sh" "$log" 40
done
echo
printf '%s\n' "${summary[@]}"
echo "Total: $passed passed, $failed failed"
exit $status
