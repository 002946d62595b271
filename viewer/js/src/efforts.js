// Actuators coloured by effort (`ccma view --trajectory=T.csv --dynamics=D.csv`;
// viewer/scene_format.md, "efforts"): the check of the scene's "efforts"
// object, each body's colour in a frame (the body an actuator with a limit
// drives, by its effort as a share of that limit: 0 to 1 on the load map,
// beyond 1 magenta; other bodies keep their colour), the legend's scale and the
// bar's line for the frame shown.
import { COLORS, css, gradientOf, rampAt } from './colors.js';
import { LOAD_RAMP } from './loads.js';
import { el } from './dom.js';

// Problems of the scene's "efforts" object (none when it is absent or valid).
export function checkEfforts(scene) {
  const efforts = scene.efforts;
  if (efforts === undefined || efforts === null) return [];
  const n = Array.isArray(scene.frames?.time) ? scene.frames.time.length : 0;
  const nb = Array.isArray(scene.bodies) ? scene.bodies.length : 0;
  const problems = [];
  const actuators = efforts.actuators;
  if (!Array.isArray(actuators) || actuators.length === 0 ||
      !actuators.every((a) => a && typeof a.name === 'string' && (a.kind === 'effort' || a.kind === 'push') &&
                             Number.isInteger(a.body) && a.body >= -1 && a.body < nb)) {
    problems.push("efforts.actuators: at least one {name, kind 'effort' or 'push', body index or -1}");
    return problems;
  }
  const isShare = (x) => Number.isFinite(x) && (x >= 0 || x === -1);
  if (!Array.isArray(efforts.shares) || efforts.shares.length !== n ||
      !efforts.shares.every((f) => Array.isArray(f) && f.length === actuators.length && f.every(isShare))) {
    problems.push('efforts.shares: per frame, a number >= 0 (or -1: not assembled) per actuator');
  }
  if (!(Number.isFinite(efforts.max) && efforts.max >= 0)) problems.push('efforts.max: a number >= 0');
  return problems;
}

// A share's colour: the load map from 0 to 1, magenta beyond the limit, grey
// where the row did not assemble.
export function shareColor(share) {
  if (share < 0) return rampAt([COLORS.unreachable, COLORS.unreachable], 0);
  if (share > 1 + 1e-9) return rampAt([COLORS.beyond, COLORS.beyond], 0);
  return rampAt(LOAD_RAMP, share);
}

// Every body's colour [r, g, b] (sRGB 0..1) at frame f: the largest share
// of the actuators on it, or `base[b]` (its own colour) when none drives it.
export function effortColors(scene, f, base) {
  const top = base.map(() => null);
  scene.efforts.actuators.forEach((a, i) => {
    if (a.body < 0) return;
    const share = scene.efforts.shares[f][i];
    if (top[a.body] === null || share > top[a.body]) top[a.body] = share;
  });
  return top.map((share, b) => (share === null ? base[b] : shareColor(share)));
}

const percent = (x) => `${Math.round(100 * x)} %`;

// The legend's block: "effort / limit", the scale from 0 to 100 %, magenta
// beyond, grey not assembled, and which bodies are coloured.
export function effortLegend(panel, scene) {
  const block = el('div', { margin: '2px 0 6px', paddingBottom: '6px', borderBottom: '1px solid #e5e7eb',
                            maxWidth: '300px' });
  block.id = 'ccma-effort-legend';
  block.append(el('div', { fontWeight: '600' }, 'effort / limit'));
  const bar = el('div', { width: '100%', height: '12px', borderRadius: '2px', marginTop: '3px',
                          background: gradientOf(LOAD_RAMP) });
  bar.id = 'ccma-effort-scale';
  const ends = el('div', { display: 'flex', justifyContent: 'space-between', width: '100%', color: '#374151' });
  ends.append(el('span', {}, '0'), el('span', {}, '100 %'));
  const beyond = el('div', { marginTop: '3px', display: 'flex', alignItems: 'center', gap: '6px' });
  beyond.append(el('span', { display: 'inline-block', width: '14px', height: '12px', borderRadius: '2px',
                             background: css(COLORS.beyond) }), el('span', {}, 'beyond the limit'));
  const names = scene.efforts.actuators.map((a) => `${a.name} (${a.kind})`).join(', ');
  block.append(bar, ends, beyond, el('div', { marginTop: '4px', color: '#6b7280' },
                                     `each body driven by a limited actuator: its effort as a share of the ` +
                                     `limit (push: the length of the base's (x, y) effort) in ccma dynamics: ${names}`));
  panel.append(block);
}

// The bar's line for the frame shown: the largest share and its actuator,
// and "beyond limit" in magenta. Returns the function that shows frame f.
export function effortLabel(bar, scene) {
  const text = el('span', { fontVariantNumeric: 'tabular-nums', whiteSpace: 'nowrap' });
  text.id = 'ccma-effort';
  const status = el('span', { color: '#fff', background: css(COLORS.beyond), borderRadius: '4px', padding: '2px 8px',
                              fontWeight: '600', display: 'none', whiteSpace: 'nowrap' }, 'beyond limit');
  status.id = 'ccma-effort-status';
  bar.append(text, status);
  const { actuators, shares } = scene.efforts;
  return (f) => {
    const row = shares[f];
    const top = row.reduce((best, x, i) => (x > row[best] ? i : best), 0);
    text.textContent = row[top] < 0 ? 'effort: not assembled'
                                    : `largest effort ${percent(row[top])} of its limit (${actuators[top].name})`;
    status.style.display = row[top] > 1 + 1e-9 ? '' : 'none';
  };
}
