// One palette for the 3D scene and its legend. Each thing a researcher must
// tell apart gets its own hue: links grey, joints dark slate, actuated joints
// amber, omni bases blue, differential bases teal; the paths green (commanded),
// violet (tracked) and dark blue (bases); flagged frames red; the end-effector
// frame the usual x red, y green, z blue; a workspace map's unreachable
// points grey (its reachable ones take the sigma_min ramp of workspace.js);
// obstacles see-through grey, the collision shapes of bases and links
// see-through sky blue (the closest pair red when below the margin).
export const COLORS = {
  background: 0xf4f5f7,
  grid: 0xdadde2,
  gridMajor: 0xb4bac3,
  link: 0x7d8da3,
  joint: 0x22324a,
  actuated: 0xf0a202,
  omni: 0x4a90d9,
  differential: 0x16a394,
  wheel: 0x2b2f36,
  heading: 0x1e293b,
  commanded: 0x16a34a,
  tracked: 0x7c3aed,
  basePath: 0x1e40af,
  flagged: 0xdc2626,
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
