#!/usr/bin/env bash
# Sets up, builds and runs ccma's main jobs on the bundled models, then says
# what ran and where every output is:
#   check and simulate (assembly) of every model in models/, control of each to
#   a target 3 to 4 cm and 0.05 rad from its home end-effector pose, the
#   paper's two 4-DOF paths with trajectory, a simulated replay of the first
#   with plots, and 3D pages of every model and of the replay (ccma view:
#   open them in a browser).
# It builds only the `ccma` tool (about 3 to 6 minutes on 2 cores the first time, apt-get
# included; the runs take about 20 s); scripts/test.sh builds and runs everything else.
# Without the viewer's JavaScript (the npm registry unreachable when the build was
# configured: build.log says why) it skips the 3D pages and says so.
#   scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
echo "demo: set-up and build of the ccma tool first (about 3 to 6 minutes on 2 cores the first time, apt-get included), then about 20 s of runs"
scripts/setup.sh --tool
ccma=build/apps/ccma
out=build/demo
mkdir -p "$out"
summary=()
# view ARGS...: a 3D page, unless the tool was built without the viewer.
viewer=1
view() {
  ((viewer)) || return 0
  if ! $ccma view "$@" > /dev/null 2> "$out/view.log"; then
    if grep -q "without the viewer" "$out/view.log"; then
      viewer=0
      echo "demo: no 3D pages: $(cat "$out/view.log")"
      return 0
    fi
    cat "$out/view.log" >&2
    return 1
  fi
}

# The value of a top-level JSON key (true/false/number) in a file.
key() { sed -n "s/^  \"$2\": \([^,]*\),\{0,1\}$/\1/p" "$1" | head -n 1; }
# A target near a model's home end-effector pose, read from its simulate
# document: 3 cm in x, -2 cm in y, 2 cm in z and 0.05 rad in yaw away
# (components the model does not control are ignored by control).
near_home() {
  local p r
  p=$(sed -n '/"end_effector": {/,/}/s/^ *"position": \[\(.*\)\],\{0,1\}$/\1/p' "$1" | head -n 1)
  r=$(sed -n '/"end_effector": {/,/}/s/^ *"rpy": \[\(.*\)\],\{0,1\}$/\1/p' "$1" | head -n 1)
  echo "$p,$r" | awk -F, '{printf "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", $1 + 0.03, $2 - 0.02, $3 + 0.02, $4 + 0, $5 + 0, $6 + 0.05}'
}
# Why a control run did not converge: its top-level "warning" (empty if none).
why() { sed -n 's/^  "warning": "\(.*\)",\{0,1\}$/\1/p' "$1" | head -n 1; }

for model in models/*.yaml; do
  name=$(basename "$model" .yaml)
  echo "demo: $name: check, simulate, control"
  $ccma check --model="$model" > "$out/${name}_check.json"
  $ccma simulate --model="$model" > "$out/${name}_simulate.json"
  $ccma control --model="$model" --target="$(near_home "$out/${name}_simulate.json")" > "$out/${name}_control.json"
  view --model="$model" --out="$out/${name}.html"
  summary+=("$(printf '%-18s rigid %-5s  assembled at home %-5s  control converged %-5s in %s ms' "$name" \
    "$(key "$out/${name}_check.json" rigid_with_controls_fixed)" "$(key "$out/${name}_simulate.json" assembled)" \
    "$(key "$out/${name}_control.json" converged)" "$(key "$out/${name}_control.json" solve_time_ms | cut -c1-6)")")
  reason=$(why "$out/${name}_control.json")
  if [ -n "$reason" ]; then summary+=("$(printf '%-18s   not converged: %s' "" "$reason")"); fi
done
for model in 4dof_reduced 4dof_complete; do
  for path in 4dof_sequential 4dof_combined; do
    echo "demo: trajectory $model on $path"
    $ccma trajectory --model=models/$model.yaml --waypoints=models/paths/$path.csv \
      --out=$out/${model}_$path.csv > "$out/${model}_${path}_trajectory.json"
    summary+=("$(printf 'trajectory %-14s %-16s converged %-5s %s steps' "$model" "$path" \
      "$(key "$out/${model}_${path}_trajectory.json" converged)" "$(key "$out/${model}_${path}_trajectory.json" steps)")")
  done
done
echo "demo: replay of 4dof_reduced on 4dof_sequential (simulated bases, about 10 s)"
$ccma replay --model=models/4dof_reduced.yaml --waypoints=models/paths/4dof_sequential.csv \
  --out=$out/replay > "$out/replay.json" 2> "$out/replay.log"
view --model=models/4dof_reduced.yaml --replay=$out/replay --out=$out/replay.html
view --model=models/4dof_reduced.yaml --trajectory=$out/4dof_reduced_4dof_combined.csv \
  --out=$out/4dof_reduced_4dof_combined.html

echo
echo "demo: done. What ran (every JSON result is in $out/):"
printf '  %s\n' "${summary[@]}"
echo "  replay: converged $(key "$out/replay.json" converged), torn $(key "$out/replay.json" torn); RMSE table $out/replay/rmse.md"
echo "Outputs:"
echo "  $out/*_check.json, *_simulate.json, *_control.json   per model"
echo "  $out/4dof_*_4dof_*.csv                                 trajectory rows (one per control step)"
echo "  $out/replay/end_effector.png, bases_xy.png (+ .svg)    replay plots; CSVs beside them"
((viewer)) && echo "  $out/<model>.html, replay.html, 4dof_reduced_4dof_combined.html   3D views (open in a browser)"
echo "  Python: scripts/setup.sh builds the module, then PYTHONPATH=build/python python3 -c 'import ccma'  (docs/python.md)"
echo "Next: build/apps/ccma --help, docs/README.md"
