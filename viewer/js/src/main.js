// ccma's 3D viewer: the page `ccma view` writes. Reads the scene from
// <script id="ccma-scene"> (viewer/scene_format.md), draws the mechanism with
// three.js, animates its frames, and exposes window.ccmaView for tests.
// Nothing is fetched: the page's CSP forbids it, and nothing here asks.
import {
  AmbientLight, Box3, Color, DirectionalLight, GridHelper, HemisphereLight, Object3D, PerspectiveCamera, Scene,
  Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { COLORS } from './colors.js';
import { buildMechanism } from './mechanism.js';
import { buildOverlay, showError } from './overlay.js';
import { buildPaths } from './paths.js';
import { checkScene } from './scene_check.js';

Object3D.DEFAULT_UP.set(0, 0, 1);  // the world is z up (model_format.md)

function readScene() {
  const tag = document.getElementById('ccma-scene');
  if (!tag) throw new Error('no <script id="ccma-scene"> in the page');
  const scene = JSON.parse(tag.textContent);
  const problems = checkScene(scene);
  if (problems.length) throw new Error('the scene is not valid: ' + problems.join('; '));
  return scene;
}

// The ground grid in the xy plane, sized to the mechanism and its paths.
function ground(radius, center) {
  const size = Math.max(0.5, Math.ceil(4 * radius * 2) / 2);
  const grid = new GridHelper(size, Math.round(size / 0.1) || 10, COLORS.gridCenter, COLORS.grid);
  grid.rotation.x = Math.PI / 2;  // GridHelper lies in xz
  grid.position.set(Math.round(center.x * 10) / 10, Math.round(center.y * 10) / 10, 0);
  return grid;
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
  document.body.style.margin = '0';
  document.body.style.overflow = 'hidden';
  document.body.style.background = '#' + COLORS.background.toString(16);

  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(COLORS.background);
  document.body.append(renderer.domElement);

  const world = new Scene();
  world.background = new Color(COLORS.background);
  world.add(new HemisphereLight(0xffffff, 0x8890a0, 1.6));
  world.add(new AmbientLight(0xffffff, 0.4));
  const sun = new DirectionalLight(0xffffff, 1.4);
  sun.position.set(2, -3, 5);
  world.add(sun);

  const mechanism = buildMechanism(scene, world);
  const paths = buildPaths(scene, world);
  mechanism.pose(frames, 0);

  // Frame the camera on the mechanism at frame 0 plus every path point.
  const box = new Box3();
  mechanism.bodyPointsWorld().forEach((p) => box.expandByPoint(p));
  for (const list of [scene.paths?.commanded, scene.paths?.tracked]) (list || []).forEach((p) => box.expandByPoint(new Vector3(...p)));
  (scene.paths?.bases || []).forEach((b) => b.forEach(([x, y]) => box.expandByPoint(new Vector3(x, y, 0))));
  box.expandByPoint(new Vector3(box.min.x, box.min.y, 0));
  const center = box.getCenter(new Vector3());
  const radius = Math.max(box.getSize(new Vector3()).length() / 2, 0.1);
  world.add(ground(radius, center));

  const camera = new PerspectiveCamera(40, window.innerWidth / window.innerHeight, radius / 100, radius * 100);
  const distance = radius / Math.sin((40 * Math.PI) / 360) * 1.3;
  camera.position.copy(center).add(new Vector3(0.55, -0.75, 0.5).normalize().multiplyScalar(distance));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(center);
  controls.update();

  const ui = buildOverlay(scene, n, Boolean(scene.paths));
  let current = 0;
  let playing = false;
  let clock = 0;  // animation time [s] since frame 0
  const t0 = frames.time[0];
  const span = frames.time[n - 1] - t0;
  // Recordings whose times do not advance play at 10 frames per second.
  const timeOf = (f) => (span > 0 ? frames.time[f] - t0 : f / 10);

  const render = () => renderer.render(world, camera);
  const show = (f) => {
    current = Math.min(Math.max(0, Math.round(f)), n - 1);
    mechanism.pose(frames, current);
    ui.slider.value = String(current);
    ui.label.textContent = `t = ${frames.time[current].toFixed(2)} s (frame ${current + 1}/${n})`;
    ui.badge.style.visibility = frames.flags && frames.flags[current] === 1 ? 'visible' : 'hidden';
    render();
  };

  ui.slider.addEventListener('input', () => { playing = false; ui.play.textContent = 'play'; show(Number(ui.slider.value)); });
  ui.play.addEventListener('click', () => {
    playing = !playing;
    ui.play.textContent = playing ? 'pause' : 'play';
    if (playing) clock = current === n - 1 ? 0 : timeOf(current);
  });
  controls.addEventListener('change', render);
  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    render();
  });

  let last = performance.now();
  const tick = (now) => {
    const dt = Math.min((now - last) / 1000, 0.25);
    last = now;
    if (playing && n > 1) {
      clock += dt;
      const end = span > 0 ? span : (n - 1) / 10;
      if (clock > end) clock = 0;  // loop
      const f = span > 0 ? frameAt(frames.time, t0 + clock) : Math.floor(clock * 10);
      if (f !== current) show(f);
    }
    requestAnimationFrame(tick);
  };
  show(0);
  requestAnimationFrame(tick);

  const toScreen = (p) => {
    const v = new Vector3(...p).project(camera);
    return [(v.x + 1) / 2 * window.innerWidth, (1 - v.y) / 2 * window.innerHeight];
  };
  const bg = new Color(COLORS.background);
  window.ccmaView = {
    ready: true,
    frames: n,
    get frame() { return current; },
    setFrame: (f) => show(f),
    endEffectorWorld: () => mechanism.endEffectorWorld().toArray(),
    projectToScreen: toScreen,
    bodyPointsScreen: () => mechanism.bodyPointsWorld().map((p) => toScreen(p.toArray())),
    background: [Math.round(bg.r * 255), Math.round(bg.g * 255), Math.round(bg.b * 255)],
    showMechanism: (visible) => { mechanism.setVisible(visible); render(); },
  };
}

try {
  start();
} catch (error) {
  window.ccmaViewError = String(error && error.message ? error.message : error);
  showError(window.ccmaViewError);
  console.error('ccma view:', error);
}
