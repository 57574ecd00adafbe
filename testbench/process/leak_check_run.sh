#!/usr/bin/env bash
# Runs one test program of the sanitize build (cmake/Tessera.cmake wraps
# every tessera_add_test there) and retries it, up to three runs, only when
# LeakSanitizer's own stop-the-world tracer crashed at exit: "Tracer caught
# signal" followed by "LeakSanitizer has encountered a fatal error", with no
# leak report. That crash is LeakSanitizer's, not the program's (its tracer
# ptrace-suspends every thread to scan them; on a loaded machine it dies
# now and then, in programs of every kind: tests/README.md "Leak checking").
# Every other outcome is final at once: a leak report, a sanitizer error, a
# failed assertion or a signal of the program itself fails the test on its
# first run, so a retry can never hide a real leak or bug.
#
#   leak_check_run.sh PROGRAM [ARGUMENTS...]
set -uo pipefail
if [[ $# -lt 1 ]]; then
  echo "leak_check_run.sh: no program given" >&2
  exit 2
fi
log=$(mktemp "${TMPDIR:-/tmp}/leak_check_run.XXXXXX")
trap 'rm -f "$log"' EXIT
runs=3
for ((run = 1; run <= runs; run++)); do
  "$@" >"$log" 2>&1
  status=$?
  if [[ $status -ne 0 ]] && grep -q "^Tracer caught signal" "$log" &&
     grep -q "LeakSanitizer has encountered a fatal error" "$log" &&
     ! grep -q "ERROR: LeakSanitizer: detected memory leaks" "$log" && [[ $run -lt $runs ]]; then
    echo "leak_check_run.sh: run $run of $*: LeakSanitizer's tracer crashed at exit (not a leak report, not the program's failure): running it again"
    continue
  fi
  cat "$log"
  [[ $run -gt 1 ]] && echo "leak_check_run.sh: run $run of $runs was final (exit status $status)"
  exit "$status"
done
