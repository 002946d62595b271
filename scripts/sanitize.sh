#!/usr/bin/env bash
# Builds ccma with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DCCMA_SANITIZE=ON) and runs the CTest suite under them, in two builds:
#   1. build-asan/        RelWithDebInfo: optimised as released, NDEBUG set;
#   2. build-asan-debug/  Debug (at -O1, so that the suite runs in reasonable
#      time): no NDEBUG, so Eigen's eigen_assert (every index and size it
#      checks) and ccma's own assert() run too; a failed assertion aborts its
#      test. Eigen 3.4.0's BDCSVD read out of bounds for months in the first
#      build without a word (tests/data/rank_decisions/README.md).
# CCMA_SANITIZE_RUNS picks the runs: "release debug" (the default),
# "release" or "debug". Exits non-zero on a failing test or on any sanitizer
# report in either run, including reports from processes the tests start
# (the ccma tool run by the CLI tests, the installed-package consumer),
# whose output a test may swallow: every report is also written under
# <build folder>/sanitizer-logs/.
#   scripts/sanitize.sh                           # both builds, everything
#   scripts/sanitize.sh -R Cli                    # extra arguments go to ctest
#   CCMA_SANITIZE_RUNS=debug scripts/sanitize.sh  # the assertions build only
# It installs nothing: run scripts/test.sh (or scripts/setup.sh) first on a
# fresh machine, and apt-get install g++ (the sanitized builds use g++).
# Re-running is incremental (the build folders are kept, ccache is used when
# installed): after a small change it rebuilds only what changed.
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

RUNS="${CCMA_SANITIZE_RUNS:-release debug}"
JOBS="${CCMA_JOBS:-$(nproc)}"
SUPP_DIR="$PWD/scripts/sanitizer-suppressions"
for run in $RUNS; do
  if [ "$run" != release ] && [ "$run" != debug ]; then
    echo "sanitize: CCMA_SANITIZE_RUNS: unknown run '$run' (release or debug)" >&2
    exit 2
  fi
done

cat << EOF
sanitize: ASan + UBSan builds, each followed by the CTest suite; runs: $RUNS
sanitize:   release: build-asan/ (RelWithDebInfo, NDEBUG: optimised as released)
sanitize:   debug:   build-asan-debug/ (Debug at -O1, no NDEBUG: Eigen's and ccma's assertions on)
sanitize: runs every C++ and CLI test, the examples, the install consumer, the fuzz corpus
sanitize: replay, the docs and layout checks and the browser tests (skipped without chromium).
sanitize: excluded: the Python module and pytest (an ASan extension cannot load into an
sanitize:   uninstrumented python3; scripts/test.sh runs them), the benchmarks (timings).
EOF

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CTEST_ARGS=("$@")

# One build and its test run: sanitize_run <build folder> <cmake options>...
# Fails on a failed build, a failing test or a sanitizer report.
sanitize_run() {
  local build_dir="$1"
  shift
  local log_dir="$PWD/$build_dir/sanitizer-logs"
  mkdir -p "$build_dir"
  # One place for the options: the build runs the test programs too
  # (GoogleTest discovery), so it gets them as well. log_path: reports go to
  # files (report.<pid>), which are listed and shown at the end.
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:log_path=$log_dir/report:suppressions=$SUPP_DIR/asan.supp"
  export LSAN_OPTIONS="suppressions=$SUPP_DIR/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$log_dir/report:suppressions=$SUPP_DIR/ubsan.supp"
  # A new build folder compiles with g++ (its sanitizer runtime comes with
  # it). Not clang yet: its UndefinedBehaviorSanitizer also checks pointer
  # arithmetic on null, which Eigen does for blocks of empty matrices
  # (Block.h: "applying non-zero offset to null pointer", first met in
  # MinimumNormSolver::nullSpace of a full-rank matrix); g++ does not check it.
  local compiler=()
  if [ ! -f "$build_dir/CMakeCache.txt" ] && [ -z "${CXX:-}" ]; then
    if ! command -v g++ > /dev/null; then
      echo "sanitize: needs g++ (apt-get install g++; scripts/setup.sh installs clang only)" >&2
      return 1
    fi
    compiler=(-DCMAKE_CXX_COMPILER=g++)
  fi
  if ! cmake -S . -B "$build_dir" "${compiler[@]}" "$@" -DCCMA_SANITIZE=ON \
       -DCCMA_BUILD_BENCHMARKS=OFF -DCCMA_BUILD_PYTHON=OFF "${launcher[@]}" \
       > "$build_dir/configure.log" 2>&1; then
    cat "$build_dir/configure.log"
    echo "sanitize: cmake configure failed; are the dependencies installed? Run scripts/setup.sh first." >&2
    return 1
  fi
  rm -rf "$log_dir"
  mkdir -p "$log_dir"

  local status=0 start=$SECONDS
  echo "sanitize: building $build_dir/ (about 25 minutes on 2 cores the first time, far less again; log: $build_dir/build.log)"
  if ! cmake --build "$build_dir" -j"$JOBS" > "$build_dir/build.log" 2>&1; then
    tail -50 "$build_dir/build.log"
    echo "sanitize: build failed (full log: $build_dir/build.log)" >&2
    status=1
  fi
  echo "sanitize: built $build_dir/ in $((SECONDS - start)) s"
  if ((status == 0)); then
    echo "sanitize: running the tests in $build_dir/ (ctest -j$JOBS, a line per test)"
    (cd "$build_dir" && ctest --output-on-failure -j"$JOBS" ${CTEST_ARGS[@]+"${CTEST_ARGS[@]}"}) || status=1
  fi

  shopt -s nullglob
  local reports=("$log_dir"/report.*)
  if ((${#reports[@]})); then
    for r in "${reports[@]}"; do
      echo "==================== sanitizer report: $r"
      cat "$r"
    done
    echo "sanitize: ${#reports[@]} sanitizer report(s) in $log_dir" >&2
    status=1
  fi
  if ((status == 0)); then
    echo "sanitize: $build_dir/: all tests passed under ASan + UBSan, no sanitizer reports ($((SECONDS - start)) s)"
  fi
  return "$status"
}

status=0
for run in $RUNS; do
  case "$run" in
    release) sanitize_run build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo || status=1 ;;
    # -O1: Eigen at -O0 under ASan makes the longest tests several times
    # slower; the assertions, not the -O0, are what this build is for.
    debug) sanitize_run build-asan-debug -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g -O1" || status=1 ;;
  esac
done
if ((status == 0)); then
  echo "sanitize: passed: $RUNS"
else
  echo "sanitize: failed (see above)" >&2
fi
exit "$status"
