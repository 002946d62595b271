#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite through CTest, then fuzzes the
# model loader for a short time (clang's libFuzzer; installed with the rest).
#   scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
# clang: the fuzzer; chromium: the viewer's real-browser test.
CCMA_EXTRA_PACKAGES="clang libclang-rt-14-dev chromium ${CCMA_EXTRA_PACKAGES:-}" scripts/setup.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
echo "test: fuzzing the model loader for ${CCMA_FUZZ_SECONDS:-20} s (fuzz/run_fuzz.sh; build log in build-fuzz.log)"
fuzz/run_fuzz.sh "${CCMA_FUZZ_SECONDS:-20}" > build-fuzz.log 2>&1 || { tail -40 build-fuzz.log; exit 1; }
tail -3 build-fuzz.log
