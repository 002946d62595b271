// Links coloured by load (`ccma view --color_by=load`; viewer/scene_format.md,
// "loads"): the load map, the check of the scene's "loads" object, each
// body's colour in a frame, the legend's scale and the bar's line for the
// frame shown (its largest load, and whether its statics is unbalanced or
// only the minimum-norm loads).
import { COLORS, css, gradientOf, rampAt } from './colors.js';
import { el } from './dom.js';

// The load map, low to high: evenly spaced sRGB stops from deep blue through
// teal and gold to orange and dark red. Its lightness rises to gold and
// falls again, so each end stays dark enough on the light background; its
// hue turns one way throughout, so no two loads share a colour.
export const LOAD_RAMP = [0x3b4cc0, 0x2aa198, 0xe0b43a, 0xf07b2c, 0xb40426];

// sRGB [r, g, b] in 0..1 of a load [N] on a scale from 0 to max (the low
// end when max is 0: a model without masses).
export function loadColor(load, max) {
  return rampAt(LOAD_RAMP, max > 0 ? load / max : 0);
}

// Problems of the scene's "loads" object (none when it is absent or valid).
export function checkLoads(scene) {
  const loads = scene.loads;
  if (loads === undefined || loads === null) return [];
  const n = Array.isArray(scene.frames?.time) ? scene.frames.time.length : 0;
  const nb = Array.isArray(scene.bodies) ? scene.bodies.length : 0;
  const problems = [];
  const isLoad = (x) => Number.isFinite(x) && x >= 0;
  if (!isLoad(loads.max)) problems.push('loads.max: a number >= 0');
  if (typeof loads.masses !== 'boolean') problems.push('loads.masses: true or false');
  if (!Array.isArray(loads.body_loads) || loads.body_loads.length !== n ||
      !loads.body_loads.every((f) => Array.isArray(f) && f.length === nb && f.every(isLoad))) {
    problems.push('loads.body_loads: per frame, a number >= 0 per body');
  }
  for (const key of ['balanced', 'determinate']) {
    if (!Array.isArray(loads[key]) || loads[key].length !== n || !loads[key].every((b) => b === 0 || b === 1)) {
      problems.push(`loads.${key}: 0 or 1 per frame`);
    }
  }
  return problems;
}

// Every body's colour [r, g, b] (sRGB 0..1) at frame f.
export function loadColors(scene, f) {
  return scene.loads.body_loads[f].map((load) => loadColor(load, scene.loads.max));
}

const number = (x) => (x === 0 ? '0' : Number(x.toPrecision(3)).toString());

// The legend's block: "joint load [N]", the scale from 0 to the page's
// largest load, what a link's load is; "no masses in the model" when so.
export function loadLegend(panel, scene) {
  const loads = scene.loads;
  const block = el('div', { margin: '2px 0 6px', paddingBottom: '6px', borderBottom: '1px solid #e5e7eb',
                            maxWidth: '300px' });
  block.id = 'ccma-load-legend';
  block.append(el('div', { fontWeight: '600' }, 'joint load [N]'));
  const bar = el('div', { width: '100%', height: '12px', borderRadius: '2px', marginTop: '3px',
                          background: gradientOf(LOAD_RAMP) });
  bar.id = 'ccma-load-scale';
  const ends = el('div', { display: 'flex', justifyContent: 'space-between', width: '100%', color: '#374151',
                           fontVariantNumeric: 'tabular-nums' });
  const hi = el('span', {}, number(loads.max));
  hi.id = 'ccma-load-max';
  ends.append(el('span', {}, '0'), hi);
  block.append(bar, ends, el('div', { marginTop: '4px', color: '#6b7280' },
                             "each link: the largest reaction force of its joints in the frame's statics " +
                             '(gravity on the masses and payload)'));
  if (!loads.masses) {
    const note = el('div', { marginTop: '4px', fontWeight: '600', color: css(COLORS.flagged) }, 'no masses in the model');
    note.id = 'ccma-load-note';
    block.append(note);
  }
  panel.append(block);
}

// The bar's line for the frame shown: its largest load and body, and
// "unbalanced" / "minimum-norm loads" when its statics is so. Returns the
// function that shows frame f.
export function loadLabel(bar, scene) {
  const text = el('span', { fontVariantNumeric: 'tabular-nums', whiteSpace: 'nowrap' });
  text.id = 'ccma-load';
  const status = el('span', { color: '#fff', background: css(COLORS.actuated), borderRadius: '4px', padding: '2px 8px',
                              fontWeight: '600', display: 'none', whiteSpace: 'nowrap' });
  status.id = 'ccma-load-status';
  bar.append(text, status);
  const loads = scene.loads;
  return (f) => {
    const row = loads.body_loads[f];
    const top = row.reduce((best, x, i) => (x > row[best] ? i : best), 0);
    text.textContent = loads.masses ? `largest load ${number(row[top])} N (${scene.bodies[top].name})`
                                    : 'loads: no masses in the model';
    const notes = [];
    if (loads.balanced[f] === 0) notes.push('unbalanced');
    if (loads.determinate[f] === 0) notes.push('minimum-norm loads');
    status.textContent = notes.join(', ');
    status.style.display = notes.length ? '' : 'none';
  };
}
