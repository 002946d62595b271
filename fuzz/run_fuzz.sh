#!/usr/bin/env bash
# Fuzzes the model loader with libFuzzer for a while (issue "hostile input").
#
#   fuzz/run_fuzz.sh [seconds]        default 30
#
# Live fuzzing only: the checked-in corpus is replayed by every ordinary test
# run (CTest `fuzz_corpus_replay`, fuzz/corpus_replay.cc, no clang needed).
#
# Configures a separate build directory (build-fuzz, or $CCMA_FUZZ_BUILD_DIR)
# with clang, -DCCMA_FUZZ=ON and AddressSanitizer + UndefinedBehaviorSanitizer,
# builds only loader_fuzzer (printing an estimate of the time that takes
# first), and runs it over a scratch copy of fuzz/corpus with fuzz/loader.dict,
# printing a progress line (libFuzzer's latest stats) at least every 15 s; the
# fuzzer's full output is in build-fuzz/fuzz.log. Exits non-zero when the
# fuzzer finds a crash (the input is left as crash-* in the build directory);
# prints one "skipped" line and exits 0 when clang is not installed.
# $CCMA_SOURCE_DIR overrides the source tree, $CCMA_FUZZ_JOBS the build jobs.
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
jobs="${CCMA_FUZZ_JOBS:-2}"
# Seconds one library file takes to compile with clang and the sanitizers on
# one core (measured: the loader's layers, core and formats, 23 files, took
# 80 s on 2 cores).
seconds_per_file=10

if ! grep -q "CCMA_FUZZ" "$source_dir/CMakeLists.txt"; then
  echo "fuzz/run_fuzz.sh: $source_dir/CMakeLists.txt has no CCMA_FUZZ option (see fuzz/CMakeLists.txt)" >&2
  exit 2
fi

# Runs "$@" in the background and, while it runs, prints "$label: N s" every
# 15 s (with the last line of $tick_log, when set, instead of nothing).
tick_log=""
with_progress() {
  local label="$1"
  shift
  "$@" &
  local pid=$! start=$SECONDS next=$((SECONDS + 15))
  while kill -0 "$pid" 2>/dev/null; do
    sleep 1
    if (( SECONDS >= next )) && kill -0 "$pid" 2>/dev/null; then
      local last=""
      [[ -n "$tick_log" && -f "$tick_log" ]] && last="$(grep -a '^#' "$tick_log" | tail -n 1 || true)"
      echo "fuzz/run_fuzz.sh: $label: $((SECONDS - start)) s${last:+: $last}"
      next=$((SECONDS + 15))
    fi
  done
  wait "$pid"
}

generator=()
command -v ninja >/dev/null 2>&1 && [[ ! -f "$build_dir/Makefile" ]] && generator=(-G Ninja)
mkdir -p "$build_dir"
CC=clang CXX=clang++ cmake -S "$source_dir" -B "$build_dir" ${generator[@]+"${generator[@]}"} -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCCMA_FUZZ=ON -DCCMA_BUILD_TESTS=OFF -DCCMA_BUILD_BENCHMARKS=OFF >"$build_dir.configure.log" 2>&1 \
  || { cat "$build_dir.configure.log" >&2; exit 2; }

# The estimate: object files not built yet, times the cost of one. (Not a dry
# run: `ninja -n` stops at the regeneration step that CONFIGURE_DEPENDS globs add.)
if [[ -f "$build_dir/build.ninja" ]]; then
  files=0
  while read -r object; do
    [[ -f "$build_dir/$object" ]] || files=$((files + 1))
  done < <(ninja -C "$build_dir" -t commands loader_fuzzer 2>/dev/null | grep -o -- ' -o [^ ]*\.o' | cut -c5- || true)
  if (( files > 0 )); then
    minutes=$(( (files * seconds_per_file + jobs * 60 - 1) / (jobs * 60) ))
    echo "fuzz/run_fuzz.sh: building loader_fuzzer with clang + sanitizers in $build_dir:" \
      "$files files to compile, about $minutes min on $jobs jobs (later runs reuse the build)"
  else
    echo "fuzz/run_fuzz.sh: loader_fuzzer: every object file exists in $build_dir; recompiling only what changed"
  fi
else
  echo "fuzz/run_fuzz.sh: building loader_fuzzer with clang + sanitizers in $build_dir:" \
    "about $(( (60 * seconds_per_file + jobs * 60 - 1) / (jobs * 60) )) min on $jobs jobs the first time"
fi
with_progress "building" cmake --build "$build_dir" -j"$jobs" --target loader_fuzzer

fuzzer="$(find "$build_dir" -type f -name loader_fuzzer -perm -u+x | head -n 1)"
[[ -n "$fuzzer" ]] || { echo "fuzz/run_fuzz.sh: loader_fuzzer was not built" >&2; exit 2; }

# Work on a copy: new inputs go there, the checked-in seed corpus stays small.
work="$build_dir/corpus"
mkdir -p "$work"
cp -n "$fuzz_dir"/corpus/* "$work"/ 2>/dev/null || true

cd "$build_dir"
log="$build_dir/fuzz.log"
echo "fuzz/run_fuzz.sh: running $fuzzer for ${seconds}s over $work (full output: $log)"
run_fuzzer() {
  "$fuzzer" -max_total_time="$seconds" -dict="$fuzz_dir/loader.dict" -timeout=10 \
    -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 "$work" >"$log" 2>&1
}
tick_log="$log"
set +e
with_progress "fuzzing" run_fuzzer
status=$?
set -e
if (( status != 0 )); then
  tail -n 60 "$log" >&2
  echo "fuzz/run_fuzz.sh: the fuzzer found a crash (exit $status); see crash-* in $build_dir and $log" >&2
  exit 1
fi
grep -a '^stat::\|^Done' "$log" || true
echo "fuzz/run_fuzz.sh: no crash in ${seconds}s"
