// The loaded shape of a compliant model (`ccma view --deflection=SCALE`;
// viewer/scene_format.md, "deflection"): a second copy of the mechanism,
// posed at the scene's exaggerated loaded poses and each body coloured by its
// deflection on the load map (0 to the largest), drawn over the rigid one;
// its legend block (the scale, the largest deflection and its body, the
// end-effector's) and the check of the scene's "deflection" object.
import { COLORS, css, gradientOf, rampAt } from './colors.js';
import { LOAD_RAMP } from './loads.js';
import { el } from './dom.js';

const isVec = (v, n) => Array.isArray(v) && v.length === n && v.every(Number.isFinite);

// Problems of the scene's "deflection" object (none when it is absent or valid).
export function checkDeflection(scene) {
  const d = scene.deflection;
  if (d === undefined || d === null) return [];
  const nb = Array.isArray(scene.bodies) ? scene.bodies.length : 0;
  const problems = [];
  if (!(Number.isFinite(d.scale) && d.scale > 0)) problems.push('deflection.scale: a number > 0');
  if (!(Number.isFinite(d.max) && d.max >= 0)) problems.push('deflection.max: a number >= 0');
  for (const key of ['poses', 'loaded_poses']) {
    if (!Array.isArray(d[key]) || d[key].length !== nb || !d[key].every((p) => isVec(p, 7))) {
      problems.push(`deflection.${key}: one [px, py, pz, qx, qy, qz, qw] per body`);
    }
  }
  if (!Array.isArray(d.body_deflection) || d.body_deflection.length !== nb ||
      !d.body_deflection.every((x) => Number.isFinite(x) && x >= 0)) {
    problems.push('deflection.body_deflection: a number >= 0 per body');
  }
  if (!isVec(d.end_effector, 6)) problems.push('deflection.end_effector: 6 numbers');
  return problems;
}

// Every body's colour [r, g, b] (sRGB 0..1): its deflection on the load map.
export function deflectionColors(scene) {
  const d = scene.deflection;
  return d.body_deflection.map((x) => rampAt(LOAD_RAMP, d.max > 0 ? x / d.max : 0));
}

// Poses and paints the loaded copy (mechanism.js's buildMechanism of the
// same scene into its own group); its joint and end-effector markers keep
// their colours.
export function showDeflected(scene, copy) {
  copy.pose({ poses: [scene.deflection.poses] }, 0);
  copy.paint(deflectionColors(scene));
}

// A length for the legend: micrometres, millimetres or metres, 3 digits.
export function formatLength(m) {
  const a = Math.abs(m);
  const [unit, f] = a < 1e-3 ? ['\u00b5m', 1e6] : a < 1 ? ['mm', 1e3] : ['m', 1];
  return `${Number((m * f).toPrecision(3))} ${unit}`;
}

// The legend's block: "deflection (drawn x SCALE)", the colour scale from 0
// to the largest deflection, the largest body and the end-effector's
// displacement, and a red note when the loaded equilibrium was not found.
export function deflectionLegend(panel, scene) {
  const d = scene.deflection;
  const block = el('div', { margin: '2px 0 6px', paddingBottom: '6px', borderBottom: '1px solid #e5e7eb',
                            maxWidth: '300px' });
  block.id = 'ccma-deflection-legend';
  const title = el('div', { fontWeight: '600' }, `loaded shape, displacements drawn \u00d7 ${Number(d.scale.toPrecision(6))}`);
  title.id = 'ccma-deflection-scale';
  block.append(title);
  block.append(el('div', { width: '100%', height: '12px', borderRadius: '2px', marginTop: '3px',
                           background: gradientOf(LOAD_RAMP) }));
  const ends = el('div', { display: 'flex', justifyContent: 'space-between', width: '100%', color: '#374151',
                           fontVariantNumeric: 'tabular-nums' });
  const hi = el('span', {}, formatLength(d.max));
  hi.id = 'ccma-deflection-max';
  ends.append(el('span', {}, '0'), hi);
  block.append(ends);
  const body = scene.bodies[d.max_body] ? scene.bodies[d.max_body].name : '';
  const ee = Math.hypot(d.end_effector[0], d.end_effector[1], d.end_effector[2]);
  block.append(el('div', { marginTop: '4px', color: '#374151' },
                  `largest deflection ${formatLength(d.max)} (${body}); end-effector ${formatLength(ee)}, ` +
                  `${Number((Math.hypot(...d.end_effector.slice(3)) * 1e3).toPrecision(3))} mrad`));
  block.append(el('div', { marginTop: '4px', color: '#6b7280' },
                  'each body: the largest displacement of its joint points under gravity, the payload and the ' +
                  'wrench (true size; drawn exaggerated); the rigid shape in grey'));
  if (d.converged === false) {
    const note = el('div', { marginTop: '4px', fontWeight: '600', color: css(COLORS.flagged) },
                    `loaded equilibrium not found: ${Number(d.load_fraction.toPrecision(3))} of the loads held`);
    note.id = 'ccma-deflection-note';
    block.append(note);
  }
  panel.append(block);
}

// The rigid mechanism drawn under the loaded one: its links' and balls'
// materials see-through.
export function fadeRigid(mechanism) {
  mechanism.fade(0.35);
}
