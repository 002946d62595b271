// The browser test's checks of a page with collision shapes (a model with
// `collision:` or `obstacles:`, or `ccma view --obstacles`), used by
// browser_test.mjs when the page's scene has "collision":
//   j. the page made one shape per obstacle, base and capsule of the scene;
//   k. each shape is drawn where the scene puts it at frame 0: its centre,
//      computed here from the scene alone (an obstacle's centre; a base's
//      cylinder at its body's x, y and half base_height; a capsule's
//      midpoint through its body's pose), projected to the screen, is within
//      3 px of a pixel that differs from the same view with the shapes hidden,
//      the shape shown alone (so that another shape cannot stand in for it);
//   l. the overlay shows each frame's clearance and pair as the scene has
//      them, with "below margin" exactly on the frames below the margin; on
//      such a frame an obstacle of the closest pair is drawn red at its centre
//      and is not on a frame above the margin.
// Returns a list of failures; adds its numbers to `result`.
import { rotate } from './mesh_checks.mjs';

const add = (a, b) => a.map((x, k) => x + b[k]);

// World centres of every collision shape at frame f, from the scene alone,
// in the page's order: obstacles, bases, capsules.
export function expectedShapeCentres(scene, f) {
  const c = scene.collision;
  const poses = scene.frames.poses[f];
  const out = c.obstacles.map((o) => [o.center[0], o.center[1], (o.z_min + o.z_max) / 2]);
  c.base_bodies.forEach((b) => out.push([poses[b][0], poses[b][1], c.base_height / 2]));
  for (const l of c.links) {
    const mid = l.from.map((x, k) => (x + l.to[k]) / 2);
    out.push(add(poses[l.body].slice(0, 3), rotate(poses[l.body].slice(3, 7), mid)));
  }
  return out;
}

// Whether some pixel within 3 px of (x, y) is clearly red.
function redNear(img, [x, y]) {
  for (let dx = -3; dx <= 3; ++dx) for (let dy = -3; dy <= 3; ++dy) {
    const px = Math.round(x) + dx, py = Math.round(y) + dy;
    if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
    const [r, g, b] = img.at(px, py);
    if (r > g + 40 && r > b + 40) return true;
  }
  return false;
}

async function checkDrawn(page, shot, drawnNear, scene, result) {
  const failures = [];
  const c = scene.collision;
  const counts = await page.evaluate(() => window.ccmaView.collision);
  const expectedCounts = { obstacles: c.obstacles.length, bases: c.bases.length, links: c.links.length };
  result.collision_shapes = counts;
  if (JSON.stringify(counts) !== JSON.stringify(expectedCounts)) {
    failures.push(`the page drew ${JSON.stringify(counts)} collision shapes, the scene has ${JSON.stringify(expectedCounts)}`);
  }
  await page.evaluate(() => window.ccmaView.setFrame(0));
  await page.evaluate(() => window.ccmaView.showCollision(false));
  const hidden = await shot();
  const centres = expectedShapeCentres(scene, 0);
  const screen = await page.evaluate((points) => points.map((p) => window.ccmaView.projectToScreen(p)), centres);
  const onScreen = ([x, y]) => x >= 0 && y >= 0 && x < hidden.width && y < hidden.height;
  const visible = screen.filter(onScreen);
  let drawn = 0;
  for (let i = 0; i < screen.length; ++i) {
    if (!onScreen(screen[i])) continue;
    await page.evaluate((only) => window.ccmaView.showCollision(true, only), i);
    drawn += drawnNear(await shot(), hidden, screen[i]) ? 1 : 0;
  }
  await page.evaluate(() => window.ccmaView.showCollision(true));
  Object.assign(result, { collision_centres: centres.length, collision_centres_drawn: drawn });
  if (visible.length < centres.length) failures.push(`only ${visible.length} of ${centres.length} collision shapes on screen`);
  if (drawn !== visible.length) failures.push(`only ${drawn} of ${visible.length} collision shapes drawn at their centre`);
  return failures;
}

// The overlay at frame f against the scene's numbers.
async function overlayAt(page, f) {
  return page.evaluate((frame) => {
    window.ccmaView.setFrame(frame);
    const below = document.getElementById('ccma-below-margin');
    return { text: document.getElementById('ccma-clearance')?.textContent || '',
             below: Boolean(below && below.style.display !== 'none') };
  }, f);
}

async function checkOverlay(page, shot, scene, result) {
  const failures = [];
  const { clearance, clearance_pairs: pairs } = scene.frames;
  if (!Array.isArray(clearance)) return failures;  // no pair is checked
  const margin = scene.collision.margin;
  const isBelow = (f) => clearance[f] < margin - 1e-9;
  const belowFrame = clearance.findIndex((_, f) => isBelow(f));
  const clearFrame = clearance.findIndex((_, f) => !isBelow(f));
  Object.assign(result, { clearance_below_frame: belowFrame, clearance_clear_frame: clearFrame });
  for (const f of [0, clearance.length - 1, belowFrame, clearFrame].filter((i) => i >= 0)) {
    const shown = await overlayAt(page, f);
    const expected = `clearance ${clearance[f].toFixed(3)} m (${pairs[f][0]} to ${pairs[f][1]})`;
    if (shown.text !== expected) failures.push(`frame ${f}: the overlay reads "${shown.text}", not "${expected}"`);
    if (shown.below !== isBelow(f)) failures.push(`frame ${f}: "below margin" ${shown.below ? 'shown' : 'not shown'}`);
  }
  // The closest pair in red: an obstacle of the pair at a frame below the margin.
  const obstacle = belowFrame >= 0 && scene.collision.obstacles.find((o) => pairs[belowFrame].includes(o.name));
  if (obstacle) {
    const centre = [obstacle.center[0], obstacle.center[1], (obstacle.z_min + obstacle.z_max) / 2];
    const at = async (f) => {
      await page.evaluate((frame) => window.ccmaView.setFrame(frame), f);
      const img = await shot();
      return redNear(img, await page.evaluate((p) => window.ccmaView.projectToScreen(p), centre));
    };
    const red = await at(belowFrame);
    const redWhenClear = clearFrame >= 0 ? await at(clearFrame) : false;
    Object.assign(result, { pair_obstacle_red_below: red, pair_obstacle_red_clear: redWhenClear });
    if (!red) failures.push(`frame ${belowFrame}: obstacle '${obstacle.name}' of the closest pair not drawn red`);
    if (redWhenClear) failures.push(`frame ${clearFrame}: obstacle '${obstacle.name}' drawn red above the margin`);
  }
  await page.evaluate(() => window.ccmaView.setFrame(0));
  return failures;
}

export async function checkCollision(page, shot, drawnNear, result) {
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ccma-scene').textContent));
  return [...await checkDrawn(page, shot, drawnNear, scene, result), ...await checkOverlay(page, shot, scene, result)];
}
