// ccma's 3D viewer: the page `ccma view` writes. Reads the scene from
// <script id="ccma-scene"> (viewer/scene_format.md), draws the mechanism with
// three.js, animates its frames, and exposes window.ccmaView for tests.
// Nothing is fetched: the page's CSP forbids it, and nothing here asks.
import { Color, Object3D, Scene, Vector3, WebGLRenderer } from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { buildCollision, clearanceAt } from './collision.js';
import { COLORS, css } from './colors.js';
import { deflectionColors, fadeRigid, showDeflected } from './deflection.js';
import { effortColors } from './efforts.js';
import { loadColors } from './loads.js';
import { buildMechanism, sceneSize } from './mechanism.js';
import { buildOverlay, showError } from './overlay.js';
import { buildPaths } from './paths.js';
import { checkScene } from './scene_check.js';
import { addGround, addLights, FOV, frameCamera, gridStep, sceneBox } from './stage.js';
import { buildWorkspace, rampColor } from './workspace.js';

Object3D.DEFAULT_UP.set(0, 0, 1);  // the world is z up; OrbitControls orbits about this axis

function readScene() {
  const tag = document.getElementById('ccma-scene');
  if (!tag) throw new Error('no <script id="ccma-scene"> in the page');
  let scene;
  try {
    scene = JSON.parse(tag.textContent);
  } catch (error) {
    throw new Error('the scene is not JSON: ' + error.message);
  }
  const problems = checkScene(scene);
  if (problems.length) throw new Error('the scene is not valid: ' + problems.join('; '));
  return scene;
}

// Index of the last frame whose time is <= t (times do not decrease).
function frameAt(times, t) {
  let lo = 0, hi = times.length - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}

function start() {
  const scene = readScene();
  const frames = scene.frames;
  const n = frames.time.length;
  Object.assign(document.body.style, { margin: '0', overflow: 'hidden', background: css(COLORS.background) });

  // preserveDrawingBuffer: the picture stays readable after it is shown
  // (screenshots, canvas.toDataURL, the browser test's pixel checks).
  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(COLORS.background);
  // Pinned to the window, so that nothing else in the page can move it away
  // from where projectToScreen says things are.
  Object.assign(renderer.domElement.style, { position: 'fixed', left: '0', top: '0', display: 'block' });
  document.body.append(renderer.domElement);

  const world = new Scene();
  world.background = new Color(COLORS.background);
  addLights(world);
  const size = sceneSize(scene);
  const mechanism = buildMechanism(scene, world, size);
  buildPaths(scene, world, size);
  const cloud = buildWorkspace(scene, world, size, FOV, renderer.getPixelRatio());
  const collision = buildCollision(scene, world);
  mechanism.pose(frames, 0);
  if (collision) collision.pose(0);
  // Colouring by effort (`--dynamics`): bodies no limited actuator drives keep these.
  const ownColors = mechanism.bodyColors().map((c) => c.map((x) => x / 255));
  // The loaded shape (`--deflection`): a second copy over the faded rigid one.
  const deflected = scene.deflection ? buildMechanism(scene, world, size) : null;
  if (deflected) {
    showDeflected(scene, deflected);
    fadeRigid(mechanism);
  }
  const box = sceneBox(scene, mechanism, collision);
  if (deflected) box.union(sceneBox(scene, deflected));
  const radius = box.getSize(new Vector3()).length() / 2;
  const step = gridStep(radius);
  addGround(world, box, step);

  const { camera, target } = frameCamera(box, window.innerWidth / window.innerHeight);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();

  const ui = buildOverlay(scene, n, step, cloud);
  let current = 0;
  let playing = false;
  let clock = 0;  // animation time [s] since frame 0
  const t0 = frames.time[0];
  const span = frames.time[n - 1] - t0;
  // Recordings whose times do not advance play at 10 frames per second.
  const timeOf = (f) => (span > 0 ? frames.time[f] - t0 : f / 10);

  // Rendered on demand: after a new frame, an orbit, a resize.
  const render = () => {
    renderer.render(world, camera);
    if (collision) collision.placeLabels(camera, window.innerWidth, window.innerHeight);
  };
  const show = (f) => {
    current = Math.min(Math.max(0, Math.round(Number(f) || 0)), n - 1);
    mechanism.pose(frames, current);
    if (collision) collision.pose(current);
    if (ui.clearance) ui.clearance(clearanceAt(scene, current));
    if (scene.loads) {
      mechanism.paint(loadColors(scene, current));
      ui.load(current);
    }
    if (scene.efforts) {
      mechanism.paint(effortColors(scene, current, ownColors), { shells: true });
      ui.effort(current);
    }
    ui.slider.value = String(current);
    ui.label.textContent = `t = ${frames.time[current].toFixed(2)} s (frame ${current + 1}/${n})`;
    ui.badge.style.visibility = frames.flags && frames.flags[current] === 1 ? 'visible' : 'hidden';
    render();
  };
  const setPlaying = (on) => {
    playing = on && n > 1;
    ui.play.textContent = playing ? 'pause' : 'play';
    if (playing) clock = current === n - 1 ? 0 : timeOf(current);  // from the end: start over
  };

  // The slider stops the animation and shows the frame (dragging fires
  // 'input', keyboard and programmatic changes may fire only 'change').
  for (const type of ['input', 'change']) {
    ui.slider.addEventListener(type, () => { setPlaying(false); show(ui.slider.value); });
  }
  ui.play.addEventListener('click', () => setPlaying(!playing));
  controls.addEventListener('change', render);
  // The unreachable points: a switch in the legend, or the key "u".
  const showUnreachable = (on) => {
    cloud.setVisible('unreachable', on);
    ui.unreachable.checked = on;
    render();
  };
  if (ui.unreachable) {
    ui.unreachable.addEventListener('change', () => showUnreachable(ui.unreachable.checked));
    window.addEventListener('keydown', (e) => {
      if (e.key === 'u' && !e.ctrlKey && !e.metaKey && !e.altKey) showUnreachable(!ui.unreachable.checked);
    });
  }
  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    render();
  });

  // Playback in the recording's own time, looping.
  let last = performance.now();
  const tick = (now) => {
    const dt = Math.min((now - last) / 1000, 0.25);  // a hidden tab does not jump ahead
    last = now;
    if (playing) {
      clock += dt;
      const end = span > 0 ? span : (n - 1) / 10;
      if (clock > end) clock = 0;
      const f = span > 0 ? frameAt(frames.time, t0 + clock) : Math.floor(clock * 10);
      if (f !== current) show(f);
    }
    requestAnimationFrame(tick);
  };
  show(0);
  requestAnimationFrame(tick);

  // Test hooks (viewer/js/test/browser_test.mjs); positions in CSS pixels.
  const toScreen = (p) => {
    const v = new Vector3(...p).project(camera);
    return [((v.x + 1) / 2) * window.innerWidth, ((1 - v.y) / 2) * window.innerHeight];
  };
  window.ccmaView = {
    ready: true,
    frames: n,
    get frame() { return current; },
    setFrame: (f) => show(f),
    endEffectorWorld: () => mechanism.endEffectorWorld().toArray(),
    projectToScreen: toScreen,
    bodyPointsScreen: () => mechanism.bodyPointsWorld().map((p) => toScreen(p.toArray())),
    background: [16, 8, 0].map((shift) => (COLORS.background >> shift) & 255),  // sRGB, as on screen
    showMechanism: (visible) => { mechanism.setVisible(visible); if (deflected) deflected.setVisible(visible); render(); },
    // The bodies' meshes (`ccma view --meshes`): how many, shown or hidden,
    // their vertex centroids in the world.
    meshes: mechanism.meshCount,
    showMeshes: (visible) => { mechanism.setMeshesVisible(visible); render(); },
    meshCentroidsWorld: () => mechanism.meshCentroidsWorld().map((p) => p.toArray()),
    // The workspace cloud: counts, visibility, reachable points on screen and
    // the ramp's colours (sRGB 0..255) that they are drawn in.
    workspace: cloud && { points: cloud.points, reachable: cloud.reachable, sigmaMin: [cloud.range.lo, cloud.range.hi] },
    showWorkspace: (visible) => { if (cloud) cloud.setVisible('all', visible); render(); },
    workspacePointsScreen: (max = 400) => (cloud ? cloud.reachableSample(max).map(toScreen) : []),
    workspaceRamp: Array.from({ length: 33 }, (_, i) => rampColor(i / 32).map((c) => Math.round(255 * c))),
    // The collision shapes: how many of each, shown or hidden (or shape i alone).
    collision: collision && collision.counts,
    showCollision: (visible, only = -1) => { if (collision) collision.setVisible(visible, only); render(); },
    // Colouring by load: each body's colour as drawn and as the scene's
    // loads at frame f give it (sRGB 0..255).
    loads: scene.loads ? { max: scene.loads.max, masses: scene.loads.masses } : null,
    bodyColors: () => mechanism.bodyColors(),
    shellColors: () => mechanism.shellColors(),
    // The loaded shape (`--deflection`): its bodies' points on screen and
    // colours as drawn, and the colours the scene's deflections give them (sRGB 0..255).
    deflection: scene.deflection ? { scale: scene.deflection.scale, max: scene.deflection.max } : null,
    deflectedPointsScreen: () => (deflected ? deflected.bodyPointsWorld().map((p) => toScreen(p.toArray())) : []),
    deflectedColors: () => (deflected ? deflected.bodyColors() : null),
    deflectionColors: () => (scene.deflection ? deflectionColors(scene).map((c) => c.map((x) => Math.round(255 * x))) : null),
    showRigid: (visible) => { mechanism.setVisible(visible); render(); },
    loadColorsAt: (f) => (scene.loads ? loadColors(scene, f).map((c) => c.map((x) => Math.round(255 * x))) : null),
    // Colouring by effort: the colours the scene's efforts give the bodies at frame f (sRGB 0..255).
    efforts: scene.efforts ? { max: scene.efforts.max, actuators: scene.efforts.actuators.length } : null,
    effortColorsAt: (f) => (scene.efforts
      ? effortColors(scene, f, ownColors).map((c) => c.map((x) => Math.round(255 * x))) : null),
  };
}

try {
  start();
} catch (error) {
  window.ccmaViewError = String(error && error.message ? error.message : error);
  showError(window.ccmaViewError);
  console.error('ccma view:', window.ccmaViewError);
}
