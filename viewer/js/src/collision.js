// The collision shapes (viewer/scene_format.md, "collision"; a model with
// `collision:` or `obstacles:`, or `ccma view --obstacles`): the obstacles
// fixed in the world, each mobile base's vertical cylinder from the floor to
// base_height (it follows its base's x and y, not its tilt), the capsules
// fixed in bodies. All translucent, so the mechanism shows through them;
// the two shapes of a frame's closest pair turn red while that frame's
// clearance is below the margin. Obstacles carry their name as a label.
import { Box3, BoxGeometry, CylinderGeometry, EdgesGeometry, Group, LineBasicMaterial, LineSegments, Mesh,
  MeshStandardMaterial, Vector3 } from 'three';
import { COLORS } from './colors.js';
import { capsule } from './shapes.js';

const isVec = (v, n) => Array.isArray(v) && v.length === n && v.every(Number.isFinite);
const positive = (x) => Number.isFinite(x) && x > 0;

// Problems with the scene's collision parts (none when it has none).
export function checkCollision(scene) {
  const c = scene.collision;
  const problems = [];
  if (c === undefined) return problems;
  if (!c || typeof c !== 'object') return ['collision: an object'];
  const nb = (scene.bodies || []).length;
  if (!(Number.isFinite(c.margin) && c.margin >= 0)) problems.push('collision.margin: a number >= 0');
  if (!positive(c.base_height)) problems.push('collision.base_height: a positive number');
  const bases = Array.isArray(c.bases) ? c.bases : [];
  if (!Array.isArray(c.bases) || !bases.every(positive)) problems.push('collision.bases: a positive radius per base');
  if (!Array.isArray(c.base_bodies) || c.base_bodies.length !== bases.length ||
      !c.base_bodies.every((b) => Number.isInteger(b) && b >= 0 && b < nb)) {
    problems.push('collision.base_bodies: a body index per base');
  }
  if (!Array.isArray(c.links)) problems.push('collision.links: a list');
  else c.links.forEach((l, i) => {
    if (!l || !Number.isInteger(l.body) || l.body < 0 || l.body >= nb || !isVec(l.from, 3) || !isVec(l.to, 3) ||
        !positive(l.radius)) {
      problems.push(`collision.links[${i}]: {body: a body index, from: [x, y, z], to: [x, y, z], radius > 0}`);
    }
  });
  if (!Array.isArray(c.obstacles)) problems.push('collision.obstacles: a list');
  else c.obstacles.forEach((o, i) => problems.push(...checkObstacle(o, `collision.obstacles[${i}]`)));
  problems.push(...checkClearance(scene.frames || {}));
  return problems;
}

function checkObstacle(o, where) {
  if (!o || typeof o.name !== 'string' || !isVec(o.center, 3)) return [`${where}: {name, center: [x, y, z], ...}`];
  if (!(Number.isFinite(o.z_min) && Number.isFinite(o.z_max) && o.z_max > o.z_min)) return [`${where}: z_min < z_max`];
  if (o.shape === 'cylinder') return positive(o.radius) ? [] : [`${where}.radius: a positive number`];
  if (o.shape === 'box') {
    return isVec(o.size, 3) && o.size.every(positive) && Number.isFinite(o.yaw) ? [] : [`${where}: size (positive) and yaw`];
  }
  return [`${where}.shape: "cylinder" or "box"`];
}

// frames.clearance and frames.clearance_pairs: both or neither, one entry per frame.
function checkClearance(frames) {
  const n = Array.isArray(frames.time) ? frames.time.length : 0;
  const { clearance, clearance_pairs: pairs } = frames;
  if (clearance === undefined && pairs === undefined) return [];
  const problems = [];
  if (!Array.isArray(clearance) || clearance.length !== n || !clearance.every(Number.isFinite)) {
    problems.push('frames.clearance: a number per frame');
  }
  if (!Array.isArray(pairs) || pairs.length !== n ||
      !pairs.every((p) => Array.isArray(p) && p.length === 2 && p.every((s) => typeof s === 'string'))) {
    problems.push('frames.clearance_pairs: two names per frame');
  }
  return problems;
}

function translucent(color, opacity) {
  return new MeshStandardMaterial({ color, roughness: 0.85, metalness: 0, transparent: true, opacity,
                                    depthWrite: false });
}

// An obstacle at its place: a vertical cylinder or a box turned by yaw, with
// its outline (a translucent solid alone is hard to read against the grid).
function obstacleShape(o, mat, edges) {
  const h = o.z_max - o.z_min;
  const geometry = o.shape === 'box' ? new BoxGeometry(o.size[0], o.size[1], h)
                                     : new CylinderGeometry(o.radius, o.radius, h, 48);
  const group = new Group();
  const solid = new Mesh(geometry, mat);
  const outline = new LineSegments(new EdgesGeometry(geometry, 20), edges);
  if (o.shape !== 'box') [solid, outline].forEach((m) => { m.rotation.x = Math.PI / 2; });  // cylinder axis y -> z
  group.add(solid, outline);
  group.position.set(o.center[0], o.center[1], (o.z_min + o.z_max) / 2);
  if (o.shape === 'box') group.rotation.z = o.yaw;
  group.name = o.name;
  return { group, solid };
}

// A base's cylinder, posed each frame at its base's x and y.
function baseShape(radius, height, mat) {
  const solid = new Mesh(new CylinderGeometry(radius, radius, height, 48), mat);
  solid.rotation.x = Math.PI / 2;
  const group = new Group();
  group.add(solid);
  return { group, solid };
}

// The obstacles' names: small labels over their tops, placed on screen at each render.
function obstacleLabels(obstacles) {
  return obstacles.map((o) => {
    const label = document.createElement('div');
    label.textContent = o.name;
    label.className = 'ccma-obstacle-label';
    Object.assign(label.style, { position: 'absolute', transform: 'translate(-50%, -100%)', pointerEvents: 'none',
                                 font: '11px system-ui, sans-serif', color: '#374151',
                                 background: 'rgba(255,255,255,0.75)', padding: '0 3px', borderRadius: '3px' });
    document.body.append(label);
    return { label, top: new Vector3(o.center[0], o.center[1], o.z_max) };
  });
}

// Builds the shapes into `root`; null when the scene has no collision
// object. Returns what the animation, the overlay and the tests need.
export function buildCollision(scene, root) {
  const c = scene.collision;
  if (!c) return null;
  const obstacleMat = translucent(COLORS.obstacle, 0.38);
  const edges = new LineBasicMaterial({ color: COLORS.obstacleEdge, transparent: true, opacity: 0.8 });
  const envelope = translucent(COLORS.envelope, 0.22);
  const near = translucent(COLORS.flagged, 0.45);
  const parts = [];  // {group, solids, owner, body, base}
  const shapes = [];  // one object per shape of the scene: obstacles, bases, capsules
  for (const o of c.obstacles) {
    const { group, solid } = obstacleShape(o, obstacleMat, edges);
    parts.push({ group, solids: [solid], owner: o.name, material: obstacleMat });
    shapes.push(group);
  }
  c.bases.forEach((r, k) => {
    const body = c.base_bodies[k];
    const { group, solid } = baseShape(r, c.base_height, envelope);
    parts.push({ group, solids: [solid], owner: scene.bodies[body].name, material: envelope, base: body });
    shapes.push(group);
  });
  const byBody = new Map();  // one group per body with capsules, posed like the body
  for (const l of c.links) {
    if (!byBody.has(l.body)) {
      const group = new Group();
      byBody.set(l.body, group);
      parts.push({ group, solids: [], owner: scene.bodies[l.body].name, material: envelope, body: l.body });
    }
    const mesh = capsule(l.from, l.to, l.radius, envelope);
    byBody.get(l.body).add(mesh);
    parts.find((p) => p.body === l.body).solids.push(mesh);
    shapes.push(mesh);
  }
  parts.forEach((p) => root.add(p.group));
  const labels = obstacleLabels(c.obstacles);
  return collisionHandle(scene, root, { parts, shapes, labels, near });
}

function collisionHandle(scene, root, { parts, shapes, labels, near }) {
  const c = scene.collision;
  const frames = scene.frames;
  let visible = true;
  return {
    counts: { obstacles: c.obstacles.length, bases: c.bases.length, links: c.links.length },
    margin: c.margin,
    // Frame f: bases and capsules with their bodies; the closest pair red when below the margin.
    pose(f) {
      for (const p of parts) {
        const pose = p.base !== undefined ? frames.poses[f][p.base] : p.body !== undefined ? frames.poses[f][p.body] : null;
        if (p.base !== undefined) p.group.position.set(pose[0], pose[1], c.base_height / 2);
        else if (pose) {
          p.group.position.set(pose[0], pose[1], pose[2]);
          p.group.quaternion.set(pose[3], pose[4], pose[5], pose[6]).normalize();
        }
      }
      const info = clearanceAt(scene, f);
      const red = info && info.below ? info.pair : [];
      for (const p of parts) p.solids.forEach((m) => { m.material = red.includes(p.owner) ? near : p.material; });
      root.updateMatrixWorld(true);
    },
    // All shapes shown or hidden; with `only` (an index into obstacles,
    // bases, capsules in that order), that one shape alone (tests).
    setVisible(on, only = -1) {
      visible = on;
      parts.forEach((p) => { p.group.visible = on; });
      if (on) shapes.forEach((m, i) => { m.visible = only < 0 || i === only; });  // after: some shapes are parts
      labels.forEach(({ label }) => { label.style.display = on ? '' : 'none'; });
    },
    // Labels follow the obstacles on screen (called after each render).
    placeLabels(camera, width, height) {
      for (const { label, top } of labels) {
        const v = top.clone().project(camera);
        const shown = visible && v.z < 1 && Math.abs(v.x) < 1 && Math.abs(v.y) < 1;
        label.style.display = shown ? '' : 'none';
        label.style.left = `${((v.x + 1) / 2) * width}px`;
        label.style.top = `${((1 - v.y) / 2) * height - 2}px`;
      }
    },
    // The world box of the static shapes and the bases' cylinders (camera framing).
    box() {
      const box = new Box3();
      parts.forEach((p) => box.expandByObject(p.group));
      return box;
    },
  };
}

// The clearance of frame f: {min [m], pair [a, b], below}; null when the
// scene has no clearance per frame.
export function clearanceAt(scene, f) {
  const frames = scene.frames;
  if (!scene.collision || !Array.isArray(frames.clearance)) return null;
  const min = frames.clearance[f];
  return { min, pair: frames.clearance_pairs[f], below: min < scene.collision.margin - 1e-9 };
}
