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
          gnuplot-nox   # gnuplot: plots of `ccma bench --out` and `ccma replay` (optional at run time)
          pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests
          python3-matplotlib  # the Python trajectory example's plot
          python3-distributed)  # ccma.workspace on a Dask cluster (and its local-cluster test)
# The viewer's JavaScript is bundled with npm (three.js from the npm registry).
command -v npm > /dev/null || PACKAGES+=(npm)
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

# `python3 -c "import ccma"`: a ccma-build.pth file in the site-packages of
# each python3 of the version the module was built for (Debian's, and the one
# first on PATH if different) adds build/python to its path. Remove that file
# to undo. ccma/__init__.py finds Debian's python3-numpy for other interpreters.
register_python() {
  local module built py version site seen=""
  module=$(ls build/python/ccma/_ccma.cpython-*.so 2>/dev/null | head -1)
  if [ -z "$module" ]; then
    echo "setup: the Python module was not built (see build.log)"
    return
  fi
  built=$(basename "$module" | sed -E 's/^_ccma\.cpython-([0-9])([0-9]+)-.*/\1.\2/')
  for py in /usr/bin/python3 "$(command -v python3 || true)"; do
    [ -x "$py" ] || continue
    py=$(readlink -f "$py")
    case " $seen " in *" $py "*) continue ;; esac
    seen="$seen $py"
    version=$("$py" -c 'import sys; print("%d.%d" % sys.version_info[:2])')
    if [ "$version" != "$built" ]; then
      echo "setup: $py is Python $version, the module is for $built: use PYTHONPATH=build/python with Python $built"
      continue
    fi
    site=$("$py" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
    if mkdir -p "$site" 2> /dev/null && printf '%s\n' "$PWD/build/python" > "$site/ccma-build.pth" 2> /dev/null; then
      echo "setup: import ccma works in $py ($site/ccma-build.pth)"
    else
      echo "setup: cannot write $site: use PYTHONPATH=$PWD/build/python"
    fi
  done
}
register_python
