// The workspace map of `ccma view --workspace` (scene.workspace,
// viewer/scene_format.md): one point per sampled end-effector position over
// the mechanism at home. Reachable points are opaque round dots coloured by
// sigma_min (the smallest singular value of dX/du) on a ramp from red
// (near-singular) through orange and gold to green and blue (well
// conditioned); unreachable points smaller, grey and see-through, so that
// the reachable volume reads as a solid and the rest as a haze around it.
// One THREE.Points per class: a million points are two draw calls.
import { BufferAttribute, BufferGeometry, CanvasTexture, Color, Points, PointsMaterial, SRGBColorSpace } from 'three';
import { COLORS, gradientOf, rampAt } from './colors.js';

// The sigma_min ramp, low to high: evenly spaced sRGB stops. Dark enough
// at every stop to stand out on the light background (no pale yellow).
export const RAMP = [0xc62828, 0xef6c00, 0xd4a20a, 0x43a047, 0x1e88e5];

// sRGB [r, g, b] in 0..1 at t in [0, 1] along the ramp (linear between stops).
export function rampColor(t) {
  return rampAt(RAMP, t);
}

// CSS linear-gradient of the ramp, left (low) to right (high).
export function rampGradient() {
  return gradientOf(RAMP);
}

// The sigma_min range of the reachable points [m or rad per control unit]
// ({lo: 0, hi: 0} when nothing is reachable). The colours span [0, hi]:
// red means close to a singularity, whatever the map's own minimum.
export function sigmaRange(workspace) {
  let lo = Infinity, hi = -Infinity;
  workspace.reachable.forEach((r, i) => {
    if (r !== 1) return;
    lo = Math.min(lo, workspace.sigma_min[i]);
    hi = Math.max(hi, workspace.sigma_min[i]);
  });
  return lo <= hi ? { lo, hi } : { lo: 0, hi: 0 };
}

// A round dot with a dark rim (points are squares otherwise); drawn on a
// canvas here, so nothing is fetched.
function dotTexture() {
  const size = 64, canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const g = canvas.getContext('2d');
  g.fillStyle = '#ffffff';
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 1, 0, 2 * Math.PI);
  g.fill();
  g.strokeStyle = 'rgba(0,0,0,0.3)';  // multiplied with the point's colour: a slightly darker rim
  g.lineWidth = 4;
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 4, 0, 2 * Math.PI);
  g.stroke();
  const texture = new CanvasTexture(canvas);
  texture.colorSpace = SRGBColorSpace;
  return texture;
}

// The typical distance between neighbouring samples [m]: the box's volume
// (or area, length over the axes it spans) shared among the points.
function spacing(points, u) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const p of points) for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); }
  const extents = [0, 1, 2].map((k) => hi[k] - lo[k]).filter((e) => e > 1e-9);
  if (!extents.length || points.length < 2) return 0.05 * u;
  const measure = extents.reduce((m, e) => m * e, 1);
  return (measure / points.length) ** (1 / extents.length);
}

// At least `pixels` drawing-buffer pixels across, however far: a dense map
// seen whole would otherwise shrink to specks below a pixel, which the GPU
// drops or aliases into moire.
function minimumSize(material, pixels) {
  material.onBeforeCompile = (shader) => {
    shader.vertexShader = shader.vertexShader.replace(
      '#include <fog_vertex>', `gl_PointSize = max(gl_PointSize, ${pixels.toFixed(1)});\n#include <fog_vertex>`);
  };
  return material;
}

function cloud(points, colors, material) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(Float32Array.from(points.flat()), 3));
  if (colors) geometry.setAttribute('color', new BufferAttribute(colors, 3));
  geometry.computeBoundingSphere();
  return new Points(geometry, material);
}

// Adds the cloud to `root` (nothing without scene.workspace). `u` is the
// scene size (markers), `fov` the camera's vertical field of view [deg]:
// with size attenuation a point's `size` is its diameter / tan(fov / 2).
export function buildWorkspace(scene, root, u, fov, pixelRatio = 1) {
  const ws = scene.workspace;
  if (!ws) return null;
  const range = sigmaRange(ws);
  const step = spacing(ws.points, u);
  const perMetre = 1 / Math.tan((fov * Math.PI) / 360);
  // Dots a third of the spacing: the mechanism inside stays visible between them.
  const diameter = Math.min(Math.max(0.32 * step, 0.004 * u), 0.04 * u);  // [m]
  const texture = dotTexture();
  const reachablePoints = [], unreachablePoints = [], colors = [];
  const color = new Color();
  ws.points.forEach((p, i) => {
    if (ws.reachable[i] !== 1) { unreachablePoints.push(p); return; }
    reachablePoints.push(p);
    const t = range.hi > 0 ? ws.sigma_min[i] / range.hi : 0;
    color.setRGB(...rampColor(t), SRGBColorSpace);  // stored linear, shown as the sRGB stop
    colors.push(color.r, color.g, color.b);
  });
  const group = { reachable: null, unreachable: null };
  if (reachablePoints.length) {
    group.reachable = cloud(reachablePoints, Float32Array.from(colors), minimumSize(new PointsMaterial({
      size: diameter * perMetre, sizeAttenuation: true, vertexColors: true, map: texture, alphaTest: 0.5,
    }), 2 * pixelRatio));
    root.add(group.reachable);
  }
  if (unreachablePoints.length) {
    // A line of sight crosses about cbrt(n) layers of a 3D map: the haze
    // thins as they grow, so that a dense map's reachable points show through.
    const opacity = Math.min(0.35, Math.max(0.06, (0.35 * 10) / Math.cbrt(unreachablePoints.length)));
    group.unreachable = cloud(unreachablePoints, null, minimumSize(new PointsMaterial({
      size: 0.6 * diameter * perMetre, sizeAttenuation: true, color: COLORS.unreachable, map: texture,
      transparent: true, opacity, depthWrite: false,
    }), 1.5 * pixelRatio));
    root.add(group.unreachable);
  }
  return {
    range,
    points: ws.points.length,
    reachable: reachablePoints.length,
    // Shows or hides a class: 'reachable', 'unreachable' or 'all'.
    setVisible(kind, visible) {
      for (const k of ['reachable', 'unreachable']) {
        if ((kind === k || kind === 'all') && group[k]) group[k].visible = visible;
      }
    },
    // Up to `max` reachable points evenly through the list, world [m] (tests).
    reachableSample(max) {
      const every = Math.max(1, Math.ceil(reachablePoints.length / max));
      return reachablePoints.filter((_, i) => i % every === 0);
    },
  };
}
