#!/usr/bin/env bash
# Fuzzes the model loader live with libFuzzer (clang, AddressSanitizer and
# UndefinedBehaviorSanitizer) for a while: a separate clang build of the
# loader's layers (core and formats) into build-fuzz/ (about 2 minutes on 2
# cores the first time), then the fuzzer, with a progress line at least every
# 20 s. The corpus itself is
# replayed by the ordinary tests (scripts/test.sh, test fuzz_corpus_replay).
# Installs clang from Debian's packages when it is missing.
#   scripts/fuzz.sh [seconds]        default 60
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang++ > /dev/null || ! dpkg-query -W libclang-rt-14-dev > /dev/null 2>&1; then
  echo "fuzz: installing clang and libclang-rt-14-dev (apt-get, about a minute)"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev > apt.log 2>&1 \
    || { tail -20 apt.log; exit 1; }
fi
exec fuzz/run_fuzz.sh "${1:-60}"
