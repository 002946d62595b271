#!/usr/bin/env bash
# Keeps the measured test times that a fresh build directory starts from
# (tests/ctest_costs.txt, CTest's CTestCostData.txt format): `ctest -j` then
# starts the longest tests first on a new machine too. Run after a full,
# passing `scripts/test.sh` on an otherwise idle machine.
#   scripts/update_test_costs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
costs=build/Testing/Temporary/CTestCostData.txt
[ -f "$costs" ] || { echo "update_test_costs: no $costs (run scripts/test.sh first)" >&2; exit 2; }
# Only the per-test lines (name, runs, seconds); the failed list after '---' is dropped.
sed '/^---$/q' "$costs" | sed '/^---$/d' > tests/ctest_costs.txt
echo "---" >> tests/ctest_costs.txt
echo "update_test_costs: $(($(wc -l < tests/ctest_costs.txt) - 1)) test times in tests/ctest_costs.txt"
