#!/usr/bin/env bash
# make test: the whole suite under CTest. A test that *crashed* (killed by a signal: CTest's
# "***Exception") is run once more, alone; a test whose checks failed, or that timed out, is
# never rerun. Why: the suite has a known intermittent heap corruption whose cause is not
# found (docs/testing.md, "Known intermittent failure"): a few times in many runs, one long
# lavapipe test aborts in glibc's heap checks or dies of SIGBUS, and passes when run again.
# The crash report (tests/crash_report.cpp) stays in the log, and the summary names every
# crashed test, so each occurrence is still seen and counted.
# PRESET (default release) and JOBS (default: the cores) as in the Makefile.
set -uo pipefail
preset=${PRESET:-release}
jobs=${JOBS:-$(nproc)}
log=$(mktemp)
trap 'rm -f "$log"' EXIT

ctest --preset "$preset" -j "$jobs" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
[ "$status" -eq 0 ] && exit 0

# CTest's result lines: "Test #N: NAME ....   Passed", "***Failed", "***Timeout",
# "Subprocess aborted***Exception:", "SEGFAULT***Exception:", "Bus error***Exception:", ...
results=$(grep -E 'Test +#[0-9]+: ' "$log")
crashed=$(grep -E '\*\*\*Exception' <<<"$results" | sed -E 's/.*Test +#[0-9]+: ([^ ]+) .*/\1/')
others=$(grep -E '\*\*\*(Failed|Timeout)|Not Run[^(]*$' <<<"$results" | grep -v 'Disabled' |
  sed -E 's/.*Test +#[0-9]+: ([^ ]+) .*/\1/')
if [ -n "$others" ] || [ -z "$crashed" ]; then
  echo "run-tests: failed (not rerun):" >&2
  printf '  %s\n' $others >&2
  exit "$status"
fi

echo
echo "run-tests: $(wc -l <<<"$crashed") test(s) crashed; rerunning only them, once:"
printf '  %s\n' $crashed
if ctest --preset "$preset" --rerun-failed; then
  echo "run-tests: the crashed test(s) passed when rerun. This is the known intermittent"
  echo "run-tests: heap corruption (docs/testing.md); its crash report is above."
  exit 0
fi
echo "run-tests: a crashed test failed again when rerun" >&2
exit 1
