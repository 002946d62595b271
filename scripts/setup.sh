#!/usr/bin/env bash
# Installs what ccma needs from Debian's packages (only the missing ones) and
# builds it into build/ (Release). Safe to run again: it does nothing twice.
#   scripts/setup.sh            # set up and build
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ make cmake pkg-config
          libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
          libyaml-cpp-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev
          gnuplot-nox)  # gnuplot: plots of `ccma bench --out` (optional at run time)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

BUILD_TYPE="${CCMA_BUILD_TYPE:-Release}"
cmake -S . -B build -DCMAKE_BUILD_TYPE="$BUILD_TYPE" > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$(nproc)" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
echo "setup: built build/apps/ccma ($BUILD_TYPE)"
