#!/usr/bin/env bash
# Builds ccma with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-asan/ (RelWithDebInfo, -DCCMA_SANITIZE=ON, no benchmarks) and runs the
# whole CTest suite under them. Exits non-zero on a failing test or on any
# sanitizer report, including reports from processes the tests start (the
# ccma tool run by cli_test, the installed-package consumer), whose output a
# test may swallow: every report is also written under build-asan/sanitizer-logs/.
#   scripts/sanitize.sh                 # configure, build, run everything
#   scripts/sanitize.sh -R cli_test     # extra arguments go to ctest
# It installs nothing: run scripts/setup.sh first on a fresh machine.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR=build-asan
JOBS="${CCMA_JOBS:-$(nproc)}"
LOG_DIR="$PWD/$BUILD_DIR/sanitizer-logs"
mkdir -p "$BUILD_DIR"

# One place for the options: the build runs the test programs too (GoogleTest
# discovery), so it gets them as well. log_path: reports go to files
# (report.<pid>), which are listed and shown at the end.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:log_path=$LOG_DIR/report"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$LOG_DIR/report"

# No Python module: an ASan-instrumented extension cannot be loaded into an
# uninstrumented python3 ("ASan runtime does not come first"); the Python
# tests run in the normal build (scripts/test.sh).
if ! cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCCMA_SANITIZE=ON \
     -DCCMA_BUILD_BENCHMARKS=OFF -DCCMA_BUILD_PYTHON=OFF > "$BUILD_DIR/configure.log" 2>&1; then
  cat "$BUILD_DIR/configure.log"
  echo "sanitize: cmake configure failed; are the dependencies installed? Run scripts/setup.sh first." >&2
  exit 1
fi

rm -rf "$LOG_DIR"
mkdir -p "$LOG_DIR"

status=0
if ! cmake --build "$BUILD_DIR" -j"$JOBS" > "$BUILD_DIR/build.log" 2>&1; then
  tail -50 "$BUILD_DIR/build.log"
  echo "sanitize: build failed (full log: $BUILD_DIR/build.log)" >&2
  status=1
fi

if ((status == 0)); then
  (cd "$BUILD_DIR" && ctest --output-on-failure -j"$JOBS" "$@") || status=1
fi

shopt -s nullglob
reports=("$LOG_DIR"/report.*)
if ((${#reports[@]})); then
  for r in "${reports[@]}"; do
    echo "==================== sanitizer report: $r"
    cat "$r"
  done
  echo "sanitize: ${#reports[@]} sanitizer report(s) in $LOG_DIR" >&2
  status=1
fi

if ((status == 0)); then
  echo "sanitize: all tests passed under ASan + UBSan, no sanitizer reports"
fi
exit "$status"
