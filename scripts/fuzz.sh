#!/usr/bin/env bash
# Fuzzes ccma's readers live with libFuzzer (clang, AddressSanitizer and
# UndefinedBehaviorSanitizer), one target at a time, each for a bounded time.
#
#   scripts/fuzz.sh [seconds_per_target] [target...]
#       seconds_per_target   1 to 3600, default 120
#       target               names from fuzz/targets.cmake (default: every
#                            target whose entry point file exists)
#   scripts/fuzz.sh --list   the targets, one per line
#
# The targets are listed once, in fuzz/targets.cmake (one
# `ccma_fuzz_target(NAME ... SOURCE ... CORPUS ... [DICT ...] [MAX_LEN ...])`
# call a line). Builds the chosen `<name>_fuzzer` binaries in a clang build of
# their own (build-fuzz/, or $CCMA_FUZZ_BUILD_DIR; only the layers they need,
# instrumented), then runs each over a scratch copy of its corpus
# (build-fuzz/corpus_<name>/: inputs the fuzzer finds stay there, the
# checked-in seeds stay small; `<name>_fuzzer -merge=1 fuzz/corpus_<name>
# build-fuzz/corpus_<name>` adds the interesting ones back) with its
# dictionary, printing a progress line at least every 20 s. The full output of
# a run is build-fuzz/fuzz_<name>.log. On a finding it stops, leaving the input
# in build-fuzz/artifacts/<name>/ (crash-*, leak-*, timeout-*, oom-*), and
# exits 1; a build failure exits 2. Ends with a table: target, seconds,
# executions, corpus size, result. The checked-in corpora are also replayed by
# the ordinary tests (CTest fuzz_corpus_replay_<name>, no clang needed).
# Installs clang and libclang-rt-14-dev from Debian's packages when missing.
# $CCMA_FUZZ_JOBS: build jobs (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
source_dir="$PWD"
fuzz_dir="$source_dir/fuzz"
targets_file="$fuzz_dir/targets.cmake"
max_seconds=3600
progress_every=20

# The value of KEY in one ccma_fuzz_target(...) line ("" when absent).
field() { sed -n "s/.*[( ]$2 \([^ )]*\).*/\1/p" <<< "$1"; }
target_lines() { grep '^ccma_fuzz_target(' "$targets_file"; }

if [[ "${1:-}" == "--list" ]]; then
  while read -r line; do field "$line" NAME; done < <(target_lines)
  exit 0
fi
seconds="${1:-120}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || (( seconds < 1 || seconds > max_seconds )); then
  echo "usage: scripts/fuzz.sh [seconds_per_target] [target...]  (seconds: 1 to $max_seconds, default 120)" >&2
  exit 2
fi
shift || true

# The chosen targets: those named, or every one whose entry point exists.
declare -A line_of=()
all=()
while read -r line; do
  name="$(field "$line" NAME)"
  line_of[$name]="$line"
  all+=("$name")
done < <(target_lines)
chosen=()
if (( $# > 0 )); then
  for name in "$@"; do
    [[ -n "${line_of[$name]:-}" ]] || { echo "scripts/fuzz.sh: no target '$name' in fuzz/targets.cmake (${all[*]})" >&2; exit 2; }
    chosen+=("$name")
  done
else
  for name in "${all[@]}"; do
    if [[ -f "$fuzz_dir/$(field "${line_of[$name]}" SOURCE)" ]]; then
      chosen+=("$name")
    else
      echo "scripts/fuzz.sh: $name: skipped, fuzz/$(field "${line_of[$name]}" SOURCE) does not exist"
    fi
  done
fi
(( ${#chosen[@]} > 0 )) || { echo "scripts/fuzz.sh: no target to run" >&2; exit 2; }

if ! command -v clang++ > /dev/null || ! dpkg-query -W libclang-rt-14-dev > /dev/null 2>&1; then
  echo "scripts/fuzz.sh: installing clang and libclang-rt-14-dev (apt-get, about a minute)"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev > apt.log 2>&1 \
    || { tail -20 apt.log; exit 2; }
fi

build_dir="${CCMA_FUZZ_BUILD_DIR:-$source_dir/build-fuzz}"
jobs="${CCMA_FUZZ_JOBS:-2}"

# Runs "$@" in the background; while it runs, prints "$label: N s" every
# $progress_every s, with the last match of $tick_pattern in $tick_log (ninja's
# "[done/all]", libFuzzer's "#runs ... exec/s" line) when set.
tick_log=""
tick_pattern=""
with_progress() {
  local label="$1"
  shift
  "$@" &
  local pid=$! start=$SECONDS next=$((SECONDS + progress_every))
  while kill -0 "$pid" 2>/dev/null; do
    sleep 1
    if (( SECONDS >= next )) && kill -0 "$pid" 2>/dev/null; then
      local last=""
      [[ -n "$tick_log" && -f "$tick_log" ]] && last="$(grep -aoE "$tick_pattern" "$tick_log" | tail -n 1 || true)"
      echo "scripts/fuzz.sh: $label: $((SECONDS - start)) s${last:+: $last}"
      next=$((SECONDS + progress_every))
    fi
  done
  wait "$pid"
}

# ------------------------------------------------------------ build ---
generator=()
command -v ninja > /dev/null 2>&1 && [[ ! -f "$build_dir/Makefile" ]] && generator=(-G Ninja)
launcher=()
command -v ccache > /dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
mkdir -p "$build_dir"
CC=clang CXX=clang++ cmake -S "$source_dir" -B "$build_dir" ${generator[@]+"${generator[@]}"} \
  ${launcher[@]+"${launcher[@]}"} -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCCMA_FUZZ=ON \
  -DCCMA_BUILD_TESTS=OFF -DCCMA_BUILD_BENCHMARKS=OFF -DCCMA_BUILD_EXAMPLES=OFF -DCCMA_BUILD_PYTHON=OFF \
  > "$build_dir/configure.log" 2>&1 || { cat "$build_dir/configure.log" >&2; exit 2; }
binaries=()
for name in "${chosen[@]}"; do binaries+=("${name}_fuzzer"); done
echo "scripts/fuzz.sh: building ${binaries[*]} with clang + sanitizers in $build_dir" \
  "(the first time about 10 s of compiling per library file on one core; later runs reuse the build)"
tick_log="$build_dir/build.log"
tick_pattern='^\[[0-9]+/[0-9]+\]'
build() { cmake --build "$build_dir" -j"$jobs" --target "${binaries[@]}" > "$build_dir/build.log" 2>&1; }
if ! with_progress "building" build; then
  tail -n 40 "$build_dir/build.log" >&2
  echo "scripts/fuzz.sh: the build failed (full log: $build_dir/build.log)" >&2
  exit 2
fi

# ------------------------------------------------------------- runs ---
# One run of $fuzzer (from the build directory: libFuzzer writes there).
run_fuzzer() { cd "$build_dir" && "$fuzzer" "${args[@]}" "$work" > "$log" 2>&1; }
summary=()
status=0
for name in "${chosen[@]}"; do
  line="${line_of[$name]}"
  fuzzer="$(find "$build_dir" -type f -name "${name}_fuzzer" -perm -u+x | head -n 1)"
  [[ -n "$fuzzer" ]] || { echo "scripts/fuzz.sh: ${name}_fuzzer was not built" >&2; exit 2; }
  corpus="$fuzz_dir/$(field "$line" CORPUS)"
  dict="$(field "$line" DICT)"
  max_len="$(field "$line" MAX_LEN)"
  work="$build_dir/corpus_$name"
  artifacts="$build_dir/artifacts/$name/"
  log="$build_dir/fuzz_$name.log"
  mkdir -p "$work" "$artifacts"
  cp -n "$corpus"/* "$work"/ 2> /dev/null || true
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${max_len:-8192}"
        -print_final_stats=1 -artifact_prefix="$artifacts")
  [[ -n "$dict" ]] && args+=(-dict="$fuzz_dir/$dict")
  echo "scripts/fuzz.sh: $name: ${seconds} s over $work (full output: $log)"
  tick_log="$log"
  tick_pattern='^#[0-9]+.*'
  set +e
  with_progress "$name" run_fuzzer
  code=$?
  set -e
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)"
  size="$(find "$work" -type f | wc -l)"
  if (( code == 0 )); then
    result="no finding"
  else
    finding="$(grep -ao 'Test unit written to [^ ]*' "$log" | tail -n 1 | cut -d' ' -f5- || true)"
    result="FINDING (exit $code)${finding:+: $finding}"
    tail -n 40 "$log" >&2
    status=1
  fi
  summary+=("$(printf '%-16s %8s %12s %8s  %s' "$name" "$seconds" "${execs:-?}" "$size" "$result")")
  (( status == 0 )) || break
done

echo
printf '%-16s %8s %12s %8s  %s\n' target seconds executions corpus result
printf '%s\n' "${summary[@]}"
exit "$status"
