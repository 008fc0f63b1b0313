#!/usr/bin/env bash
# Utilities/failed-test-output.sh LOG [LINES]
# Prints, for every test run a ctest log (run with --output-on-failure) reports as failed or timed
# out, its name and the last LINES (default 40) lines of its output; with --repeat until-pass, a
# failed attempt that was then repeated is printed too, marked "attempt". test.sh calls it at the very end,
# so that a CI system that keeps only the tail of the output still shows what failed and why.
set -uo pipefail
log=$1
lines=${2:-40}
[[ -f "$log" ]] || exit 0
awk -v keep="$lines" '
  function flush() {
    if (name != "") {
      print "---- " name " (" verdict "): last " (n < keep ? n : keep) " lines of its output";
      for (i = (n > keep ? n - keep + 1 : 1); i <= n; ++i) print buf[i];
    }
    name = ""; n = 0;
  }
  /^ *Start +[0-9]+: / { flush(); next }
  /^ *([0-9]+\/[0-9]+ )?Test +#[0-9]+: / {
    flush();
    if ($0 ~ /\*\*\*|Failed|Timeout|Not Run|Exception/) {
      name = $0; sub(/^ *([0-9]+\/[0-9]+ )?Test +#[0-9]+: /, "", name); sub(/ \.+.*/, "", name);
      verdict = $0; sub(/.*\.+ */, "", verdict);
      if ($0 !~ /^ *[0-9]+\/[0-9]+ /) verdict = "attempt " verdict;
    }
    next
  }
  /^[0-9]+% tests passed/ { flush(); exit }
  name != "" { buf[++n] = $0 }
  END { flush() }
' "$log"
