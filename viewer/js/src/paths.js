// The recorded paths: the end-effector's commanded (dashed) and tracked paths
// in 3D, each base's path on the ground, flagged frames as red balls on the
// tracked path. Lines are three's "fat" Line2 (a width in CSS pixels): WebGL
// draws ordinary lines one pixel wide, too thin to read on a large screen.
import { InstancedMesh, Matrix4, SphereGeometry } from 'three';
import { Line2 } from 'three/examples/jsm/lines/Line2.js';
import { LineGeometry } from 'three/examples/jsm/lines/LineGeometry.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { COLORS } from './colors.js';
import { material } from './shapes.js';

// Paths are drawn over everything (no depth test): a path inside the
// platform or under a base's disc would otherwise be hidden.
function line(points, color, width, dashed, u) {
  const geometry = new LineGeometry();
  geometry.setPositions(points.flat());
  const mat = new LineMaterial({ color, linewidth: width, dashed, dashSize: 0.025 * u, gapSize: 0.015 * u,
                                 depthTest: false });
  const l = new Line2(geometry, mat);
  l.computeLineDistances();  // for the dashes
  l.renderOrder = 10;
  return l;
}

// Adds the paths to `root`; dashes and dots sized from `u` (sceneSize).
export function buildPaths(scene, root, u) {
  const paths = scene.paths;
  if (!paths) return;
  for (const base of paths.bases || []) {
    if (base.length > 1) root.add(line(base.map(([x, y]) => [x, y, 0.001]), COLORS.basePath, 2, false, u));
  }
  if (Array.isArray(paths.tracked) && paths.tracked.length > 1) {
    root.add(line(paths.tracked, COLORS.tracked, 3, false, u));
  }
  if (Array.isArray(paths.commanded) && paths.commanded.length > 1) {
    root.add(line(paths.commanded, COLORS.commanded, 2.5, true, u));
  }
  // One instanced mesh for all flagged frames: a long replay may flag many.
  const flags = scene.frames.flags || [];
  const flagged = (paths.tracked || []).filter((_, i) => flags[i] === 1);
  if (flagged.length) {
    const dots = new InstancedMesh(new SphereGeometry(0.014 * u, 12, 8),
                                   material(COLORS.flagged, { depthTest: false }), flagged.length);
    flagged.forEach((p, i) => dots.setMatrixAt(i, new Matrix4().makeTranslation(p[0], p[1], p[2])));
    dots.renderOrder = 11;
    root.add(dots);
  }
}
