#!/usr/bin/env bash
# Installs what ccma needs from Debian's packages (only the missing ones) and
# builds it into build/ (Release), showing progress. Safe to run again: it
# does nothing twice.
#   scripts/setup.sh                 # set up and build
#   CCMA_EXTRA_PACKAGES="clang libclang-rt-14-dev" scripts/setup.sh   # more packages
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ make cmake pkg-config
          libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
          libyaml-cpp-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev
          gnuplot-nox)  # gnuplot: plots of `ccma bench --out` and `ccma replay` (optional at run time)
# shellcheck disable=SC2206
PACKAGES+=(${CCMA_EXTRA_PACKAGES:-})

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]} (apt-get)"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
fi

BUILD_TYPE="${CCMA_BUILD_TYPE:-Release}"
echo "setup: configuring build/ ($BUILD_TYPE); the first build takes about 3 minutes on 2 cores"
cmake -S . -B build -DCMAKE_BUILD_TYPE="$BUILD_TYPE" > build.log 2>&1 || { cat build.log; exit 1; }
# Progress: one line per 10% of the build (the whole log is in build.log).
# A shell loop, not awk: mawk reads its input in blocks and would print late.
progress() {
  local next=0 line p
  while IFS= read -r line; do
    printf '%s\n' "$line" >> build.log
    if [[ "$line" =~ ^\[\ *([0-9]+)%\] ]]; then
      p=${BASH_REMATCH[1]}
      if (( p >= next )); then
        printf 'setup: building %3d%%\n' "$p"
        next=$(( p - p % 10 + 10 ))
      fi
    fi
  done
}
if ! cmake --build build -j"$(nproc)" 2>&1 | progress; then
  tail -50 build.log
  exit 1
fi
echo "setup: built build/apps/ccma ($BUILD_TYPE; log in build.log)"
