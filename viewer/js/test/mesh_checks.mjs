// The browser test's checks of a page with meshes (`ccma view --meshes`),
// used by browser_test.mjs when the page's scene has "meshes":
//   h. the page made one three.js mesh per body mesh of the scene;
//   i. each mesh is drawn where the scene puts it: its vertex centroid,
//      computed here from the scene alone (the base64 binary STL decoded by
//      hand, then scale, the mesh pose in its body, the body pose at frame 0),
//      projected to the screen, is within 3 px of a pixel that differs from
//      the same view with the meshes hidden; and the page's own centroids
//      agree with these to 1e-6 m.
// Returns a list of failures; adds its numbers to `result`.

// The centroid of the vertices of a binary STL (base64), in its own units.
function stlCentroid(base64) {
  const bytes = Buffer.from(base64, 'base64');
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const n = view.getUint32(80, true);
  const c = [0, 0, 0];
  for (let t = 0; t < n; ++t) {
    for (let v = 0; v < 3; ++v) for (let k = 0; k < 3; ++k) c[k] += view.getFloat32(84 + 50 * t + 12 + 12 * v + 4 * k, true);
  }
  return c.map((x) => x / (3 * n));
}

// q (x, y, z, w) applied to vector v (also used by collision_checks.mjs).
export function rotate([x, y, z, w], v) {
  const n = Math.hypot(x, y, z, w);
  [x, y, z, w] = [x / n, y / n, z / n, w / n];
  const t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])];
  return [v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]),
          v[2] + w * t[2] + (x * t[1] - y * t[0])];
}

const add = (a, b) => a.map((x, k) => x + b[k]);

// World centroids of every body mesh at frame 0, from the scene alone.
export function expectedMeshCentroids(scene) {
  const centroids = (scene.meshes || []).map((f) => stlCentroid(f.stl_base64));
  const out = [];
  scene.bodies.forEach((body, b) => {
    const pose = scene.frames.poses[0][b];
    for (const m of body.meshes || []) {
      const local = centroids[m.file].map((x, k) => x * m.scale[k]);
      const inBody = add(m.position, rotate(m.quaternion, local));
      out.push(add(pose.slice(0, 3), rotate(pose.slice(3, 7), inBody)));
    }
  });
  return out;
}

export async function checkMeshes(page, shot, drawnNear, result) {
  const failures = [];
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ccma-scene').textContent));
  const expected = expectedMeshCentroids(scene);
  const count = await page.evaluate(() => window.ccmaView.meshes);
  result.meshes = count;
  if (count !== expected.length) failures.push(`the page drew ${count} meshes, the scene has ${expected.length}`);
  await page.evaluate(() => window.ccmaView.setFrame(0));
  const shown = await shot();
  await page.evaluate(() => window.ccmaView.showMeshes(false));
  const hidden = await shot();
  await page.evaluate(() => window.ccmaView.showMeshes(true));
  const screen = await page.evaluate((points) => points.map((p) => window.ccmaView.projectToScreen(p)), expected);
  const drawn = screen.filter((p) => drawnNear(shown, hidden, p)).length;
  result.meshes_drawn_at_their_centroid = drawn;
  if (drawn !== expected.length) failures.push(`only ${drawn} of ${expected.length} meshes drawn at their centroid`);
  const own = await page.evaluate(() => window.ccmaView.meshCentroidsWorld());
  const worst = Math.max(0, ...expected.map((p, i) => (own[i] ? Math.hypot(...p.map((x, k) => x - own[i][k])) : Infinity)));
  result.mesh_centroid_error_m = worst;
  if (!(worst < 1e-6)) failures.push(`the page's mesh centroids are ${worst} m from the scene's`);
  return failures;
}
