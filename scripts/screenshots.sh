#!/usr/bin/env bash
# The README's viewer screenshots: `ccma view` of every bundled model and of a
# replay, opened in headless Chromium by the browser test, which also checks
# each page (no console error, no request, the mechanism drawn) before saving
# docs/images/view_<name>.png. Needs a build (scripts/setup.sh) and chromium.
#   scripts/screenshots.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CCMA_BUILD_DIR:-build}
out=$build/screenshots
mkdir -p "$out" docs/images
for model in models/*.yaml; do
  name=$(basename "$model" .yaml)
  "$build"/apps/ccma view --model="$model" --out="$out/$name.html" > /dev/null
  node viewer/js/test/browser_test.mjs --html "$out/$name.html" --screenshot "docs/images/view_$name.png" > /dev/null
  echo "screenshots: docs/images/view_$name.png"
done
"$build"/apps/ccma replay --model=models/4dof_reduced.yaml --waypoints=models/paths/4dof_combined.csv \
  --out="$out/replay" > /dev/null 2>&1
"$build"/apps/ccma view --model=models/4dof_reduced.yaml --replay="$out/replay" --out="$out/replay.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/replay.html" --expect-animation \
  --screenshot docs/images/view_replay_4dof_reduced.png --screenshot-frame 200 > /dev/null
echo "screenshots: docs/images/view_replay_4dof_reduced.png"
