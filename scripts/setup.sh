#!/usr/bin/env bash
# Installs what ccma needs from Debian's packages (only the missing ones) and
# builds it into build/ (Release), printing progress at least every 20 s.
# Safe to run again: it does nothing twice.
#   scripts/setup.sh                      # set up and build everything (tests too)
#   scripts/setup.sh --tool               # only what the `ccma` tool needs (the demo's choice):
#                                         #   fewer packages, no tests, Python or benchmarks
#   scripts/setup.sh --register-python    # also make `import ccma` work without PYTHONPATH
#   CCMA_EXTRA_PACKAGES="..." scripts/setup.sh        # more packages, before the build
#   CCMA_LATE_PACKAGES="chromium" scripts/setup.sh     # more packages, installed while it builds
# Without --register-python nothing is written outside this clone: use
# PYTHONPATH=build/python python3 ... (docs/python.md).
set -euo pipefail
cd "$(dirname "$0")/.."

register=0
tool_only=0
npm_late=0
for arg in "$@"; do
  case "$arg" in
    --register-python) register=1 ;;
    --tool) tool_only=1 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "setup: unknown argument '$arg' (see scripts/setup.sh --help)" >&2; exit 2 ;;
  esac
done

# What the library and the `ccma` tool need to build and run.
PACKAGES=(clang  # the compiler of a new build/ (below: a fifth less compile time than g++)
          make cmake pkg-config
          ninja-build  # the generator of a new build/: it compiles a target's files while the libraries it links still build
          libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
          libyaml-cpp-dev nlohmann-json3-dev
          liburdfdom-dev libsdformat-dev  # ccma import: URDF and SDFormat robot files
          libmujoco-dev  # MuJoCo 2.2.2: ccma import of MJCF files; judges what ccma export writes
          ca-certificates)  # HTTPS: the build fetches three.js and esbuild for the viewer from the npm registry
# What only running the tool or the tests needs: installed in the background
# while the build runs (the build needs none of them), waited for before
# setup ends. gnuplot draws the plots of `ccma bench --out` and `ccma replay`
# (optional at run time).
LATE_PACKAGES=(gnuplot-nox)
# What the tests, benchmarks, examples and the Python module add.
if ((!tool_only)); then
  PACKAGES+=(libgtest-dev libbenchmark-dev
             pybind11-dev python3-dev python3-numpy  # the Python module
             python3-matplotlib  # the Python trajectory example's plot (its test expects the plot when present)
             libfcl-dev  # tests: FCL's distances, the independent check of ccma's clearances
             gnuplot-nox)  # before the configure: the C++ trajectory example's test expects its plot when gnuplot is found
  # The viewer's browser tests: Node.js and npm (playwright-core from the npm
  # registry). Only the tests need them, and npm brings about 370 packages:
  # installed while the build runs, then the build is configured again so
  # that it adds the browser tests (npm_late below).
  command -v npm > /dev/null || { LATE_PACKAGES+=(npm); npm_late=1; }
  LATE_PACKAGES+=(python3-pytest  # the Python tests
                  python3-distributed  # ccma.workspace on a Dask cluster (and its local-cluster test)
                  python3-zarr python3-tqdm)  # sweeps: finished chunks kept for resuming; the progress bar
fi
# shellcheck disable=SC2206
PACKAGES+=(${CCMA_EXTRA_PACKAGES:-})
# shellcheck disable=SC2206
LATE_PACKAGES+=(${CCMA_LATE_PACKAGES:-})

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
apt_updated=0
# missing_of NAME...: the packages among NAME... that are not installed.
missing_of() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
# install LOG WHAT NAME...: apt-get install, a line at least every 20 s.
install() {
  local log=$1 what=$2 pid
  shift 2
  ((apt_updated)) || $SUDO apt-get update -qq
  apt_updated=1
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "$@" > "$log" 2>&1 &
  pid=$!
  while kill -0 "$pid" 2> /dev/null; do
    sleep 20
    kill -0 "$pid" 2> /dev/null && echo "setup: still installing $what ($(grep -c '^Setting up' "$log" || true) set up)"
  done
  wait "$pid" || { tail -30 "$log"; return 1; }
}
mapfile -t missing < <(missing_of "${PACKAGES[@]}")
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages (apt-get, about 1 minute): ${missing[*]}"
  install apt.log "the build's packages" "${missing[@]}" || exit 1
fi
mapfile -t late < <(missing_of "${LATE_PACKAGES[@]}")
late_pid=""
if ((${#late[@]})); then
  ((apt_updated)) || $SUDO apt-get update -qq
  echo "setup: installing ${#late[@]} run-time packages while the build runs (apt-late.log): ${late[*]}"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${late[@]}" \
    > apt-late.log 2>&1 &
  late_pid=$!
fi

BUILD_TYPE="${CCMA_BUILD_TYPE:-Release}"
launcher=()
# ccache, when installed, makes a second clone's or a rebuilt branch's build fast.
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# A new build/ uses Ninja; an existing one keeps the generator it was made with.
generator=()
[ -f build/CMakeCache.txt ] || ! command -v ninja > /dev/null || generator=(-G Ninja)
# A new build/ compiles with clang++ unless CXX names another compiler: the
# tool's build takes a fifth less compiler time than with g++ and the
# solvers run as fast (benchmarks/RESULTS.md, "clang instead of g++"). An
# existing build/ keeps its compiler; any C++17 compiler builds ccma.
compiler=()
if [ ! -f build/CMakeCache.txt ] && [ -z "${CXX:-}" ] && command -v clang++ > /dev/null; then
  compiler=(-DCMAKE_CXX_COMPILER=clang++)
fi
# --tool configures without the parts that need the test packages, unless
# build/ already has them (a later --tool run never takes tests away).
parts=(-DCCMA_BUILD_TESTS=ON -DCCMA_BUILD_BENCHMARKS=ON -DCCMA_BUILD_EXAMPLES=ON -DCCMA_BUILD_PYTHON=ON)
target_args=()
what="everything (library, tool, tests, benchmarks, examples, Python module)"
estimate="about 4 to 8 minutes on 2 cores after the demo, 6 to 13 from nothing"
if ((tool_only)); then
  target_args=(--target ccma_tool)
  what="the ccma tool"
  estimate="about 3 to 5 minutes on 2 cores the first time"
  if grep -qs '^CCMA_BUILD_TESTS:BOOL=ON' build/CMakeCache.txt; then
    parts=()
  else
    parts=(-DCCMA_BUILD_TESTS=OFF -DCCMA_BUILD_BENCHMARKS=OFF -DCCMA_BUILD_EXAMPLES=OFF -DCCMA_BUILD_PYTHON=OFF)
  fi
fi
echo "setup: configuring build/ (CMake, a few seconds)"
cmake -S . -B build "${generator[@]}" "${compiler[@]}" -DCMAKE_BUILD_TYPE="$BUILD_TYPE" "${launcher[@]}" "${parts[@]}" > build.log 2>&1 \
  || { cat build.log; exit 1; }
echo "setup: building $what into build/ ($BUILD_TYPE), $estimate; log in build.log"

# build_with_progress ARGS...: `cmake --build build ARGS` in the background; a
# line for every 10 % and, between them, a line at least every 20 s naming
# what is being compiled. Exits the script when the build fails.
build_with_progress() {
  local build_pid start=$SECONDS last_print=$SECONDS next=0 line p what_now
  cmake --build build -j"$(nproc)" "$@" >> build.log 2>&1 &
  build_pid=$!
  while kill -0 "$build_pid" 2> /dev/null; do
    sleep 2
    # make prints "[ 42%] ...", ninja (a build/ configured with -G Ninja) "[42/180] ...".
    line=$(grep -E '^\[ *[0-9]+(%|/[0-9]+)\]' build.log | tail -n 1 || true)
    p=$(sed -nE 's/^\[ *([0-9]+)%\].*/\1/p' <<< "$line")
    if [[ -z "$p" && "$line" =~ ^\[([0-9]+)/([0-9]+)\] ]]; then
      p=$(( 100 * BASH_REMATCH[1] / BASH_REMATCH[2] ))
    fi
    if [[ -n "$p" ]] && (( p >= next )); then
      printf 'setup: building %3d%% (%d s)\n' "$p" $((SECONDS - start))
      next=$(( p - p % 10 + 10 ))
      last_print=$SECONDS
    elif (( SECONDS - last_print >= 20 )); then
      what_now=${line#*] }
      echo "setup: building ${p:-0}% ($((SECONDS - start)) s): ${what_now#Building CXX object }"
      last_print=$SECONDS
    fi
  done
  if ! wait "$build_pid"; then
    # A half-finished apt-get must not be cut off (dpkg would be left locked mid-install).
    [ -z "$late_pid" ] || wait "$late_pid" || true
    grep -E 'error|Error' build.log | head -20
    tail -30 build.log
    exit 1
  fi
}
start=$SECONDS
build_with_progress "${target_args[@]}"
echo "setup: built $what in $((SECONDS - start)) s (build/apps/ccma; log in build.log)"
if [ -n "$late_pid" ]; then
  while kill -0 "$late_pid" 2> /dev/null; do
    echo "setup: waiting for the run-time packages ($(grep -c '^Setting up' apt-late.log || true) set up; apt-late.log)"
    sleep 10
  done
  wait "$late_pid" || { tail -30 apt-late.log; exit 1; }
  echo "setup: installed the run-time packages"
  if ((npm_late)); then
    echo "setup: npm is here now: configuring build/ again for the browser tests and building what they add (npm ci of playwright-core, about 20 s)"
    cmake -S . -B build >> build.log 2>&1 || { tail -30 build.log; exit 1; }
    build_with_progress
  fi
fi

# `import ccma` without PYTHONPATH, on request only: a ccma-build.pth file in
# the site-packages of the python3 the module was built for adds build/python
# to its path (one clone at a time; remove the file to undo).
register_python() {
  local module built py version site
  module=$(ls build/python/ccma/_ccma.cpython-*.so 2>/dev/null | head -1)
  if [ -z "$module" ]; then
    echo "setup: the Python module was not built (see build.log)"
    return
  fi
  built=$(basename "$module" | sed -E 's/^_ccma\.cpython-([0-9])([0-9]+)-.*/\1.\2/')
  py=$(readlink -f /usr/bin/python3)
  version=$("$py" -c 'import sys; print("%d.%d" % sys.version_info[:2])')
  if [ "$version" != "$built" ]; then
    echo "setup: $py is Python $version, the module is for $built: use PYTHONPATH=build/python with Python $built"
    return
  fi
  site=$("$py" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
  if [ -e "$site/ccma-build.pth" ] && [ "$(cat "$site/ccma-build.pth")" != "$PWD/build/python" ]; then
    echo "setup: $site/ccma-build.pth pointed at $(cat "$site/ccma-build.pth"); now at this clone"
  fi
  if mkdir -p "$site" 2> /dev/null && printf '%s\n' "$PWD/build/python" > "$site/ccma-build.pth" 2> /dev/null; then
    echo "setup: import ccma works in $py ($site/ccma-build.pth; remove it to undo)"
  else
    echo "setup: cannot write $site: use PYTHONPATH=$PWD/build/python"
  fi
}
if ((register)); then
  register_python
elif [ -d build/python/ccma ]; then
  echo "setup: Python: PYTHONPATH=$PWD/build/python python3 -c 'import ccma'  (or scripts/setup.sh --register-python)"
fi
