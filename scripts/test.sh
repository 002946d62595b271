#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite through CTest: C++ (GoogleTest),
# Python (pytest), the viewer in headless Chromium, the examples, the docs,
# the layout rules and the fuzz corpus replayed through the model loader.
# About 4 to 8 minutes of building on 2 cores after scripts/demo.sh (6 to 13 from nothing), then about 3 to 5 minutes of tests.
# Live fuzzing (clang, libFuzzer) is its own script: scripts/fuzz.sh.
#   scripts/test.sh                 # everything
#   scripts/test.sh -R loader       # extra arguments go to ctest
set -euo pipefail
cd "$(dirname "$0")/.."
# chromium: the viewer's real-browser test.
CCMA_LATE_PACKAGES="chromium ${CCMA_LATE_PACKAGES:-}" scripts/setup.sh
echo "test: running the suite (ctest -j$(nproc); about 3 to 5 minutes on 2 cores; a line per test)"
(cd build && ctest --output-on-failure -j"$(nproc)" "$@")
