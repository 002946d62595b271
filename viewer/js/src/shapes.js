// Small mesh builders shared by the mechanism's parts. three.js builds
// cylinders, capsules and cones along their local +y axis; alongAxis turns
// such a mesh onto any direction.
import { CapsuleGeometry, ConeGeometry, CylinderGeometry, Group, Mesh, MeshStandardMaterial, Quaternion,
  SphereGeometry, Vector3 } from 'three';

const Y = new Vector3(0, 1, 0);

export function material(color, options = {}) {
  return new MeshStandardMaterial({ color, roughness: 0.6, metalness: 0.05, ...options });
}

// Rotates `object` so that its local +y points along `dir` (left alone for a zero vector).
export function alongAxis(object, dir) {
  const d = new Vector3(...dir);
  if (d.lengthSq() > 1e-24) object.quaternion.setFromUnitVectors(Y, d.normalize());
  return object;
}

// A capsule of radius `radius` from point a to point b (a ball when they coincide).
export function capsule(a, b, radius, mat) {
  const pa = new Vector3(...a), pb = new Vector3(...b);
  const length = pa.distanceTo(pb);
  if (length < 1e-9) return ball(a, radius, mat);
  const mesh = new Mesh(new CapsuleGeometry(radius, length, 4, 14), mat);
  mesh.position.copy(pa).add(pb).multiplyScalar(0.5);
  return alongAxis(mesh, pb.sub(pa).toArray());
}

export function ball(p, radius, mat) {
  const mesh = new Mesh(new SphereGeometry(radius, 18, 12), mat);
  mesh.position.set(...p);
  return mesh;
}

// A solid arrow (shaft and cone) from `origin` along `dir`, `length` long in
// all. Solid rather than three's ArrowHelper, whose one-pixel line shaft is
// hard to see.
export function arrow(origin, dir, length, radius, color) {
  const mat = material(color);
  const head = Math.min(0.3 * length, 5 * radius);
  const group = new Group();
  const shaft = new Mesh(new CylinderGeometry(radius, radius, length - head, 12), mat);
  shaft.position.y = (length - head) / 2;
  const cone = new Mesh(new ConeGeometry(2.4 * radius, head, 16), mat);
  cone.position.y = length - head / 2;
  group.add(shaft, cone);
  group.position.set(...origin);
  return alongAxis(group, dir);
}
