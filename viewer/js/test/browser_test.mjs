// Opens a page written by `ccma view` in headless Chromium (Debian's, driven
// by playwright-core) and checks it the way a user would see it:
//   a. no console error and no page error;
//   b. no network request but the page's own file;
//   c. the viewer is ready with a WebGL canvas and its controls (play button,
//      slider over every frame, time label);
//   d. the mechanism is drawn: at the screen positions of the body points the
//      picture differs from the same view with the mechanism hidden (so
//      neither the grid, the paths nor a workspace cloud count), and >= 0.2%
//      of all pixels do; >= 1% of the pixels differ from the background colour;
//   g. (pages of `ccma view --workspace`) the cloud is drawn: with the
//      unreachable points switched off (the legend's checkbox, clicked),
//      near the screen positions of >= 60% of the reachable points (a sample
//      of <= 400) the picture differs from the same view without the cloud
//      and has a colour of the sigma_min ramp, and >= 0.2% of all pixels
//      have such a colour where the cloud-less view does not; the checkbox
//      changes the picture (off and on again);
//   e. (--expect-animation) moving the time slider through the UI moves the
//      end-effector and the picture; play advances the frames, pause stops them;
//   h, i. (pages with meshes, `ccma view --meshes`) the meshes are drawn
//      where the scene puts them: test/mesh_checks.mjs;
//   j, k, l. (pages with collision shapes: `collision:`, `obstacles:`,
//      `--obstacles`) every shape drawn where the scene puts it, the overlay's
//      clearance and "below margin" per frame, the closest pair in red:
//      test/collision_checks.mjs;
//   m, n, o. (pages coloured by load, `ccma view --color_by=load`) the load
//      legend, each body in its load's colour, the bar's load line:
//      test/load_checks.mjs;
//   p, q, r. (pages with a loaded shape, `ccma view --deflection`) the
//      legend's scale, each loaded body in its deflection's colour, the
//      loaded copy at the scene's poses: test/deflection_checks.mjs;
//   s, t, u. (pages coloured by effort, `ccma view --dynamics`) the effort
//      legend, each driven body (and base shape) in its share's colour, the
//      bar's effort line: test/effort_checks.mjs;
//   f. (--screenshot OUT.png) saves the 1200x800 picture at frame 0 (or at
//      --screenshot-frame N), also of a failed page.
// Prints one JSON line; exit 0 when every check passes, 1 otherwise, 77 when
// Chromium is not installed (CTest reports that as skipped, with the reason).
//   node test/browser_test.mjs --html PAGE.html [--expect-animation]
//        [--screenshot OUT.png] [--screenshot-frame N]
import { existsSync, writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';
import { checkCollision } from './collision_checks.mjs';
import { checkDeflection } from './deflection_checks.mjs';
import { checkEfforts } from './effort_checks.mjs';
import { checkLoads } from './load_checks.mjs';
import { checkMeshes } from './mesh_checks.mjs';
import { decodePng } from './png.mjs';

const CHROMIUM = '/usr/bin/chromium';
const args = process.argv.slice(2);
const option = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
const html = option('--html');
if (!html) { console.error('usage: browser_test.mjs --html PAGE.html [--expect-animation] [--screenshot OUT.png]'); process.exit(2); }
if (!existsSync(CHROMIUM)) { console.log('SKIP: chromium not installed (apt-get install chromium)'); process.exit(77); }

const url = pathToFileURL(resolve(html)).href;
const failures = [];
const result = { page: html };
const browser = await chromium.launch({
  executablePath: CHROMIUM,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
         '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  const errors = [], requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => { if (r.url() !== url && !/^(data|blob):/.test(r.url())) requests.push(r.url()); });
  await page.goto(url, { waitUntil: 'load' });
  // Ready, or the viewer reported a problem, or a script failed outright.
  await Promise.race([
    page.waitForFunction(() => (window.ccmaView && window.ccmaView.ready) || window.ccmaViewError, null,
                         { timeout: 20000 }),
    page.waitForEvent('pageerror', { timeout: 20000 }),
  ]).catch(() => failures.push('the viewer did not become ready within 20 s'));
  const pageError = await page.evaluate(() => window.ccmaViewError);
  if (pageError) failures.push('the viewer reported: ' + pageError);
  const view = await page.evaluate(() => {
    const canvas = document.querySelector('canvas');
    const slider = document.getElementById('ccma-slider');
    return {
      ready: Boolean(window.ccmaView && window.ccmaView.ready),
      frames: window.ccmaView ? window.ccmaView.frames : 0,
      // The renderer's own context (getContext returns it again for its type).
      webgl: Boolean(canvas && (canvas.getContext('webgl2') || canvas.getContext('webgl'))),
      play: Boolean(document.getElementById('ccma-play')),
      sliderMax: slider ? Number(slider.max) : -1,
      time: document.getElementById('ccma-time')?.textContent || '',
    };
  });
  Object.assign(result, { frames: view.frames, webgl: view.webgl, time_label: view.time });
  if (view.ready && !view.webgl) failures.push('no WebGL canvas');
  if (view.ready) {
    if (!view.play) failures.push('no play button #ccma-play');
    if (view.sliderMax !== view.frames - 1) failures.push(`the slider's max is ${view.sliderMax}, not ${view.frames - 1}`);
    if (!/^t = -?\d+\.\d+ s \(frame \d+\/\d+\)$/.test(view.time)) failures.push(`time label "${view.time}"`);
  }

  // d. Pixels at the body points differ from the same view without the bodies.
  const shot = async () => decodePng(await page.screenshot({ type: 'png' }));
  const differ = (a, b, x, y) => {
    const p = a.at(x, y), q = b.at(x, y);
    return Math.abs(p[0] - q[0]) + Math.abs(p[1] - q[1]) + Math.abs(p[2] - q[2]) > 30;
  };
  const drawnNear = (a, b, [x, y]) => {
    for (let dx = -3; dx <= 3; ++dx) for (let dy = -3; dy <= 3; ++dy) {
      const px = Math.round(x) + dx, py = Math.round(y) + dy;
      if (px >= 0 && py >= 0 && px < a.width && py < a.height && differ(a, b, px, py)) return true;
    }
    return false;
  };
  const hasCloud = view.ready && await page.evaluate(() => Boolean(window.ccmaView.workspace));
  if (hasCloud) await page.evaluate(() => window.ccmaView.showWorkspace(false));  // d. sees the mechanism alone
  if (view.ready) {
    const first = await shot();
    await page.evaluate(() => window.ccmaView.showMechanism(false));
    const empty = await shot();
    await page.evaluate(() => window.ccmaView.showMechanism(true));
    const points = await page.evaluate(() => window.ccmaView.bodyPointsScreen());
    const onScreen = points.filter(([x, y]) => x >= 0 && y >= 0 && x < first.width && y < first.height);
    const drawn = onScreen.filter((p) => drawnNear(first, empty, p)).length;
    let changed = 0;
    for (let y = 0; y < first.height; y += 2) for (let x = 0; x < first.width; x += 2) changed += differ(first, empty, x, y) ? 1 : 0;
    const fraction = changed / ((first.width / 2) * (first.height / 2));
    // Anything drawn at all (mechanism, grid, paths) against the clear colour,
    // read back from the canvas itself (which needs preserveDrawingBuffer).
    const { background, png } = await page.evaluate(() => ({
      background: window.ccmaView.background,
      png: document.querySelector('canvas').toDataURL('image/png'),
    }));
    const canvas = decodePng(Buffer.from(png.slice(png.indexOf(',') + 1), 'base64'));
    let drawnPixels = 0;
    for (let i = 0; i < canvas.data.length; i += 4) {
      const d = Math.abs(canvas.data[i] - background[0]) + Math.abs(canvas.data[i + 1] - background[1]) +
                Math.abs(canvas.data[i + 2] - background[2]);
      drawnPixels += d > 30 ? 1 : 0;
    }
    const nonBackground = drawnPixels / (canvas.width * canvas.height);
    Object.assign(result, { body_points: points.length, body_points_drawn: drawn, mechanism_pixels: Number(fraction.toFixed(4)),
                            non_background_pixels: Number(nonBackground.toFixed(4)) });
    if (nonBackground < 0.01) failures.push(`only ${(100 * nonBackground).toFixed(2)}% of the canvas differs from the background`);
    if (onScreen.length < points.length * 0.9) failures.push(`only ${onScreen.length} of ${points.length} body points on screen`);
    if (drawn < onScreen.length * 0.9) failures.push(`only ${drawn} of ${onScreen.length} body points drawn`);
    if (fraction < 0.002) failures.push(`the mechanism covers only ${(100 * fraction).toFixed(2)}% of the picture`);

    // g. The workspace cloud, against the same view without it.
    if (hasCloud) {
      await page.evaluate(() => window.ccmaView.showWorkspace(true));
      const full = await shot();
      const toggle = await page.$('#ccma-unreachable');
      if (toggle) await toggle.click();  // off: the reachable points alone
      const cloud = await shot();
      if (toggle) {
        let toggled = 0;
        for (let i = 0; i < full.data.length; i += 4) toggled += full.data[i] !== cloud.data[i] ? 1 : 0;
        result.unreachable_toggle_pixels = toggled;
        if (toggled < 20) failures.push('the unreachable checkbox did not change the picture');
        await toggle.click();  // on again, as the page starts
      }
      const ws = await page.evaluate(() => ({ info: window.ccmaView.workspace, ramp: window.ccmaView.workspaceRamp,
                                               points: window.ccmaView.workspacePointsScreen(400) }));
      const rampLike = (img, x, y) => {
        const p = img.at(x, y);
        return ws.ramp.some((c) => Math.abs(p[0] - c[0]) + Math.abs(p[1] - c[1]) + Math.abs(p[2] - c[2]) <= 45);
      };
      const cloudAt = (x, y) => differ(cloud, first, x, y) && rampLike(cloud, x, y);
      const near = ([x, y]) => {
        for (let dx = -2; dx <= 2; ++dx) for (let dy = -2; dy <= 2; ++dy) {
          const px = Math.round(x) + dx, py = Math.round(y) + dy;
          if (px >= 0 && py >= 0 && px < cloud.width && py < cloud.height && cloudAt(px, py)) return true;
        }
        return false;
      };
      const visible = ws.points.filter(([x, y]) => x >= 0 && y >= 0 && x < cloud.width && y < cloud.height);
      const drawnPoints = visible.filter(near).length;
      let rampPixels = 0;
      for (let y = 0; y < cloud.height; y += 2) for (let x = 0; x < cloud.width; x += 2) rampPixels += cloudAt(x, y) ? 1 : 0;
      const rampFraction = rampPixels / ((cloud.width / 2) * (cloud.height / 2));
      Object.assign(result, { workspace_points: ws.info.points, workspace_reachable: ws.info.reachable,
                              workspace_sampled: visible.length, workspace_sampled_drawn: drawnPoints,
                              workspace_ramp_pixels: Number(rampFraction.toFixed(4)) });
      if (ws.info.reachable === 0) {  // only the grey points: something must still appear
        let changed = 0;
        for (let y = 0; y < cloud.height; y += 2) for (let x = 0; x < cloud.width; x += 2) changed += differ(cloud, first, x, y) ? 1 : 0;
        if (changed < 0.0005 * (cloud.width / 2) * (cloud.height / 2)) failures.push('the (unreachable) workspace cloud is not drawn');
      } else {
        if (visible.length < ws.points.length * 0.9) failures.push(`only ${visible.length} of ${ws.points.length} workspace points on screen`);
        if (drawnPoints < visible.length * 0.6) failures.push(`only ${drawnPoints} of ${visible.length} workspace points drawn in the sigma_min colours`);
        if (rampFraction < 0.002) failures.push(`the workspace cloud covers only ${(100 * rampFraction).toFixed(2)}% of the picture`);
      }
    }

    // h, i. The bodies' meshes, where the scene puts them.
    if (await page.evaluate(() => window.ccmaView.meshes > 0)) failures.push(...await checkMeshes(page, shot, drawnNear, result));
    // j, k, l. The collision shapes and the clearance, as the scene has them.
    if (await page.evaluate(() => Boolean(window.ccmaView.collision))) {
      failures.push(...await checkCollision(page, shot, drawnNear, result));
    }

    // m, n, o. The links coloured by load, the legend and the bar's line.
    // (Asked of the scene, not of the page: a page that ignores the loads fails.)
    const hasLoads = await page.evaluate(() => Boolean(JSON.parse(document.getElementById('ccma-scene').textContent).loads));
    if (hasLoads) failures.push(...await checkLoads(page, shot, result));
    // p, q, r. The loaded shape: its legend, colours and poses.
    const hasDeflection = await page.evaluate(() => Boolean(JSON.parse(document.getElementById('ccma-scene').textContent).deflection));
    if (hasDeflection) failures.push(...await checkDeflection(page, result));
    // s, t, u. The actuators coloured by effort, the legend and the bar's line.
    const hasEfforts = await page.evaluate(() => Boolean(JSON.parse(document.getElementById('ccma-scene').textContent).efforts));
    if (hasEfforts) failures.push(...await checkEfforts(page, result));

    // e. The slider (through the UI) and play move the end-effector.
    if (args.includes('--expect-animation') && view.frames < 2) {
      failures.push(`expected an animation, got ${view.frames} frame(s)`);
    } else if (args.includes('--expect-animation')) {
      const before = await page.evaluate(() => window.ccmaView.endEffectorWorld());
      // The frame whose end-effector is farthest from frame 0's (a path may
      // come back to its start), chosen from the page's own scene data.
      // (The last frame when the scene has no tracked path for every frame.)
      const target = await page.evaluate(() => {
        const tracked = JSON.parse(document.getElementById('ccma-scene').textContent).paths?.tracked || [];
        let best = window.ccmaView.frames - 1, distance = -1;
        if (tracked.length === window.ccmaView.frames) tracked.forEach((p, i) => {
          const d = Math.hypot(p[0] - tracked[0][0], p[1] - tracked[0][1], p[2] - tracked[0][2]);
          if (d > distance) { distance = d; best = i; }
        });
        return Math.max(best, 0);
      });
      await page.locator('#ccma-slider').fill(String(target));  // as a user drags it: input events
      const after = await page.evaluate(() => ({ ee: window.ccmaView.endEffectorWorld(), frame: window.ccmaView.frame }));
      const moved = Math.hypot(after.ee[0] - before[0], after.ee[1] - before[1], after.ee[2] - before[2]);
      const second = await shot();
      let pixels = 0;
      for (let i = 0; i < first.data.length; i += 4) pixels += first.data[i] !== second.data[i] ? 1 : 0;
      Object.assign(result, { slider_frame: after.frame, end_effector_moved_m: Number(moved.toFixed(6)), pixels_changed: pixels });
      if (after.frame !== target) failures.push(`the slider went to frame ${after.frame}, not ${target}`);
      if (!(moved > 1e-4)) failures.push(`the end-effector moved ${moved} m when the slider moved`);
      if (pixels < 100) failures.push('the picture did not change when the slider moved');
      // Play (as a click) advances in the recording's time: wait up to the
      // time of frame 1 plus a second, at least 0.5 s; pause (a click) stops.
      const wait = await page.evaluate(() => {
        const t = JSON.parse(document.getElementById('ccma-scene').textContent).frames.time;
        return Math.min(10000, Math.max(500, 1000 * (t[1] - t[0]) + 1000));
      });
      await page.evaluate(() => window.ccmaView.setFrame(0));
      await page.click('#ccma-play');
      await page.waitForTimeout(500);
      await page.waitForFunction(() => window.ccmaView.frame !== 0, null, { timeout: wait }).catch(() => {});
      const playing = await page.evaluate(() => window.ccmaView.frame);
      const pauseLabel = await page.textContent('#ccma-play');
      await page.click('#ccma-play');
      const paused = await page.evaluate(() => window.ccmaView.frame);
      await page.waitForTimeout(300);
      const still = await page.evaluate(() => window.ccmaView.frame);
      result.frame_after_play = playing;
      if (playing === 0) failures.push('play did not advance the frames');
      if (pauseLabel !== 'pause') failures.push(`while playing, the button reads "${pauseLabel}", not "pause"`);
      if (still !== paused) failures.push(`pause did not stop the frames (${paused} -> ${still})`);
    }
  }
  // f. The picture at the chosen frame (also of a page that failed: it shows why).
  const target = option('--screenshot');
  if (target) {
    if (view.ready) await page.evaluate((f) => window.ccmaView.setFrame(f), Number(option('--screenshot-frame') || 0));
    writeFileSync(target, await page.screenshot({ type: 'png' }));
    result.screenshot = target;
  }
  if (errors.length) failures.push('console errors: ' + errors.join(' | '));
  if (requests.length) failures.push('network requests: ' + requests.join(' '));
  Object.assign(result, { console_errors: errors.length, requests: requests.length });
} finally {
  await browser.close();
}
result.ok = failures.length === 0;
result.failures = failures;
console.log(JSON.stringify(result));
process.exit(failures.length ? 1 : 0);
