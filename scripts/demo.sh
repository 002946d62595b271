#!/usr/bin/env bash
# Sets up, builds and runs ccma's main jobs on the bundled reference models:
# `ccma check` (counts and numerical mobility), `ccma simulate` (assembly),
# `ccma control` (bases that put the end-effector 3 cm and 0.05 rad away),
# `ccma trajectory` on the paper's two 4-DOF paths, and `ccma replay` of the first
# (simulated base driving; CSV and plots in build/demo/).
#   scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ccma=build/apps/ccma
mkdir -p build/demo
for model in models/*.yaml; do
  echo "== $ccma check --model=$model"
  $ccma check --model="$model"
  echo "== $ccma simulate --model=$model"
  $ccma simulate --model="$model"
  echo "== $ccma control --model=$model --target=0.03,-0.02,0.62,0,0,0.05"
  $ccma control --model="$model" --target=0.03,-0.02,0.62,0,0,0.05
done
for model in 4dof_reduced 4dof_complete; do
  for path in 4dof_sequential 4dof_combined; do
    echo "== $ccma trajectory --model=models/$model.yaml --waypoints=models/paths/$path.csv --out=build/demo/${model}_$path.csv"
    $ccma trajectory --model=models/$model.yaml --waypoints=models/paths/$path.csv \
      --out=build/demo/${model}_$path.csv
  done
done
echo "== $ccma replay --model=models/4dof_reduced.yaml --waypoints=models/paths/4dof_sequential.csv --out=build/demo/replay"
$ccma replay --model=models/4dof_reduced.yaml --waypoints=models/paths/4dof_sequential.csv \
  --out=build/demo/replay
