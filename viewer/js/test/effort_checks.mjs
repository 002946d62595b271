// The browser test's checks of a page coloured by effort (`ccma view
// --trajectory=T.csv --dynamics=D.csv`), used by browser_test.mjs when the
// page's scene has "efforts":
//   s. the legend shows the effort scale: "effort / limit", a colour bar,
//      "beyond the limit", and names every limited actuator;
//   t. at frame 0, at the frame of the page's largest share and at the last
//      frame, the body each limited actuator drives (its capsules and, for a
//      base, its disc or body box) has the colour of the largest share on it
//      (the load map from 0 to 1, copied in load_checks.mjs, so the page's
//      own colour function is checked too; magenta beyond 1, grey where the row
//      did not assemble), and every other body keeps the colour it has
//      without efforts;
//   u. the bar reads the frame's largest share and its actuator, and
//      "beyond limit" exactly on the frames where a share is above 1.
// Returns a list of failures; adds its numbers to `result`.
import { mapColor } from './load_checks.mjs';

const BEYOND = [217, 70, 239];
const GREY = [139, 146, 156];

function expectedShareColor(share) {
  if (share < 0) return GREY;
  if (share > 1 + 1e-9) return BEYOND;
  return mapColor(share);
}

const near = (a, b) => a && b && a.every((x, k) => Math.abs(x - b[k]) <= 2);

async function checkFrame(page, scene, f, own, failures) {
  const { actuators, shares } = scene.efforts;
  await page.evaluate((k) => window.ccmaView.setFrame(k), f);
  const drawn = await page.evaluate(() => window.ccmaView.bodyColors());
  const shells = await page.evaluate(() => window.ccmaView.shellColors());
  const top = new Map();
  actuators.forEach((a, i) => {
    if (a.body >= 0 && (!top.has(a.body) || shares[f][i] > top.get(a.body))) top.set(a.body, shares[f][i]);
  });
  scene.bodies.forEach((body, b) => {
    const want = top.has(b) ? expectedShareColor(top.get(b)) : own[b];
    if (!near(drawn[b], want)) failures.push(`frame ${f}: body ${body.name} drawn ${drawn[b]}, not ${want.map(Math.round)}`);
    if (top.has(b) && shells[b] && !near(shells[b], want)) {
      failures.push(`frame ${f}: the base ${body.name}'s shape drawn ${shells[b]}, not ${want.map(Math.round)}`);
    }
  });
  const row = shares[f];
  const best = row.reduce((a, x, i) => (x > row[a] ? i : a), 0);
  const text = row[best] < 0 ? 'effort: not assembled'
                             : `largest effort ${Math.round(100 * row[best])} % of its limit (${actuators[best].name})`;
  const bar = await page.evaluate(() => document.getElementById('ccma-effort')?.textContent || '');
  if (bar !== text) failures.push(`frame ${f}: the bar reads "${bar}", not "${text}"`);
  const status = await page.evaluate(() => {
    const s = document.getElementById('ccma-effort-status');
    return Boolean(s && s.style.display !== 'none');
  });
  if (status !== row[best] > 1 + 1e-9) failures.push(`frame ${f}: "beyond limit" ${status ? 'shown' : 'not shown'}`);
  return row[best];
}

export async function checkEfforts(page, result) {
  const failures = [];
  const scene = await page.evaluate(() => JSON.parse(document.getElementById('ccma-scene').textContent));
  const legend = await page.evaluate(() => ({
    text: document.getElementById('ccma-effort-legend')?.textContent || '',
    scale: Boolean(document.getElementById('ccma-effort-scale')),
  }));
  if (!legend.text.startsWith('effort / limit')) failures.push(`the effort legend reads "${legend.text}"`);
  if (!legend.text.includes('beyond the limit')) failures.push('the effort legend does not say "beyond the limit"');
  if (!legend.scale) failures.push('no effort colour bar #ccma-effort-scale');
  for (const a of scene.efforts.actuators) {
    if (!legend.text.includes(a.name)) failures.push(`the effort legend does not name ${a.name}`);
  }
  // The colours the bodies have without efforts: a link's grey, a base's kind.
  const own = scene.bodies.map((b) => ({ omni: [74, 144, 217], differential: [22, 163, 148], legged: [180, 83, 9] }[b.kind]
                                        || [125, 141, 163]));
  const { shares } = scene.efforts;
  const n = shares.length;
  const peak = shares.reduce((best, row, f) => (Math.max(...row) > Math.max(...shares[best]) ? f : best), 0);
  const frames = [...new Set([0, peak, n - 1])];
  const seen = [];
  for (const f of frames) seen.push(await checkFrame(page, scene, f, own, failures));
  await page.evaluate(() => window.ccmaView.setFrame(0));
  Object.assign(result, { effort_max: scene.efforts.max, effort_frames_checked: frames,
                          effort_shares_checked: seen.map((x) => Number(x.toFixed(4))) });
  return failures;
}
