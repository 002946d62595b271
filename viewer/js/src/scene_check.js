// Checks the scene document (viewer/scene_format.md) before anything is
// drawn, so that a malformed page shows one readable message instead of a
// half-built view. Returns a list of problems (empty when the scene is usable).
export function checkScene(scene) {
  const problems = [];
  const isVec = (v, n) => Array.isArray(v) && v.length === n && v.every(Number.isFinite);
  if (!scene || scene.format !== 'ccma-scene-1') problems.push('format is not "ccma-scene-1"');
  if (!scene || !Array.isArray(scene.bodies) || scene.bodies.length === 0) {
    problems.push('no bodies');
    return problems;
  }
  scene.bodies.forEach((b, i) => {
    if (!Array.isArray(b.points) || !b.points.every((p) => isVec(p, 3))) problems.push(`bodies[${i}].points`);
    if (!Array.isArray(b.links)) problems.push(`bodies[${i}].links`);
  });
  const frames = scene.frames || {};
  if (!Array.isArray(frames.time) || frames.time.length === 0) problems.push('frames.time is empty');
  if (!Array.isArray(frames.poses) || frames.poses.length !== (frames.time || []).length) {
    problems.push('frames.poses does not match frames.time');
  } else if (!frames.poses.every((f) => Array.isArray(f) && f.length === scene.bodies.length &&
                                        f.every((p) => isVec(p, 7)))) {
    problems.push('frames.poses: one [px,py,pz,qx,qy,qz,qw] per body per frame');
  }
  return problems;
}
