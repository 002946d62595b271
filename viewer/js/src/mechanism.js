// The mechanism as three.js objects, built once from the scene: one Group per
// body (posed per frame), joint markers inside the group of the joint's body
// (or the world, static), the end-effector's frame. Shapes are derived from
// the joint points alone (viewer/scene_format.md), so any model file can be
// shown. Sizes are fractions of the scene's `scale` (its bounding radius), so
// a 0.3 m planar robot and a 2 m Stewart platform look alike.
import { BoxGeometry, CylinderGeometry, Group, Mesh, SphereGeometry, SRGBColorSpace, Vector3 } from 'three';
import { COLORS } from './colors.js';
import { addBodyMeshes, meshCentroidsWorld, meshesBox, meshGeometries } from './meshes.js';
import { alongAxis, arrow, ball, capsule, material } from './shapes.js';

// Marker sizes as fractions of the scene's scale.
const SIZE = {
  link: 0.015,       // capsule radius
  point: 0.021,      // ball at each body point
  joint: 0.025,      // revolute cylinder radius; the other markers scale with it
  frame: 0.2,        // end-effector arrows' length
};

// A legged base: a body box of its footprint at the body frame (tilting with
// it), four legs from the box's corners down the body's -z by the home body
// height (they reach the floor at home), an arrow along the heading.
function leggedShape(body, u) {
  const group = new Group();
  const [length, width] = body.footprint || [0.6, 0.3];
  const thickness = 0.25 * width;
  const mat = material(COLORS.legged, { roughness: 0.7 });
  const box = new Mesh(new BoxGeometry(length, width, thickness), mat);
  group.add(box);
  group.userData.shell = mat;  // recoloured by effort (efforts.js)
  const legMat = material(COLORS.wheel, { roughness: 0.9 });
  const legLength = body.body_height > 0 ? body.body_height : 0.4;
  const r = Math.max(0.08 * width, 0.004 * u);
  for (const sx of [-1, 1]) {
    for (const sy of [-1, 1]) {
      const leg = new Mesh(new CylinderGeometry(r, 0.7 * r, legLength, 12), legMat);
      leg.rotation.x = Math.PI / 2;  // cylinder axis (y) -> body z
      leg.position.set(0.4 * sx * length, 0.4 * sy * width, -legLength / 2);
      group.add(leg);
    }
  }
  group.add(arrow([0, 0, thickness / 2], [1, 0, 0], 0.75 * length, Math.max(0.03 * width, 0.004 * u), COLORS.heading));
  return group;
}

// A mobile base: a flat disc on the ground (its axis the body's z, its bottom
// at the body origin), an arrow along the heading (body +x) and, for a
// differential drive, its two wheels on the body y axis.
function baseShape(body, u) {
  const group = new Group();
  const r = body.radius > 0 ? body.radius : 0.2 * u;
  const color = body.kind === 'differential' ? COLORS.differential : COLORS.omni;
  const thickness = 0.12 * r;
  const disc = new Mesh(new CylinderGeometry(r, r, thickness, 48), material(color, { roughness: 0.75 }));
  disc.rotation.x = Math.PI / 2;  // cylinder axis (y) -> body z
  disc.position.z = thickness / 2;
  group.add(disc);
  group.userData.shell = disc.material;  // recoloured by effort (efforts.js)
  group.add(arrow([0, 0, thickness], [1, 0, 0], 1.35 * r, Math.max(0.06 * r, 0.004 * u), COLORS.heading));
  if (body.kind === 'differential') {
    const wheelMat = material(COLORS.wheel, { roughness: 0.9 });
    for (const side of [-1, 1]) {
      const wheel = new Mesh(new CylinderGeometry(0.32 * r, 0.32 * r, 0.16 * r, 28), wheelMat);
      wheel.position.set(0, side * 1.0 * r, 0.32 * r);  // axle along body y, touching the ground
      group.add(wheel);
    }
  }
  return group;
}

// A body's group; a body with meshes (`ccma view --meshes`) shows them
// instead of its capsules, which are pushed onto `meshes`. The materials of
// its capsules, balls and meshes (not a base's disc) are kept in
// userData.materials: colouring by load recolours them; a base's disc or
// body box is userData.shell, which colouring by effort recolours too.
function bodyGroup(body, u, geometries, meshes) {
  const group = new Group();
  group.name = body.name;
  const isBase = body.kind === 'omni' || body.kind === 'differential' || body.kind === 'legged';
  const shape = body.kind === 'legged' ? leggedShape(body, u) : isBase ? baseShape(body, u) : null;
  if (shape) group.add(shape);
  const color = !isBase ? COLORS.link : COLORS[body.kind];
  const mat = material(color);
  const own = addBodyMeshes(group, body, geometries);
  meshes.push(...own);
  for (const [i, j] of own.length ? [] : body.links) {
    if (body.points[i] && body.points[j]) group.add(capsule(body.points[i], body.points[j], SIZE.link * u, mat));
  }
  for (const p of body.points) group.add(ball(p, SIZE.point * u, mat));
  group.userData.materials = [...new Set([mat, ...own.map((m) => m.material)])];
  group.userData.shell = shape ? shape.userData.shell : null;  // a base's disc or body box
  return group;
}

// A unit vector perpendicular to `a`.
function perpendicular(a) {
  const v = new Vector3(...a).normalize();
  const other = Math.abs(v.z) < 0.9 ? new Vector3(0, 0, 1) : new Vector3(1, 0, 0);
  return other.cross(v).normalize().toArray();
}

// A marker that says the joint's type: revolute a short cylinder along its
// axis, prismatic a bar along it, spherical a ball, universal two crossed
// cylinders (the first along its axis), fixed a cube. Actuated joints amber.
function jointMarker(joint, u) {
  const mat = material(joint.actuated ? COLORS.actuated : COLORS.joint, { roughness: 0.45 });
  const r = SIZE.joint * u;
  const axis = joint.axis || [0, 0, 1];
  let marker;
  switch (joint.type) {
    case 'revolute':
      marker = alongAxis(new Mesh(new CylinderGeometry(r, r, 3.2 * r, 24), mat), axis);
      break;
    case 'prismatic':
      marker = alongAxis(new Mesh(new BoxGeometry(1.7 * r, 6 * r, 1.7 * r), mat), axis);
      break;
    case 'universal':
      marker = new Group();
      marker.add(alongAxis(new Mesh(new CylinderGeometry(0.65 * r, 0.65 * r, 3.4 * r, 16), mat), axis));
      marker.add(alongAxis(new Mesh(new CylinderGeometry(0.65 * r, 0.65 * r, 3.4 * r, 16), mat), perpendicular(axis)));
      break;
    case 'fixed':
      marker = new Mesh(new BoxGeometry(1.8 * r, 1.8 * r, 1.8 * r), mat);
      break;
    default:  // spherical
      marker = new Mesh(new SphereGeometry(1.25 * r, 24, 16), mat);
  }
  marker.position.set(...joint.point);
  marker.name = joint.name;
  return marker;
}

// The end-effector's frame: x, y, z arrows of its body's axes at its point.
function endEffectorFrame(point, u) {
  const frame = new Group();
  frame.position.set(...point);
  const length = SIZE.frame * u, radius = 0.007 * u;
  frame.add(arrow([0, 0, 0], [1, 0, 0], length, radius, COLORS.axisX));
  frame.add(arrow([0, 0, 0], [0, 1, 0], length, radius, COLORS.axisY));
  frame.add(arrow([0, 0, 0], [0, 0, 1], length, radius, COLORS.axisZ));
  return frame;
}

// The scene's characteristic size [m]: its `scale` (written by ccma view),
// else the reach of its bodies from their centre at frame 0.
export function sceneSize(scene) {
  if (scene.scale > 0) return scene.scale;
  const poses = scene.frames.poses[0];
  const c = [0, 1, 2].map((k) => poses.reduce((sum, p) => sum + p[k], 0) / poses.length);
  let r = 0;
  scene.bodies.forEach((b, i) => {
    const reach = Math.max(0, ...b.points.map((q) => Math.hypot(...q)));
    r = Math.max(r, Math.hypot(poses[i][0] - c[0], poses[i][1] - c[1], poses[i][2] - c[2]) + reach);
  });
  return Math.max(r, 0.05);
}

// Builds the mechanism into `root` with markers sized from `u` (sceneSize);
// returns what the animation and the tests need.
export function buildMechanism(scene, root, u) {
  const geometries = meshGeometries(scene);
  const meshes = [];  // every body's meshes
  const bodies = scene.bodies.map((b) => bodyGroup(b, u, geometries, meshes));
  const ground = new Group();  // joints on the world (body -1): static
  bodies.forEach((g) => root.add(g));
  root.add(ground);
  for (const joint of scene.joints || []) {
    const parent = joint.body >= 0 && joint.body < bodies.length ? bodies[joint.body] : ground;
    parent.add(jointMarker(joint, u));
  }
  // Without an end-effector in the scene, no frame is drawn and the tests
  // follow body 0's origin instead.
  const ee = scene.end_effector || { body: 0, point: [0, 0, 0] };
  const eeBody = bodies[ee.body];
  if (scene.end_effector) eeBody.add(endEffectorFrame(ee.point, u));
  return {
    // Every body at frame f: p_WB and the quaternion of R_WB.
    pose(frames, f) {
      frames.poses[f].forEach(([px, py, pz, qx, qy, qz, qw], b) => {
        bodies[b].position.set(px, py, pz);
        bodies[b].quaternion.set(qx, qy, qz, qw).normalize();
      });
      root.updateMatrixWorld(true);
    },
    // Colours each body's capsules, balls and meshes: colors[b] is sRGB
    // [r, g, b] in 0..1 (loads.js); and each body's colour as drawn, sRGB
    // 0..255 (the browser test compares them with the scene's loads).
    // With shells (colouring by effort: a base is the actuator), a base's disc
    // or body box too.
    paint(colors, { shells = false } = {}) {
      bodies.forEach((g, b) => {
        const all = shells && g.userData.shell ? [...g.userData.materials, g.userData.shell] : g.userData.materials;
        all.forEach((m) => m.color.setRGB(...colors[b], SRGBColorSpace));
      });
    },
    // The links and balls see-through (the rigid shape under a loaded one, deflection.js).
    fade(opacity) {
      bodies.forEach((g) => g.userData.materials.forEach((m) => {
        m.transparent = true;
        m.opacity = opacity;
        m.depthWrite = false;
      }));
    },
    bodyColors() {
      return bodies.map((g) => {
        const c = g.userData.materials[0].color.clone().convertLinearToSRGB();
        return [c.r, c.g, c.b].map((x) => Math.round(255 * x));
      });
    },
    // Each base's disc or body box colour as drawn (sRGB 0..255; null for a link).
    shellColors() {
      return bodies.map((g) => {
        if (!g.userData.shell) return null;
        const c = g.userData.shell.color.clone().convertLinearToSRGB();
        return [c.r, c.g, c.b].map((x) => Math.round(255 * x));
      });
    },
    // Hides or shows the whole mechanism (the browser test compares the two pictures).
    setVisible(visible) {
      [...bodies, ground].forEach((g) => { g.visible = visible; });
    },
    endEffectorWorld() {
      return eeBody.localToWorld(new Vector3(...ee.point));
    },
    // World positions of every body point (for framing the camera and for
    // the browser test's pixel checks) and of every body's origin.
    bodyPointsWorld() {
      const out = [];
      scene.bodies.forEach((b, i) => b.points.forEach((p) => out.push(bodies[i].localToWorld(new Vector3(...p)))));
      return out;
    },
    bodyOriginsWorld() {
      return bodies.map((g) => g.position.clone());
    },
    // The bodies' meshes: how many, their world box as posed, their vertex
    // centroids in the world (tests), shown or hidden.
    meshCount: meshes.length,
    meshesBox: () => meshesBox(meshes),
    meshCentroidsWorld: () => meshCentroidsWorld(meshes),
    setMeshesVisible(visible) {
      meshes.forEach((m) => { m.visible = visible; });
    },
  };
}
