// One palette for the page and its legend (CSS hex strings and numbers).
export const COLORS = {
  background: 0xf4f5f7,
  grid: 0xc8ccd2,
  gridCenter: 0x9aa0a8,
  link: 0x5b6b82,
  omni: 0x2f7ed8,
  differential: 0x8e44ad,
  heading: 0xf39c12,
  joint: 0x34495e,
  actuated: 0xc0392b,
  commanded: 0x16a34a,
  tracked: 0xe67e22,
  basePath: 0x1a3a6b,
  flagged: 0xd6006e,
  axisX: 0xe74c3c,
  axisY: 0x27ae60,
  axisZ: 0x2f7ed8,
};

export function css(color) {
  return '#' + color.toString(16).padStart(6, '0');
}
