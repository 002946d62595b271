#!/usr/bin/env bash
# The viewer's screenshots in docs/viewer.md: `ccma view` of every bundled model, of a
# replay, of a workspace map (a few seconds of `ccma workspace`), of a model with meshes, of
# one coloured by load and of a loaded shape, opened in headless
# Chromium by the browser test, which also checks
# each page (no console error, no request, the mechanism drawn) before saving
# docs/images/view_<name>.png; and the workspace slice map of docs/workspace.md (gnuplot).
# Needs the full build of scripts/setup.sh (not --tool: the browser tests' Node.js and
# playwright-core in viewer/js/node_modules/), chromium and gnuplot.
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
"$build"/apps/ccma workspace --model=models/4dof_reduced.yaml --x=-0.5:0.5 --y=-0.5:0.5 --z=0.4:1.0 \
  --resolution=13 --threads=2 --out="$out/workspace.csv" > /dev/null
"$build"/apps/ccma view --model=models/4dof_reduced.yaml --workspace="$out/workspace.csv" \
  --out="$out/workspace.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/workspace.html" \
  --screenshot docs/images/view_workspace_4dof_reduced.png > /dev/null
echo "screenshots: docs/images/view_workspace_4dof_reduced.png"
# A model with STL meshes (docs/viewer.md, "Meshes").
"$build"/apps/ccma view --model=tests/meshes/four_bar_meshes.yaml --meshes --out="$out/meshes.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/meshes.html" --screenshot docs/images/viewer_meshes.png > /dev/null
echo "screenshots: docs/images/viewer_meshes.png"
# Links coloured by load (docs/viewer.md, "Colouring by load"): a Stewart platform with an off-centre payload.
"$build"/apps/ccma view --model=examples/statics/stewart_gough_loaded.yaml --color_by=load \
  --out="$out/loads.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/loads.html" --screenshot docs/images/view_loads_stewart_gough.png > /dev/null
echo "screenshots: docs/images/view_loads_stewart_gough.png"
# A loaded shape (docs/statics.md and docs/viewer.md, "Deflection"): the compliant Stewart platform, 100 times.
"$build"/apps/ccma view --model=examples/statics/stewart_gough_compliant.yaml --deflection=100 \
  --out="$out/deflection.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/deflection.html" \
  --screenshot docs/images/view_deflection_stewart_gough.png > /dev/null
echo "screenshots: docs/images/view_deflection_stewart_gough.png"
# An imported robot (docs/import.md): the five-bar of example-parallel-robots.
robots=models/robots/example-parallel-robots
"$build"/apps/ccma import --from=$robots/5bar_linkage/robot.urdf --closures=$robots/5bar_linkage/robot.yaml \
  --end_effector=effector --out="$out/5bar.yaml" > /dev/null
"$build"/apps/ccma view --model="$out/5bar.yaml" --out="$out/5bar.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/5bar.html" --screenshot docs/images/import_5bar.png > /dev/null
echo "screenshots: docs/images/import_5bar.png"
# The workspace slice map of docs/workspace.md (gnuplot, `ccma workspace --plot`).
"$build"/apps/ccma workspace --model=models/4dof_reduced.yaml --x=-0.5:0.5 --z=0.4:1.0 --resolution=25 \
  --out="$out/slice.csv" --plot="$out/slice" > /dev/null
cp "$out/slice/sigma_min.png" docs/images/workspace_sigma_min_4dof_reduced.png
echo "screenshots: docs/images/workspace_sigma_min_4dof_reduced.png"
# A detour round a pillar (docs/obstacles.md): ccma plan where the greedy walk stops.
"$build"/apps/ccma plan --model=examples/obstacles/pillar_detour.yaml --waypoints=examples/obstacles/one_metre_x.csv \
  --out="$out/detour.csv" > /dev/null
"$build"/apps/ccma view --model=examples/obstacles/pillar_detour.yaml --trajectory="$out/detour.csv" \
  --out="$out/detour.html" > /dev/null
node viewer/js/test/browser_test.mjs --html "$out/detour.html" --expect-animation \
  --screenshot docs/images/obstacles_detour.png --screenshot-frame 75 > /dev/null
echo "screenshots: docs/images/obstacles_detour.png"
