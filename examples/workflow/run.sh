#!/usr/bin/env bash
# The whole path of docs/workflow.md on a robot of the example-parallel-robots
# collection, the five-bar linkage, with no file edited by hand: every input
# (waypoints, obstacles, design targets) is written here, every model by ccma.
#
#   import -> check -> control -> trajectory -> --obstacles -> plan -> statics
#   -> design -> view -> export (URDF, SDFormat) -> import again
#
# Usage: examples/workflow/run.sh [TOOL [OUT_DIR]]
#   TOOL     the ccma executable (default build/apps/ccma)
#   OUT_DIR  where every file goes (default build/workflow; replaced)
# Each stage's JSON is kept as OUT_DIR/NN_stage.json; a stage whose JSON says
# it failed stops the script with "workflow: FAILED at STAGE: why" (exit 1).
# Prints one line per stage, then "workflow: ok".
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
tool="$(realpath "${1:-$root/build/apps/ccma}")"
out="${2:-$root/build/workflow}"
robot="$root/models/robots/example-parallel-robots/5bar_linkage"
radius=0.02  # m: the capsules import gives every link (the URDF's collision shapes are meshes)

rm -rf "$out"
mkdir -p "$out"
cd "$out"

fail() { echo "workflow: FAILED at $1: $2" >&2; exit 1; }

# run STAGE FILE.json ccma-arguments...: runs ccma, keeps its JSON and stderr.
run() {
  local stage="$1" json="$2"
  shift 2
  if ! "$tool" "$@" > "$json" 2> "${json%.json}.stderr"; then
    cat "${json%.json}.stderr" >&2
    fail "$stage" "ccma $1 exited with an error (see above)"
  fi
}

# py STAGE FILES... <<'PY' ... PY: runs the Python on stdin with j[0], j[1],
# ... the JSON of the files; prints what it prints; a failed assertion
# fails the stage.
py() {
  local stage="$1"
  shift
  { printf 'import json, sys\nj = [json.load(open(f)) for f in sys.argv[1:]]\n'; cat; } | python3 - "$@" ||
    fail "$stage" "check failed (see above)"
}

# 1. import: the URDF and its closure file -> a model assembled at home, with
#    capsules on every link so that obstacles and clearance apply.
run import 01_import.json import --from="$robot/robot.urdf" --closures="$robot/robot.yaml" \
    --end_effector=effector --collision_radius=$radius --out=5bar.yaml
py import 01_import.json <<'PY'
d = j[0]
assert d["assembled"], "not assembled"
assert d["controlled"] == ["y", "z"], f"controlled {d['controlled']}, expected y z (a planar five-bar)"
print(f"import:     {d['bodies']} bodies, {d['joints']} joints, {d['closures']} closure, controlled {','.join(d['controlled'])}, "
      f"E at home {d['residual_energy']:.1e} m^2, {d['collision_capsules']} capsules, {d['collision_ignored_pairs']} pairs touching at home ignored")
PY

# 2. check: mobility at home; its end-effector pose at home from simulate.
run check 02_check.json check --model=5bar.yaml
run check 02_home.json simulate --model=5bar.yaml --controls=0,0
py check 02_check.json 02_home.json <<'PY'
d, h = j
assert d["assembled_at_home"], "not assembled at home"
assert d["end_effector_dof"] == 2 and d["effective_controls"] == 2, "expected 2 controls moving 2 end-effector DOF"
assert not d["clearance"]["below_margin"], "below the margin at home"
p = h["end_effector"]["position"]
print(f"check:      {d['controls']} controls, {d['end_effector_dof']} end-effector DOF, {d['dof_with_controls_fixed']} idle motion, "
      f"clearance at home {d['clearance']['min']:.4f} m ({'|'.join(d['clearance']['pair'])}), end-effector y z {p[1]:.4f} {p[2]:.4f} m")
open("home.txt", "w").write(" ".join(repr(v) for v in p) + "\n")
PY
read -r x0 y0 z0 < home.txt

# The inputs, written here from the home pose: a small loop in the robot's
# y-z plane (6 cm across, 10 cm up), a ledge 4.5 cm below the end-effector's
# lowest point, design targets 2 cm above home and 1.3 cm below it.
python3 - "$x0" "$y0" "$z0" <<'PYEOF'
import sys
x0, y0, z0 = (float(v) for v in sys.argv[1:])
rows = [(0, y0, z0), (2, y0 + 0.06, z0 + 0.03), (4, y0 + 0.06, z0 + 0.10), (6, y0, z0 + 0.10), (8, y0, z0)]
with open("path.csv", "w") as f:
    f.write("# A loop in the five-bar's y-z plane (x is not controlled). Units: s, m, rad.\n")
    f.write("time,x,y,z,roll,pitch,yaw\n")
    for t, y, z in rows:
        f.write(f"{t},{x0!r},{y!r},{z!r},0,0,0\n")
with open("obstacles.yaml", "w") as f:
    f.write("# A ledge under the five-bar's end-effector: its top 4.5 cm below the lowest point.\n")
    f.write("obstacles:\n")
    f.write(f"  - {{name: ledge, box: {{center: [{x0!r}, {y0 + 0.04!r}, {z0 - 0.07!r}], size: [0.4, 0.1, 0.05], yaw: 0}}}}\n")
with open("targets.csv", "w") as f:
    f.write("# Two poses the design must reach with a margin of 0.05 (smallest singular value of dX/du).\n")
    f.write("time,x,y,z,roll,pitch,yaw\n")
    f.write(f"0,{x0!r},{y0!r},{z0 + 0.02!r},0,0,0\n1,{x0!r},{y0!r},{z0 - 0.013!r},0,0,0\n")
PYEOF

# 3. control: 6 cm along y and 4 cm up.
target_y=$(python3 -c "print(repr($y0 + 0.06))")
target_z=$(python3 -c "print(repr($z0 + 0.04))")
run control 03_control.json control --model=5bar.yaml --target="$target_y,$target_z"
py control 03_control.json <<'PY'
d = j[0]
assert d["converged"], d.get("warning", "not converged")
u = d["controls"]
print(f"control:    converged, error {d['error']:.1e} m, controls {u[0]:.6f} {u[1]:.6f} rad, {d['steps']} path steps")
open("control_u.txt", "w").write(",".join(repr(v) for v in u) + "\n")
PY

# 4. trajectory: the loop, without obstacles.
run trajectory 04_trajectory.json trajectory --model=5bar.yaml --waypoints=path.csv --out=trajectory.csv
py trajectory 04_trajectory.json <<'PY'
d = j[0]
assert d["converged"], d.get("warning", "not converged")
print(f"trajectory: {d['waypoints']} waypoints reached in {d['steps']} steps, largest error {d['max_error']:.1e} m, "
      f"smallest singular value of dX/du {d['conditioning']['min_singular_value_dX_du_on_path']:.4f}")
PY

# 5. --obstacles: the same loop with the ledge; clearance at every step.
run obstacles 05_obstacles.json trajectory --model=5bar.yaml --waypoints=path.csv --obstacles=obstacles.yaml \
    --out=trajectory_obstacles.csv
py obstacles 05_obstacles.json <<'PY'
d = j[0]
assert d["converged"], d.get("warning", "not converged")
c = d["clearance"]
assert c["min_on_path"] >= c["margin"], f"clearance {c['min_on_path']} below the margin {c['margin']}"
assert "ledge" in c["pair_on_path"], f"the closest pair {c['pair_on_path']} is not at the ledge"
print(f"obstacles:  {d['steps']} steps, closest {c['min_on_path']:.4f} m ({'|'.join(c['pair_on_path'])}), margin {c['margin']} m")
PY

# ... and control towards a target 1.3 cm below home (reached without the
# ledge): it stops where the effector's capsule (radius 2 cm) is at the
# margin (2 cm) above the ledge's top, z0 - 0.045 + 0.04, naming the ledge.
target_low="$y0,$(python3 -c "print(repr($z0 - 0.013))")"
run obstacles 05_free.json control --model=5bar.yaml --target="$target_low"
run obstacles 05_stop.json control --model=5bar.yaml --target="$target_low" --obstacles=obstacles.yaml
py obstacles 05_free.json 05_stop.json 02_home.json <<'PY'
free, stop, home = j
assert free["converged"], "the low target is not reached without the ledge"
assert not stop["converged"] and "'ledge'" in stop["warning"], "control did not stop at the ledge"
z_stop = home["end_effector"]["position"][2] - 0.045 + 0.04
z = stop["end_effector"]["position"][2]
assert abs(z - z_stop) < 1e-9 and abs(stop["clearance"]["min"] - 0.02) < 1e-9, f"stopped at z {z}, expected {z_stop}"
print(f"obstacles:  control to 1.3 cm below home stops {z - z_stop:.1e} m from the closed form, at clearance "
      f"{stop['clearance']['min']:.6f} m ({'|'.join(stop['clearance']['pair'])})")
PY

# 6. plan: the whole loop optimised, with the ledge.
run plan 06_plan.json plan --model=5bar.yaml --waypoints=path.csv --obstacles=obstacles.yaml --out=plan.csv
py plan 06_plan.json <<'PY'
d = j[0]
assert d["converged"], d.get("warning", "not converged")
assert d["clearance"]["min_on_path"] >= d["clearance"]["margin"], "plan below the margin"
print(f"plan:       used {d['used']}, {d['plan']['reached_waypoints']}/{d['waypoints']} waypoints, {d['steps']} steps, "
      f"{d['iterations']} iterations, closest {d['clearance']['min_on_path']:.4f} m")
PY

# 7. statics: 20 N down and 5 N along -y on the end-effector at the control
#    stage's controls; the motor efforts must equal the wrench's virtual work
#    through dp/du (central differences of simulate, h = 1e-6 rad).
u=$(cat control_u.txt)
run statics 07_statics.json statics --model=5bar.yaml --controls="$u" --wrench=0,-5,-20,0,0,0
h=1e-6
IFS=, read -r u0 u1 <<< "$u"
for k in 0 1; do
  for s in p m; do
    if [[ $s == p ]]; then sign=+; else sign=-; fi
    if [[ $k == 0 ]]; then c="$(python3 -c "print(repr($u0 $sign $h))"),$u1"; else c="$u0,$(python3 -c "print(repr($u1 $sign $h))")"; fi
    run statics "07_fd_${k}_$s.json" simulate --model=5bar.yaml --controls="$c"
  done
done
py statics 07_statics.json 07_fd_0_p.json 07_fd_0_m.json 07_fd_1_p.json 07_fd_1_m.json <<'PY'
d = j[0]
assert d["assembled"] and d["balanced"], d.get("warning", "not balanced")
F = [0, -5, -20]
efforts = [a["effort"] for a in d["actuators"]]
for k in range(2):
    pp, pm = j[1 + 2 * k]["end_effector"]["position"], j[2 + 2 * k]["end_effector"]["position"]
    work = -sum(F[i] * (pp[i] - pm[i]) / 2e-6 for i in range(3))  # effort = -F . dp/du
    assert abs(work - efforts[k]) <= 1e-5 * max(1.0, abs(efforts[k])), f"effort {efforts[k]} != virtual work {work}"
print(f"statics:    efforts {efforts[0]:.4f} {efforts[1]:.4f} N*m (= -F . dp/du by central differences), "
      f"balanced, determinate {str(d['determinate']).lower()}")
PY

# 8. design: lengthen the upper links until both targets are reached with
#    a margin of 0.05 (the lower one is reached with 0.026 at first).
run design 08_design.json design --model=5bar.yaml --targets=targets.csv --out=5bar_designed.yaml \
    --vary_length=mot1:free1,mot2:free2 --min_singular_value=0.05
py design 08_design.json <<'PY'
d = j[0]
assert d["converged"], d.get("warning", "not converged")
ch = ", ".join(f"{c['parameter']} {c['old']:.4f} -> {c['new']:.4f} m" for c in d["changed"])
sv = min(t["min_singular_value"] for t in d["targets"])
print(f"design:     converged in {d['iterations']} iterations, {ch}, smallest singular value {sv:.4f}")
PY

# 9. view: the planned loop with the ledge, as one HTML page.
run view 09_view.json view --model=5bar.yaml --trajectory=plan.csv --obstacles=obstacles.yaml --out=5bar.html
py view 09_view.json <<'PY'
d = j[0]
import os
assert os.path.getsize("5bar.html") > 0, "no page"
flagged = d["flagged_frames"]
assert flagged == 0, f"{flagged} frames flagged"
print(f"view:       5bar.html, {d['frames']} frames, none flagged")
PY

# 10. export: URDF (with its closure file) and SDFormat.
run export 10_export_urdf.json export --model=5bar.yaml --format=urdf --out=5bar.urdf
run export 10_export_sdf.json export --model=5bar.yaml --format=sdf --out=5bar.sdf
py export 10_export_urdf.json 10_export_sdf.json <<'PY'
u, s = j
print(f"export:     5bar.urdf ({u['links']} links, {u['loops']} closure in {u['closures']}), 5bar.sdf ({s['links']} links, {s['loops']} loop)")
PY

# 11. import again, from both files (their stored end-effector and components).
run reimport 11_reimport_urdf.json import --from=5bar.urdf --closures=5bar.closures.yaml \
    --collision_radius=$radius --out=5bar_from_urdf.yaml
run reimport 11_reimport_sdf.json import --from=5bar.sdf --collision_radius=$radius --out=5bar_from_sdf.yaml

# 12. the round trip: the same end-effector pose at the same controls (home,
#     the control stage's, and the trajectory's every 8th row).
mapfile -t controls < <(python3 - "$u" <<'PYEOF'
import csv, sys
print("0,0")
print(sys.argv[1])
rows = list(csv.DictReader(open("trajectory.csv")))
for r in rows[::8]:
    print(f"{r['u_mot1_rad']},{r['u_mot2_rad']}")
PYEOF
)
files=()
for i in "${!controls[@]}"; do
  for m in 5bar 5bar_from_urdf 5bar_from_sdf; do
    run reimport "12_${m}_$i.json" simulate --model=$m.yaml --controls="${controls[$i]}"
    files+=("12_${m}_$i.json")
  done
done
py reimport "${files[@]}" <<'PY'
worst = 0.0
for i in range(0, len(j), 3):
    base = j[i]
    assert base["assembled"], "first import not assembled"
    for other in j[i + 1:i + 3]:
        assert other["assembled"], "re-imported model not assembled"
        pa, pb = other["end_effector"]["position"], base["end_effector"]["position"]
        dp = sum((a - b) ** 2 for a, b in zip(pa, pb)) ** 0.5
        Ra, Rb = other["end_effector"]["rotation"], base["end_effector"]["rotation"]
        dR = max(abs(a - b) for ra, rb in zip(Ra, Rb) for a, b in zip(ra, rb))
        worst = max(worst, dp, dR)
assert worst < 1e-9, f"the re-imported models differ by {worst}"
print(f"reimport:   URDF and SDFormat re-imports give the same end-effector pose at {len(j) // 3} controls (largest difference {worst:.1e})")
PY

echo "outputs: $out (5bar.yaml, 5bar.html, trajectory.csv, plan.csv, 5bar_designed.yaml, 5bar.urdf, 5bar.sdf, NN_stage.json)"
echo "workflow: ok"
