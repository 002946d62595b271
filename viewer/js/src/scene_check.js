// Checks the scene document (viewer/scene_format.md) before anything is
// drawn, so that a malformed page shows one readable message instead of a
// half-built view or an exception from deep inside three.js. Returns a list
// of problems (empty when the scene is usable). Optional parts (joints,
// end_effector, paths, flags, workspace, meshes, collision, loads, efforts, deflection) are checked only when present.
import { checkCollision } from './collision.js';
import { checkDeflection } from './deflection.js';
import { checkEfforts } from './efforts.js';
import { checkLoads } from './loads.js';
import { checkMeshes } from './meshes.js';

const isVec = (v, n) => Array.isArray(v) && v.length === n && v.every(Number.isFinite);
const isList = (v, n) => Array.isArray(v) && v.every((p) => isVec(p, n));

export function checkScene(scene) {
  const problems = [];
  if (!scene || typeof scene !== 'object') return ['the scene is not a JSON object'];
  if (scene.format !== 'ccma-scene-1') problems.push('format is not "ccma-scene-1"');
  if (!Array.isArray(scene.bodies) || scene.bodies.length === 0) return [...problems, 'no bodies'];
  const nb = scene.bodies.length;
  scene.bodies.forEach((b, i) => {
    if (!b || !isList(b.points, 3)) { problems.push(`bodies[${i}].points: a list of [x, y, z]`); return; }
    if (!Array.isArray(b.links) || !b.links.every((l) => Array.isArray(l) && l.length === 2 &&
                                                          l.every((k) => Number.isInteger(k) && k >= 0 && k < b.points.length))) {
      problems.push(`bodies[${i}].links: pairs of indices into its points`);
    }
    if (b.radius !== undefined && !(Number.isFinite(b.radius) && b.radius >= 0)) problems.push(`bodies[${i}].radius`);
  });
  if (scene.scale !== undefined && !(Number.isFinite(scene.scale) && scene.scale > 0)) problems.push('scale: a positive number');
  if (scene.joints !== undefined) {
    if (!Array.isArray(scene.joints)) problems.push('joints: a list');
    else scene.joints.forEach((j, i) => {
      if (!j || !Number.isInteger(j.body) || j.body < -1 || j.body >= nb) problems.push(`joints[${i}].body: -1 or a body index`);
      if (!j || !isVec(j.point, 3)) problems.push(`joints[${i}].point: [x, y, z]`);
      if (j && j.axis !== undefined && !isVec(j.axis, 3)) problems.push(`joints[${i}].axis: [x, y, z]`);
    });
  }
  const ee = scene.end_effector;
  if (ee !== undefined && (!ee || !Number.isInteger(ee.body) || ee.body < 0 || ee.body >= nb || !isVec(ee.point, 3))) {
    problems.push('end_effector: {body: a body index, point: [x, y, z]}');
  }
  const frames = scene.frames || {};
  const n = Array.isArray(frames.time) ? frames.time.length : 0;
  if (n === 0 || !frames.time.every(Number.isFinite)) problems.push('frames.time: one number per frame (at least one)');
  if (!Array.isArray(frames.poses) || frames.poses.length !== n) {
    problems.push('frames.poses: one entry per frame of frames.time');
  } else if (!frames.poses.every((f) => Array.isArray(f) && f.length === nb && isList(f, 7))) {
    problems.push('frames.poses: one [px, py, pz, qx, qy, qz, qw] per body per frame');
  }
  if (frames.flags !== undefined && !Array.isArray(frames.flags)) problems.push('frames.flags: a list');
  const paths = scene.paths;
  if (paths !== undefined && paths !== null) {
    for (const key of ['commanded', 'tracked']) {
      if (paths[key] !== undefined && !isList(paths[key], 3)) problems.push(`paths.${key}: a list of [x, y, z]`);
    }
    if (paths.bases !== undefined && !(Array.isArray(paths.bases) && paths.bases.every((b) => isList(b, 2)))) {
      problems.push('paths.bases: per base, a list of [x, y]');
    }
  }
  const ws = scene.workspace;
  if (ws !== undefined && ws !== null) {
    const m = Array.isArray(ws.points) ? ws.points.length : -1;
    if (!isList(ws.points, 3)) problems.push('workspace.points: a list of [x, y, z]');
    if (!Array.isArray(ws.reachable) || ws.reachable.length !== m || !ws.reachable.every((r) => r === 0 || r === 1)) {
      problems.push('workspace.reachable: 0 or 1 per point');
    }
    if (!Array.isArray(ws.sigma_min) || ws.sigma_min.length !== m ||
        !ws.sigma_min.every((s) => Number.isFinite(s) && s >= 0)) {
      problems.push('workspace.sigma_min: a number >= 0 per point');
    }
    if (ws.components !== undefined && !(Array.isArray(ws.components) && ws.components.every((c) => typeof c === 'string'))) {
      problems.push('workspace.components: a list of names');
    }
  }
  problems.push(...checkMeshes(scene));
  problems.push(...checkCollision(scene));
  problems.push(...checkLoads(scene));
  problems.push(...checkEfforts(scene));
  problems.push(...checkDeflection(scene));
  return problems;
}
