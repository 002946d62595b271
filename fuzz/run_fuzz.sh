#!/usr/bin/env bash
# Fuzzes the model loader with libFuzzer for a while (issue "hostile input").
#
#   fuzz/run_fuzz.sh [seconds]        default 30
#
# Configures a separate build directory (build-fuzz, or $CCMA_FUZZ_BUILD_DIR)
# with clang, -DCCMA_FUZZ=ON and AddressSanitizer + UndefinedBehaviorSanitizer,
# builds only loader_fuzzer, and runs it over a scratch copy of fuzz/corpus with
# fuzz/loader.dict. Exits non-zero when the fuzzer finds a crash (the input is
# left as crash-* in the build directory); prints one "skipped" line and exits
# 0 when clang is not installed. $CCMA_SOURCE_DIR overrides the source tree.
set -euo pipefail

seconds="${1:-30}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || (( seconds < 1 )); then
  echo "usage: $0 [seconds]  (a positive whole number, default 30)" >&2
  exit 2
fi

if ! command -v clang++ >/dev/null 2>&1 || ! command -v clang >/dev/null 2>&1; then
  echo "fuzz/run_fuzz.sh: skipped: clang not installed (apt-get install clang libclang-rt-14-dev)"
  exit 0
fi
fuzz_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source_dir="${CCMA_SOURCE_DIR:-$(dirname "$fuzz_dir")}"
build_dir="${CCMA_FUZZ_BUILD_DIR:-$source_dir/build-fuzz}"

if ! grep -q "CCMA_FUZZ" "$source_dir/CMakeLists.txt"; then
  echo "fuzz/run_fuzz.sh: $source_dir/CMakeLists.txt has no CCMA_FUZZ option (see fuzz/CMakeLists.txt)" >&2
  exit 2
fi

CC=clang CXX=clang++ cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCCMA_FUZZ=ON -DCCMA_BUILD_TESTS=OFF -DCCMA_BUILD_BENCHMARKS=OFF >"$build_dir.configure.log" 2>&1 \
  || { cat "$build_dir.configure.log" >&2; exit 2; }
cmake --build "$build_dir" -j"${CCMA_FUZZ_JOBS:-2}" --target loader_fuzzer

fuzzer="$(find "$build_dir" -type f -name loader_fuzzer -perm -u+x | head -n 1)"
[[ -n "$fuzzer" ]] || { echo "fuzz/run_fuzz.sh: loader_fuzzer was not built" >&2; exit 2; }

# Work on a copy: new inputs go there, the checked-in seed corpus stays small.
work="$build_dir/corpus"
mkdir -p "$work"
cp -n "$fuzz_dir"/corpus/* "$work"/ 2>/dev/null || true

cd "$build_dir"
echo "fuzz/run_fuzz.sh: running $fuzzer for ${seconds}s over $work"
set +e
"$fuzzer" -max_total_time="$seconds" -dict="$fuzz_dir/loader.dict" -timeout=10 \
  -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 "$work"
status=$?
set -e
if (( status != 0 )); then
  echo "fuzz/run_fuzz.sh: the fuzzer found a crash (exit $status); see crash-* in $build_dir" >&2
  exit 1
fi
echo "fuzz/run_fuzz.sh: no crash in ${seconds}s"
