// Everything around the mechanism: lights, the ground grid and the camera
// framing. The world is z up with the ground at z = 0 (model_format.md).
import { AmbientLight, Box3, DirectionalLight, GridHelper, HemisphereLight, PerspectiveCamera, Vector3 } from 'three';
import { COLORS } from './colors.js';

// Soft light from above and a key light from the viewer's side, so that
// cylinders and discs read as solids without harsh shadows.
export function addLights(world) {
  world.add(new HemisphereLight(0xffffff, 0x9098a8, 1.7));
  world.add(new AmbientLight(0xffffff, 0.35));
  const key = new DirectionalLight(0xffffff, 1.5);
  key.position.set(2, -3, 5);
  world.add(key);
}

// A round grid step (1, 2 or 5 times a power of ten) giving ~10-25 squares
// across the mechanism.
export function gridStep(radius) {
  const raw = (2 * radius) / 15;
  const power = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw * 0.7) || 10 * power;
}

// The ground: fine lines every `step`, bold ones every 5 steps, centred on
// the mechanism (snapped to the grid, so lines stay on round coordinates).
export function addGround(world, box, step) {
  const center = box.getCenter(new Vector3());
  const major = 5 * step;
  const half = Math.ceil((2 * box.getSize(new Vector3()).length()) / major) * major;  // well past the mechanism
  const x = Math.round(center.x / major) * major, y = Math.round(center.y / major) * major;
  const fine = new GridHelper(2 * half, Math.round((2 * half) / step), COLORS.grid, COLORS.grid);
  const bold = new GridHelper(2 * half, Math.round((2 * half) / major), COLORS.gridMajor, COLORS.gridMajor);
  for (const grid of [fine, bold]) {
    grid.rotation.x = Math.PI / 2;  // GridHelper lies in xz
    grid.position.set(x, y, -1e-3 * step);  // just below links lying on the ground
    world.add(grid);
  }
  bold.renderOrder = 1;  // drawn after the fine grid where they coincide
}

// The box of everything shown: the mechanism at frame 0 (its meshes
// included), every path, the workspace cloud and the collision shapes.
export function sceneBox(scene, mechanism, collision = null) {
  const box = new Box3();
  mechanism.bodyPointsWorld().forEach((p) => box.expandByPoint(p));
  mechanism.bodyOriginsWorld().forEach((p) => box.expandByPoint(p));
  const paths = scene.paths || {};
  for (const list of [paths.commanded, paths.tracked]) (list || []).forEach((p) => box.expandByPoint(new Vector3(...p)));
  (paths.bases || []).forEach((b) => b.forEach(([x, y]) => box.expandByPoint(new Vector3(x, y, 0))));
  const cloud = (scene.workspace || {}).points || [];
  if (cloud.length) {  // min and max by hand: a million Vector3s would be slow
    const lo = [...cloud[0]], hi = [...cloud[0]];
    for (const p of cloud) for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); }
    box.expandByPoint(new Vector3(...lo)).expandByPoint(new Vector3(...hi));
  }
  if (mechanism.meshCount) box.union(mechanism.meshesBox());  // bodies' meshes (`ccma view --meshes`)
  if (collision) box.union(collision.box());  // obstacles, bases' cylinders, capsules at frame 0
  box.expandByPoint(new Vector3(box.min.x, box.min.y, 0));  // down to the ground
  // Below the ground only what is there (a robot imported in its own frame
  // may hang below z = 0), not the bases' disc radius added next.
  const lowest = Math.min(box.min.z, 0);
  // The bases' discs reach past their points.
  const r = Math.max(0, ...scene.bodies.map((b) => (b.kind !== 'body' && b.radius > 0 ? b.radius : 0)));
  box.expandByScalar(r);
  box.min.z = Math.max(box.min.z, lowest);
  return box;
}

// The camera's vertical field of view [deg].
export const FOV = 35;

// A camera looking at the box from an elevated three-quarter view (from -y,
// +x, ~30 degrees up), a little farther than where the box's bounding
// sphere just fits the narrower of the two fields of view. The sphere is
// loose around a flat mechanism, which so fills about 60% of the picture and
// leaves room for the overlay's panels.
export function frameCamera(box, aspect) {
  const center = box.getCenter(new Vector3());
  const radius = Math.max(box.getSize(new Vector3()).length() / 2, 0.05);
  const fov = FOV;
  const halfV = (fov * Math.PI) / 360, halfH = Math.atan(Math.tan(halfV) * aspect);
  const distance = (1.08 * radius) / Math.sin(Math.min(halfV, halfH));
  const camera = new PerspectiveCamera(fov, aspect, distance / 200, distance * 50);
  camera.position.copy(center).add(new Vector3(0.5, -0.8, 0.55).normalize().multiplyScalar(distance));
  camera.lookAt(center);
  return { camera, target: center };
}
