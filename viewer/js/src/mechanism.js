// The mechanism as three.js objects, built once from the scene: one Group per
// body (posed per frame), joint markers inside the group of the joint's body
// (or the world), the end-effector's frame. Shapes are derived from the joint
// points alone (viewer/scene_format.md), so any model file can be shown.
import {
  ArrowHelper, BoxGeometry, CapsuleGeometry, CylinderGeometry, Group, Mesh, MeshStandardMaterial,
  Quaternion, SphereGeometry, Vector3,
} from 'three';
import { COLORS } from './colors.js';

const Y = new Vector3(0, 1, 0);

function material(color, options = {}) {
  return new MeshStandardMaterial({ color, roughness: 0.55, metalness: 0.1, ...options });
}

// A mesh whose local +y axis (three's cylinder/capsule axis) points along `dir`.
function alongAxis(mesh, dir) {
  const d = new Vector3(...dir);
  if (d.lengthSq() > 0) mesh.quaternion.copy(new Quaternion().setFromUnitVectors(Y, d.normalize()));
  return mesh;
}

function capsule(a, b, radius, mat) {
  const pa = new Vector3(...a), pb = new Vector3(...b);
  const length = pa.distanceTo(pb);
  const geometry = length > 1e-9 ? new CapsuleGeometry(radius, length, 4, 12) : new SphereGeometry(radius, 16, 12);
  const mesh = new Mesh(geometry, mat);
  mesh.position.copy(pa).add(pb).multiplyScalar(0.5);
  if (length > 1e-9) alongAxis(mesh, pb.clone().sub(pa).toArray());
  return mesh;
}

function baseShape(body, s) {
  const group = new Group();
  const r = body.radius || 2 * s;
  const color = body.kind === 'differential' ? COLORS.differential : COLORS.omni;
  const disc = new Mesh(new CylinderGeometry(r, r, 0.15 * r, 40), material(color, { transparent: true, opacity: 0.6 }));
  disc.rotation.x = Math.PI / 2;  // cylinder axis (y) -> body z
  disc.position.z = 0.075 * r;
  group.add(disc);
  // Heading: the body's +x axis.
  group.add(new ArrowHelper(new Vector3(1, 0, 0), new Vector3(0, 0, 0.16 * r), 1.5 * r, COLORS.heading,
                            0.45 * r, 0.3 * r));
  if (body.kind === 'differential') {
    for (const side of [-1, 1]) {
      const wheel = new Mesh(new CylinderGeometry(0.35 * r, 0.35 * r, 0.18 * r, 24), material(0x222222));
      wheel.position.set(0, side * 1.05 * r, 0.35 * r);  // axle along body y
      group.add(wheel);
    }
  }
  return group;
}

function bodyGroup(body, s) {
  const group = new Group();
  group.name = body.name;
  const isBase = body.kind === 'omni' || body.kind === 'differential';
  if (isBase) group.add(baseShape(body, s));
  const linkMat = material(isBase ? COLORS.omni : COLORS.link);
  for (const [i, j] of body.links) {
    if (body.points[i] && body.points[j]) group.add(capsule(body.points[i], body.points[j], 0.22 * s, linkMat));
  }
  for (const p of body.points) {
    const ball = new Mesh(new SphereGeometry(0.3 * s, 16, 12), linkMat);
    ball.position.set(...p);
    group.add(ball);
  }
  return group;
}

// A marker that says the joint's type: revolute a cylinder along its axis,
// prismatic a bar along it, spherical a ball, universal two crossed
// cylinders, fixed a cube. Actuated joints in their own colour.
function jointMarker(joint, s) {
  const mat = material(joint.actuated ? COLORS.actuated : COLORS.joint);
  const axis = joint.axis || [0, 0, 1];
  let marker;
  switch (joint.type) {
    case 'revolute':
      marker = alongAxis(new Mesh(new CylinderGeometry(0.3 * s, 0.3 * s, 1.1 * s, 20), mat), axis);
      break;
    case 'prismatic':
      marker = alongAxis(new Mesh(new BoxGeometry(0.6 * s, 3 * s, 0.6 * s), mat), axis);
      break;
    case 'universal': {
      marker = new Group();
      marker.add(alongAxis(new Mesh(new CylinderGeometry(0.2 * s, 0.2 * s, 1.1 * s, 16), mat), axis));
      const a = new Vector3(...axis).normalize();
      const other = Math.abs(a.z) < 0.9 ? new Vector3(0, 0, 1) : new Vector3(1, 0, 0);
      marker.add(alongAxis(new Mesh(new CylinderGeometry(0.2 * s, 0.2 * s, 1.1 * s, 16), mat),
                           other.cross(a).normalize().toArray()));
      break;
    }
    case 'fixed':
      marker = new Mesh(new BoxGeometry(0.5 * s, 0.5 * s, 0.5 * s), mat);
      break;
    default:  // spherical
      marker = new Mesh(new SphereGeometry(0.3 * s, 20, 14), mat);
  }
  marker.position.set(...joint.point);
  marker.name = joint.name;
  return marker;
}

function endEffectorFrame(point, size) {
  const frame = new Group();
  frame.position.set(...point);
  const o = new Vector3(0, 0, 0);
  frame.add(new ArrowHelper(new Vector3(1, 0, 0), o, size, COLORS.axisX, 0.25 * size, 0.12 * size));
  frame.add(new ArrowHelper(new Vector3(0, 1, 0), o, size, COLORS.axisY, 0.25 * size, 0.12 * size));
  frame.add(new ArrowHelper(new Vector3(0, 0, 1), o, size, COLORS.axisZ, 0.25 * size, 0.12 * size));
  return frame;
}

// Builds the mechanism into `root`; returns what the animation needs.
export function buildMechanism(scene, root) {
  const s = Math.max(scene.scale || 0.5, 1e-3) * 0.05;  // marker unit [m]
  const bodies = scene.bodies.map((b) => bodyGroup(b, s));
  bodies.forEach((g) => root.add(g));
  for (const joint of scene.joints || []) {
    const parent = joint.body >= 0 && joint.body < bodies.length ? bodies[joint.body] : root;
    parent.add(jointMarker(joint, s));
  }
  const ee = scene.end_effector || { body: 0, point: [0, 0, 0] };
  const eeBody = bodies[ee.body] || bodies[0];
  eeBody.add(endEffectorFrame(ee.point, 5 * s));
  return {
    bodies,
    // Every body at frame f: p_WB and the quaternion of R_WB.
    pose(frames, f) {
      frames.poses[f].forEach(([px, py, pz, qx, qy, qz, qw], b) => {
        bodies[b].position.set(px, py, pz);
        bodies[b].quaternion.set(qx, qy, qz, qw).normalize();
      });
      root.updateMatrixWorld(true);
    },
    // Hides or shows every body (the browser test compares the two pictures).
    setVisible(visible) {
      bodies.forEach((g) => { g.visible = visible; });
    },
    endEffectorWorld() {
      return eeBody.localToWorld(new Vector3(...ee.point));
    },
    // World positions of every body point (for the browser test's pixel checks).
    bodyPointsWorld() {
      const out = [];
      scene.bodies.forEach((b, i) => b.points.forEach((p) => out.push(bodies[i].localToWorld(new Vector3(...p)))));
      return out;
    },
  };
}
