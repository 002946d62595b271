#!/usr/bin/env bash
# Optional: ccma against Simbody on the same warm paths (benchmarks/simbody/,
# issue 11). Installs Debian's libsimbody-dev if it is missing (it is not in
# scripts/setup.sh, to keep the README's set-up fast), configures build/ so
# that CMake finds Simbody, builds only the simbody_benchmark target, runs it
# and writes benchmarks/results/simbody.md (the table of benchmarks/RESULTS.md,
# "Against Simbody") and benchmarks/results/simbody.json.
#   scripts/simbody_bench.sh                       # 10 laps of each 200-step circle
#   CCMA_SIMBODY_LAPS=20 scripts/simbody_bench.sh  # more laps
#   CCMA_BUILD_DIR=build-other scripts/simbody_bench.sh   # another build directory
# Exit status 1 when a solver failed a step or the end-effectors disagreed by
# more than 1e-9 m (the results are still written, for inspection).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! dpkg-query -W -f='${Status}' libsimbody-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "simbody_bench: installing libsimbody-dev (apt-get)"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  # env: sudo does not pass the caller's environment on.
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libsimbody-dev > /dev/null
fi

BUILD="${CCMA_BUILD_DIR:-build}"
LAPS="${CCMA_SIMBODY_LAPS:-10}"
mkdir -p "$BUILD"
log="$BUILD/simbody_bench.log"
echo "simbody_bench: configuring $BUILD/ (Release) and building simbody_benchmark (log: $log)"
# Configuring again is what lets CMake find Simbody in a build/ set up before
# it was installed (a not-found package is searched for again on every run).
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > "$log" 2>&1 || { cat "$log"; exit 1; }
if ! grep -q "building simbody_benchmark" "$log"; then
  grep -i simbody "$log" || true
  echo "simbody_bench: CMake did not find Simbody (see $log)" >&2
  exit 1
fi
cmake --build "$BUILD" --target simbody_benchmark -j"$(nproc)" >> "$log" 2>&1 || { tail -50 "$log"; exit 1; }

out=benchmarks/results
mkdir -p "$out"
echo "simbody_bench: running ($LAPS laps per path; under a minute)"
status=0
table=$("$BUILD/benchmarks/simbody_benchmark" --laps="$LAPS" --json="$out/simbody.json") || status=$?
{
  echo "# ccma against Simbody"
  echo
  echo "Produced by \`scripts/simbody_bench.sh\` (\`$BUILD/benchmarks/simbody_benchmark --laps=$LAPS"
  echo "--json=$out/simbody.json\`); raw numbers in \`simbody.json\`. Explained in"
  echo "\`benchmarks/RESULTS.md\`, section \"Against Simbody\"."
  echo
  printf '%s\n' "$table"
} > "$out/simbody.md"
cat "$out/simbody.md"
echo "simbody_bench: wrote $out/simbody.md and $out/simbody.json"
exit "$status"
