#!/usr/bin/env bash
# Builds ccma with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-asan/ (RelWithDebInfo, -DCCMA_SANITIZE=ON) and runs the CTest suite
# under them. Exits non-zero on a failing test or on any sanitizer report,
# including reports from processes the tests start (the ccma tool run by the
# CLI tests, the installed-package consumer), whose output a test may swallow:
# every report is also written under build-asan/sanitizer-logs/.
#   scripts/sanitize.sh                 # configure, build, run everything
#   scripts/sanitize.sh -R Cli          # extra arguments go to ctest
# It installs nothing: run scripts/test.sh (or scripts/setup.sh) first on a
# fresh machine, and apt-get install g++ (the sanitized build uses g++). Re-running is incremental (build-asan/ is kept, ccache is
# used when installed): after a small change it rebuilds only what changed.
#
# What runs: every C++ test (GoogleTest), every CLI test (they start the
# sanitized ccma tool), the examples, the installed-package consumer, the
# fuzz corpus replay, the docs and layout checks, and the viewer's browser
# tests (the sanitized tool writes the pages; they are skipped, as in the
# normal build, when /usr/bin/chromium is missing).
# What does not run, and why (the same list is printed when it starts):
#   - the Python module and its pytest suite (python_test_*): an
#     ASan-instrumented extension cannot be loaded into an uninstrumented
#     python3 ("ASan runtime does not come first in initial library list");
#     they run in the normal build (scripts/test.sh).
#   - the benchmarks (CCMA_BUILD_BENCHMARKS=OFF): timings, not tests; under
#     ASan they would measure the sanitizer.
# Reports in code that is not ccma's (Debian's Ceres, glog, libsdformat,
# urdfdom, ...) are suppressed, narrowly and each with its reason, by
# scripts/sanitizer-suppressions/{asan,lsan,ubsan}.supp.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR=build-asan
JOBS="${CCMA_JOBS:-$(nproc)}"
LOG_DIR="$PWD/$BUILD_DIR/sanitizer-logs"
SUPP_DIR="$PWD/scripts/sanitizer-suppressions"
mkdir -p "$BUILD_DIR"

cat << 'EOF'
sanitize: ASan + UBSan build in build-asan/ (RelWithDebInfo), then the CTest suite.
sanitize: runs every C++ and CLI test, the examples, the install consumer, the fuzz corpus
sanitize: replay, the docs and layout checks and the browser tests (skipped without chromium).
sanitize: excluded: the Python module and pytest (an ASan extension cannot load into an
sanitize:   uninstrumented python3; scripts/test.sh runs them), the benchmarks (timings).
EOF

# One place for the options: the build runs the test programs too (GoogleTest
# discovery), so it gets them as well. log_path: reports go to files
# (report.<pid>), which are listed and shown at the end.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:log_path=$LOG_DIR/report:suppressions=$SUPP_DIR/asan.supp"
export LSAN_OPTIONS="suppressions=$SUPP_DIR/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$LOG_DIR/report:suppressions=$SUPP_DIR/ubsan.supp"

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# A new build-asan/ compiles with g++ (its sanitizer runtime comes with it).
# Not clang yet: its UndefinedBehaviorSanitizer also checks pointer
# arithmetic on null, which Eigen does for blocks of empty matrices
# (Block.h: "applying non-zero offset to null pointer", first met in
# MinimumNormSolver::nullSpace of a full-rank matrix); g++ does not check it.
compiler=()
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ] && [ -z "${CXX:-}" ]; then
  if ! command -v g++ > /dev/null; then
    echo "sanitize: needs g++ (apt-get install g++; scripts/setup.sh installs clang only)" >&2
    exit 1
  fi
  compiler=(-DCMAKE_CXX_COMPILER=g++)
fi
if ! cmake -S . -B "$BUILD_DIR" "${compiler[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCCMA_SANITIZE=ON \
     -DCCMA_BUILD_BENCHMARKS=OFF -DCCMA_BUILD_PYTHON=OFF "${launcher[@]}" \
     > "$BUILD_DIR/configure.log" 2>&1; then
  cat "$BUILD_DIR/configure.log"
  echo "sanitize: cmake configure failed; are the dependencies installed? Run scripts/setup.sh first." >&2
  exit 1
fi

rm -rf "$LOG_DIR"
mkdir -p "$LOG_DIR"

status=0
start=$SECONDS
echo "sanitize: building (about 25 minutes on 2 cores the first time, far less again; log: $BUILD_DIR/build.log)"
if ! cmake --build "$BUILD_DIR" -j"$JOBS" > "$BUILD_DIR/build.log" 2>&1; then
  tail -50 "$BUILD_DIR/build.log"
  echo "sanitize: build failed (full log: $BUILD_DIR/build.log)" >&2
  status=1
fi
echo "sanitize: built in $((SECONDS - start)) s"

if ((status == 0)); then
  echo "sanitize: running the tests (ctest -j$JOBS, a line per test)"
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
  echo "sanitize: all tests passed under ASan + UBSan, no sanitizer reports ($((SECONDS - start)) s)"
fi
exit "$status"
