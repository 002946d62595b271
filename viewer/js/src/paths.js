// The recorded paths: the end-effector's commanded and tracked paths in 3D,
// each base's path on the ground, flagged frames as red dots.
import {
  BufferGeometry, Float32BufferAttribute, Line, LineBasicMaterial, LineDashedMaterial, Points, PointsMaterial,
} from 'three';
import { COLORS } from './colors.js';

// Paths are drawn over everything (no depth test): a path inside the
// platform or under a base's disc would otherwise be hidden.
function line(points, material) {
  material.depthTest = false;
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new Float32BufferAttribute(points.flat(), 3));
  const l = new Line(geometry, material);
  l.computeLineDistances();  // for dashes
  l.renderOrder = 10;
  return l;
}

export function buildPaths(scene, root) {
  const paths = scene.paths;
  if (!paths) return { commanded: false };
  const s = Math.max(scene.scale || 0.5, 1e-3);
  if (Array.isArray(paths.commanded) && paths.commanded.length > 1) {
    root.add(line(paths.commanded, new LineDashedMaterial({ color: COLORS.commanded, dashSize: 0.02 * s,
                                                            gapSize: 0.012 * s })));
  }
  if (Array.isArray(paths.tracked) && paths.tracked.length > 1) {
    root.add(line(paths.tracked, new LineBasicMaterial({ color: COLORS.tracked })));
    const flags = scene.frames.flags || [];
    const flagged = paths.tracked.filter((_, i) => flags[i] === 1);
    if (flagged.length) {
      const geometry = new BufferGeometry();
      geometry.setAttribute('position', new Float32BufferAttribute(flagged.flat(), 3));
      const dots = new Points(geometry, new PointsMaterial({ color: COLORS.flagged, size: 0.03 * s, depthTest: false }));
      dots.renderOrder = 11;
      root.add(dots);
    }
  }
  for (const base of paths.bases || []) {
    if (base.length > 1) {
      root.add(line(base.map(([x, y]) => [x, y, 0.002]), new LineBasicMaterial({ color: COLORS.basePath })));
    }
  }
  return { commanded: Array.isArray(paths.commanded) };
}
