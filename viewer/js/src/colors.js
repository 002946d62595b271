// One palette for the 3D scene and its legend. Each thing a researcher must
// tell apart gets its own hue: links grey, joints dark slate, actuated joints
// amber, omni bases blue, differential bases teal, legged bases brown; the paths green (commanded),
// violet (tracked) and dark blue (bases); flagged frames red; the end-effector
// frame the usual x red, y green, z blue; a workspace map's unreachable
// points grey (its reachable ones take the sigma_min ramp of workspace.js);
// obstacles see-through grey, the collision shapes of bases and links
// see-through sky blue (the closest pair red when below the margin). Links
// coloured by load (`--color_by=load`) take the load map of loads.js instead.
export const COLORS = {
  background: 0xf4f5f7,
  grid: 0xdadde2,
  gridMajor: 0xb4bac3,
  link: 0x7d8da3,
  joint: 0x22324a,
  actuated: 0xf0a202,
  omni: 0x4a90d9,
  differential: 0x16a394,
  legged: 0xb45309,
  wheel: 0x2b2f36,
  heading: 0x1e293b,
  commanded: 0x16a34a,
  tracked: 0x7c3aed,
  basePath: 0x1e40af,
  flagged: 0xdc2626,
  beyond: 0xd946ef,  // an effort beyond its limit (efforts.js): apart from the load map's dark-red end
  unreachable: 0x8b929c,
  axisX: 0xe53935,
  axisY: 0x43a047,
  axisZ: 0x1e88e5,
  mesh: 0xb3bcc8,  // a body's meshes (`ccma view --meshes`)
  obstacle: 0x6b7280,      // obstacles (translucent) and their outline
  obstacleEdge: 0x374151,
  envelope: 0x0ea5e9,      // collision shapes of bases and links (translucent sky blue)
};

// CSS "#rrggbb" of a palette colour.
export function css(color) {
  return '#' + color.toString(16).padStart(6, '0');
}

// sRGB [r, g, b] in 0..1 at t in [0, 1] along `stops` (evenly spaced sRGB
// colours, linear between them): the colour maps of workspace.js and loads.js.
export function rampAt(stops, t) {
  const x = Math.min(Math.max(Number.isFinite(t) ? t : 0, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2), f = x - i;
  const a = stops[i], b = stops[i + 1];
  return [16, 8, 0].map((s) => (((a >> s) & 255) * (1 - f) + ((b >> s) & 255) * f) / 255);
}

// CSS linear-gradient of `stops`, left (low) to right (high).
export function gradientOf(stops) {
  const list = stops.map((c, i) => `${css(c)} ${((100 * i) / (stops.length - 1)).toFixed(0)}%`);
  return `linear-gradient(to right, ${list.join(', ')})`;
}
