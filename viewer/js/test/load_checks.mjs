// The browser test's checks of a page coloured by load (`ccma view
// --color_by=load`), used by browser_test.mjs when the page's scene has "loads":
//   m. the legend shows the load scale: "joint load [N]", a colour bar, 0 and
//      the scene's largest load; "no masses in the model" exactly when the
//      scene says so;
//   n. at frame 0 and at the last frame, every body's material has the
//      colour of its load on the map (the map's stops copied here, so the
//      page's own colour function is checked too), and on screen the least
//      loaded body's first capsule is drawn blue-dominant (when it carries at
//      most 5% of the page's largest load; a model without masses: all blue)
//      and the most loaded body's red-dominant (at least 95% of it);
//   o. the bar reads the frame's largest load and its body, and "unbalanced"
//      / "minimum-norm loads" exactly on the frames the scene flags.
// Returns a list of failures; adds its numbers to `result`.
import { rotate } from './mesh_checks.mjs';

const STOPS = [[59, 76, 192], [42, 161, 152], [224, 180, 58], [240, 123, 44], [180, 4, 38]];

// sRGB 0..255 of the map at t in [0, 1], linear between evenly spaced stops.
export function mapColor(t) {
  const x = Math.min(Math.max(t, 0), 1) * (STOPS.length - 1);
  const i = Math.min(Math.floor(x), STOPS.length - 2), f = x - i;
  return [0, 1, 2].map((k) => STOPS[i][k] * (1 - f) + STOPS[i + 1][k] * f);
}

const number = (x) => (x === 0 ? '0' : Number(x.toPrecision(3)).toString());
const add = (a, b) => a.map((x, k) => x + b[k]);

// Screen point of the middle of body b's first capsule at frame f (null without one).
async function capsuleMiddle(page, scene, b, f) {
  const body = scene.bodies[b];
  if (!body.links.length) return null;
  const [i, j] = body.links[0];
  const mid = body.points[i].map((x, k) => (x + body.points[j][k]) / 2);
  const pose = scene.frames.poses[f][b];
  const world = add(pose.slice(0, 3), rotate(pose.slice(3, 7), mid));
  return page.evaluate((p) => window.ccmaView.projectToScreen(p), world);
}

function hueNear(img, [x, y], test) {
  for (let dx = -3; dx <= 3; ++dx) for (let dy = -3; dy <= 3; ++dy) {
    const px = Math.round(x) + dx, py = Math.round(y) + dy;
    if (px >= 0 && py >= 0 && px < img.width && py < img.height && test(img.at(px, py))) return true;
  }
  return false;
}
const red = ([r, g, b]) => r > g + 40 && r > b + 40;
const blue = ([r, g, b]) => b > r + 40 && b > g + 20;

// n and o at frame f.
async function checkFrame(page, shot, scene, f, failures) {
  const loads = scene.loads;
  await page.evaluate((k) => window.ccmaView.setFrame(k), f);
  const drawn = await page.evaluate(() => (window.ccmaView.bodyColors ? window.ccmaView.bodyColors() : null));
  if (!drawn) failures.push('the page gives no body colours (window.ccmaView.bodyColors)');
  if (drawn) loads.body_loads[f].forEach((load, b) => {
    const want = mapColor(loads.max > 0 ? load / loads.max : 0);
    if (want.some((c, k) => Math.abs(c - drawn[b][k]) > 2)) {
      failures.push(`frame ${f}: body ${scene.bodies[b].name} (load ${load} N) drawn ${drawn[b]}, not ${want.map(Math.round)}`);
    }
  });
  const row = loads.body_loads[f];
  // Among the bodies drawn with capsules: the most and the least loaded.
  const drawnBodies = row.map((_, i) => i).filter((i) => scene.bodies[i].links.length > 0);
  const most = drawnBodies.reduce((a, i) => (row[i] > row[a] ? i : a), drawnBodies[0]);
  const least = drawnBodies.reduce((a, i) => (row[i] < row[a] ? i : a), drawnBodies[0]);
  const img = await shot();
  const onScreen = (p) => p && p[0] >= 0 && p[1] >= 0 && p[0] < img.width && p[1] < img.height;
  const leastAt = least === undefined ? null : await capsuleMiddle(page, scene, least, f);
  if (onScreen(leastAt) && row[least] <= 0.05 * loads.max && !hueNear(img, leastAt, blue)) {
    failures.push(`frame ${f}: the least loaded body ${scene.bodies[least].name} is not drawn blue`);
  }
  const mostAt = most === undefined ? null : await capsuleMiddle(page, scene, most, f);
  if (loads.max > 0 && onScreen(mostAt) && row[most] >= 0.95 * loads.max && !hueNear(img, mostAt, red)) {
    failures.push(`frame ${f}: the most loaded body ${scene.bodies[most].name} is not drawn red`);
  }
  const bar = await page.evaluate(() => document.getElementById('ccma-load')?.textContent || '');
  const status = await page.evaluate(() => {
    const s = document.getElementById('ccma-load-status');
    return s && s.style.display !== 'none' ? s.textContent : '';
  });
  const top = row.indexOf(Math.max(...row));
  const text = loads.masses ? `largest load ${number(row[top])} N (${scene.bodies[top].name})` : 'loads: no masses in the model';
  if (bar !== text) failures.push(`frame ${f}: the bar reads "${bar}", not "${text}"`);
  const notes = [loads.balanced[f] === 0 ? 'unbalanced' : '', loads.determinate[f] === 0 ? 'minimum-norm loads' : '']
    .filter(Boolean).join(', ');
  if (status !== notes) failures.push(`frame ${f}: the load status reads "${status}", not "${notes}"`);
  return { most: scene.bodies[most]?.name, least: scene.bodies[least]?.name, status };
}

export async function checkLoads(page, shot, result) {
  const failures = [];
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ccma-scene').textContent));
  const legend = await page.evaluate(() => ({
    text: document.getElementById('ccma-load-legend')?.textContent || '',
    scale: Boolean(document.getElementById('ccma-load-scale')),
    max: document.getElementById('ccma-load-max')?.textContent || '',
    note: document.getElementById('ccma-load-note')?.textContent || '',
  }));
  if (!legend.text.startsWith('joint load [N]')) failures.push(`the load legend reads "${legend.text}"`);
  if (!legend.scale) failures.push('no load colour bar #ccma-load-scale');
  if (legend.max !== number(scene.loads.max)) failures.push(`the scale ends at "${legend.max}", not ${number(scene.loads.max)}`);
  const note = scene.loads.masses ? '' : 'no masses in the model';
  if (legend.note !== note) failures.push(`the legend's note reads "${legend.note}", not "${note}"`);
  const n = scene.frames.time.length;
  const frames = [...new Set([0, n - 1])];
  const seen = [];
  for (const f of frames) seen.push(await checkFrame(page, shot, scene, f, failures));
  await page.evaluate(() => window.ccmaView.setFrame(0));
  Object.assign(result, { load_max: scene.loads.max, load_masses: scene.loads.masses, load_frames_checked: frames,
                          load_most: seen[0].most, load_least: seen[0].least, load_status: seen[0].status });
  return failures;
}
