// The browser test's checks of a page with a loaded shape (`ccma view
// --deflection=SCALE`), used by browser_test.mjs when the page's scene has
// "deflection":
//   p. the legend shows the scale ("drawn x SCALE") and the largest
//      deflection in micrometres, millimetres or metres;
//   q. every body of the loaded copy has the colour of its deflection on the
//      load map (the map's stops copied from load_checks.mjs, so the page's
//      own colour function is checked too);
//   r. the loaded copy is drawn at the scene's deflection poses: its body
//      points on screen are where the scene alone puts them (within 1 px),
//      and differ from the rigid copy's where the scene says they moved.
// Returns a list of failures; adds its numbers to `result`.
import { rotate } from './mesh_checks.mjs';

const STOPS = [[59, 76, 192], [42, 161, 152], [224, 180, 58], [240, 123, 44], [180, 4, 38]];

function mapColor(t) {
  const x = Math.min(Math.max(t, 0), 1) * (STOPS.length - 1);
  const i = Math.min(Math.floor(x), STOPS.length - 2), f = x - i;
  return [0, 1, 2].map((k) => STOPS[i][k] * (1 - f) + STOPS[i + 1][k] * f);
}

function lengthText(m) {
  const a = Math.abs(m);
  const [unit, f] = a < 1e-3 ? ['\u00b5m', 1e6] : a < 1 ? ['mm', 1e3] : ['m', 1];
  return `${Number((m * f).toPrecision(3))} ${unit}`;
}

export async function checkDeflection(page, result) {
  const failures = [];
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ccma-scene').textContent));
  const d = scene.deflection;
  // p. The legend.
  const legend = await page.evaluate(() => ({
    scale: document.getElementById('ccma-deflection-scale')?.textContent ?? null,
    max: document.getElementById('ccma-deflection-max')?.textContent ?? null,
  }));
  if (!legend.scale || !legend.scale.includes(`\u00d7 ${Number(d.scale.toPrecision(6))}`)) {
    failures.push(`the legend does not show the scale x ${d.scale}: ${legend.scale}`);
  }
  if (legend.max !== lengthText(d.max)) failures.push(`the legend's largest deflection reads ${legend.max}, not ${lengthText(d.max)}`);
  // q. The colours.
  const drawn = await page.evaluate(() => window.ccmaView.deflectedColors());
  let worst = 0;
  d.body_deflection.forEach((x, b) => {
    const want = mapColor(d.max > 0 ? x / d.max : 0);
    worst = Math.max(worst, ...want.map((c, k) => Math.abs(c - drawn[b][k])));
  });
  result.deflection_color_error = worst;
  if (worst > 3) failures.push(`a loaded body's colour is ${worst} sRGB units off its deflection's`);
  // r. The places.
  const expected = [];
  scene.bodies.forEach((body, b) => body.points.forEach((p) => {
    const pose = d.poses[b];
    expected.push(rotate(pose.slice(3, 7), p).map((x, k) => x + pose[k]));
  }));
  const screen = await page.evaluate((ps) => ps.map((p) => window.ccmaView.projectToScreen(p)), expected);
  const shown = await page.evaluate(() => window.ccmaView.deflectedPointsScreen());
  const rigid = await page.evaluate(() => window.ccmaView.bodyPointsScreen());
  let off = 0, moved = 0;
  screen.forEach((s, i) => {
    off = Math.max(off, Math.hypot(s[0] - shown[i][0], s[1] - shown[i][1]));
    if (Math.hypot(s[0] - rigid[i][0], s[1] - rigid[i][1]) > 2) moved += 1;
  });
  result.deflection_points_off_px = off;
  result.deflection_points_moved = moved;
  if (shown.length !== expected.length || off > 1) failures.push(`the loaded copy is ${off} px off the scene's poses`);
  if (d.max * d.scale > 1e-3 * (scene.scale || 1) && moved === 0) failures.push('the loaded copy lies on the rigid one');
  return failures;
}
