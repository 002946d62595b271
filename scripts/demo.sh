#!/usr/bin/env bash
# Sets up, builds and runs ccma's main job on the bundled reference models:
# `ccma check` (counts and numerical mobility), `ccma simulate` (assembly),
# and the embedding example (warm-started solves while every base drives).
#   scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
for model in models/*.yaml; do
  echo "== build/apps/ccma check --model=$model"
  build/apps/ccma check --model="$model"
  echo "== build/apps/ccma simulate --model=$model"
  build/apps/ccma simulate --model="$model"
  echo "== build/apps/embed_example $model"
  build/apps/embed_example "$model"
done
