// The page's controls and labels, plain DOM over the canvas (styles set from
// here: the page has no stylesheet): title, legend, play/pause, the time
// slider and label, a badge for flagged frames, the frame's clearance (with
// collision geometry), the workspace cloud's colour scale and its
// "unreachable" switch, the load scale and the frame's loads (colouring by
// load, loads.js); the effort scale and the frame's largest effort share
// (colouring by effort, efforts.js); and the error panel.
import { COLORS, css } from './colors.js';
import { deflectionLegend } from './deflection.js';
import { effortLabel, effortLegend } from './efforts.js';
import { loadLabel, loadLegend } from './loads.js';
import { rampGradient } from './workspace.js';
import { el } from './dom.js';

const round = (x) => Number(x.toPrecision(6));  // 0.30000000000000004 -> 0.3

const PANEL = {
  position: 'absolute', background: 'rgba(255,255,255,0.9)', borderRadius: '6px', padding: '8px 12px',
  font: '13px system-ui, -apple-system, "Segoe UI", sans-serif', color: '#1f2533',
  boxShadow: '0 1px 4px rgba(0,0,0,0.15)',
};

// Legend swatches: a block for solid parts, a line (solid or dashed) for paths, a dot.
function swatch(kind, colors) {
  const box = el('span', { display: 'inline-flex', gap: '2px', width: '26px', justifyContent: 'center',
                           alignItems: 'center' });
  for (const color of colors) {
    if (kind === 'block') {
      box.append(el('span', { width: `${Math.floor(20 / colors.length)}px`, height: '10px', borderRadius: '2px',
                              background: css(color) }));
    } else if (kind === 'dot') {
      box.append(el('span', { width: '9px', height: '9px', borderRadius: '50%', background: css(color) }));
    } else {
      box.append(el('span', { width: '24px', borderTop: `3px ${kind} ${css(color)}` }));
    }
  }
  return box;
}

const ORIENTATION = ['roll', 'pitch', 'yaw'];

// The workspace cloud's part of the legend: the sigma_min colour scale with
// its range and unit, the unreachable points with a switch (returned), the
// counts and what the positions are made of.
function workspaceLegend(panel, scene, cloud) {
  const ws = scene.workspace;
  const block = el('div', { margin: '2px 0 6px', paddingBottom: '6px', borderBottom: '1px solid #e5e7eb',
                            maxWidth: '300px' });
  block.append(el('div', { fontWeight: '600' }, `workspace map: ${cloud.reachable} of ${cloud.points} reachable`));
  if (cloud.reachable > 0) {
    block.append(el('div', { marginTop: '4px' }, 'reachable, coloured by sigma_min, the smallest singular value of dX/du:'));
    const bar = el('div', { width: '100%', height: '12px', borderRadius: '2px', marginTop: '3px', background: rampGradient() });
    bar.id = 'ccma-sigma-scale';
    const ends = el('div', { display: 'flex', justifyContent: 'space-between', width: '100%', color: '#374151',
                             fontVariantNumeric: 'tabular-nums' });
    const number = (x) => (x === 0 ? '0' : Math.abs(x) < 1e-3 ? x.toExponential(1) : Number(x.toPrecision(3)).toString());
    ends.append(el('span', {}, '0 (singular)'), el('span', {}, number(cloud.range.hi)));
    block.append(bar, ends, el('div', { color: '#6b7280' }, 'in m or rad per control unit'),
                 el('div', { color: '#6b7280' }, `this map: ${number(cloud.range.lo)} to ${number(cloud.range.hi)}`));
  }
  let toggle = null;
  if (cloud.points > cloud.reachable) {
    const row = el('label', { display: 'flex', alignItems: 'center', gap: '8px', marginTop: '4px', cursor: 'pointer' });
    toggle = el('input', { margin: '0' });
    Object.assign(toggle, { type: 'checkbox', id: 'ccma-unreachable', checked: true });
    const dot = el('span', { width: '8px', height: '8px', borderRadius: '50%', background: css(COLORS.unreachable),
                             opacity: '0.6' });
    row.append(toggle, dot, el('span', {}, `unreachable (${cloud.points - cloud.reachable}); key u`));
    block.append(row);
  }
  const components = ws.components || [];
  const hidden = components.filter((c) => ORIENTATION.includes(c));
  const drawn = components.filter((c) => !ORIENTATION.includes(c));
  let note = `end-effector positions${ws.source ? ` from ${ws.source}` : ''}` +
             (drawn.length < 3 ? `; ${['x', 'y', 'z'].filter((c) => !drawn.includes(c)).join(', ')} at home` : '');
  if (hidden.length) note += `; ${hidden.join(', ')} not drawn (samples differing only there coincide)`;
  block.append(el('div', { marginTop: '4px', color: '#6b7280' }, note));
  panel.append(block);
  return toggle;
}

function legend(scene, gridStep, cloud) {
  const panel = el('div', { ...PANEL, top: '10px', right: '10px' });
  const toggle = cloud ? workspaceLegend(panel, scene, cloud) : null;
  if (scene.loads) loadLegend(panel, scene);
  if (scene.efforts) effortLegend(panel, scene);
  if (scene.deflection) deflectionLegend(panel, scene);
  const item = (kind, colors, label) => {
    const row = el('div', { display: 'flex', alignItems: 'center', gap: '8px', margin: '3px 0' });
    row.append(swatch(kind, colors), el('span', {}, label));
    panel.append(row);
  };
  const kinds = new Set(scene.bodies.map((b) => b.kind));
  const joints = scene.joints || [];
  const byEffort = scene.efforts ? '; coloured by effort when limited' : '';
  if (kinds.has('omni')) item('block', [COLORS.omni], `omni base (arrow: heading${byEffort})`);
  if (kinds.has('differential')) item('block', [COLORS.differential], `differential base (arrow: heading${byEffort})`);
  if (kinds.has('legged')) item('block', [COLORS.legged], `legged base: body box on four legs (arrow: heading${byEffort})`);
  const withMeshes = scene.bodies.filter((b) => (b.meshes || []).length > 0).length;
  if (withMeshes < scene.bodies.length && !scene.loads) item('block', [COLORS.link], scene.deflection ? 'link (rigid shape, faded)' : 'link');
  if (withMeshes > 0 && !scene.loads) item('block', [COLORS.mesh], 'body mesh (STL)');
  if (joints.some((j) => !j.actuated)) item('block', [COLORS.joint], 'joint (passive)');
  if (joints.some((j) => j.actuated)) item('block', [COLORS.actuated], 'actuated joint');
  if (scene.end_effector) item('block', [COLORS.axisX, COLORS.axisY, COLORS.axisZ], 'end-effector frame x, y, z');
  const paths = scene.paths || {};
  if ((paths.commanded || []).length > 1) item('dashed', [COLORS.commanded], 'end-effector commanded');
  if ((paths.tracked || []).length > 1) item('solid', [COLORS.tracked], 'end-effector tracked');
  if ((paths.bases || []).some((b) => b.length > 1)) item('solid', [COLORS.basePath], 'base paths (ground)');
  const collision = scene.collision;
  if (collision && collision.obstacles.length) item('block', [COLORS.obstacle], 'obstacle');
  if (collision && (collision.bases.length || collision.links.length)) {
    item('block', [COLORS.envelope], `collision shape (red: closest pair below the ${round(collision.margin)} m margin)`);
  }
  if ((scene.frames.flags || []).includes(1)) {
    item('dot', [COLORS.flagged], `suspect frame (not assembled / torn${collision ? ' / below the margin' : ''})`);
  }
  panel.append(el('div', { marginTop: '5px', color: '#6b7280' }, `grid: ${round(gridStep)} m squares (bold every ${round(5 * gridStep)} m); world z up`));
  return { panel, toggle };
}

// `cloud`: what buildWorkspace returned (null without a workspace map).
export function buildOverlay(scene, frames, gridStep, cloud = null) {
  const title = el('div', { ...PANEL, top: '10px', left: '10px', maxWidth: '46%' });
  title.append(el('div', { fontWeight: '600', fontSize: '15px' }, `ccma view: ${scene.model ?? ''}`));
  if (scene.description) title.append(el('div', { marginTop: '3px', color: '#4b5563' }, scene.description));
  title.append(el('div', { marginTop: '3px', color: '#6b7280' },
                  `${scene.bodies.length} bodies, ${(scene.joints || []).length} joints` +
                  (scene.source ? `, from ${scene.source}` : '') +
                  '. Drag to orbit, scroll to zoom, right-drag to pan.'));
  const { panel, toggle } = legend(scene, gridStep, cloud);
  document.body.append(title, panel);

  const bar = el('div', { ...PANEL, bottom: '10px', left: '10px', right: '10px', display: 'flex',
                          alignItems: 'center', gap: '12px' });
  const play = el('button', { font: 'inherit', padding: '3px 12px', minWidth: '72px' }, 'play');
  play.id = 'ccma-play';
  const slider = el('input', { flex: '1' });
  Object.assign(slider, { type: 'range', id: 'ccma-slider', min: 0, max: Math.max(frames - 1, 0), step: 1, value: 0 });
  const label = el('span', { minWidth: '230px', fontVariantNumeric: 'tabular-nums' });
  label.id = 'ccma-time';
  const badge = el('span', { color: '#fff', background: css(COLORS.flagged), borderRadius: '4px', padding: '2px 8px',
                             fontWeight: '600', visibility: 'hidden' }, 'suspect frame');
  badge.id = 'ccma-flag';
  if (frames <= 1) {  // a model at home: nothing to play
    play.disabled = true;
    slider.disabled = true;
    play.textContent = 'static';
  }
  bar.append(play, slider, label);
  const clearance = scene.collision ? clearanceLabel(bar) : null;
  const load = scene.loads ? loadLabel(bar, scene) : null;
  const effort = scene.efforts ? effortLabel(bar, scene) : null;
  bar.append(badge);
  document.body.append(bar);
  return { play, slider, label, badge, unreachable: toggle, clearance, load, effort };
}

// The frame's clearance: its value and pair, and "below margin" in red.
function clearanceLabel(bar) {
  const text = el('span', { fontVariantNumeric: 'tabular-nums', whiteSpace: 'nowrap' });
  text.id = 'ccma-clearance';
  const below = el('span', { color: '#fff', background: css(COLORS.flagged), borderRadius: '4px', padding: '2px 8px',
                             fontWeight: '600', display: 'none' }, 'below margin');
  below.id = 'ccma-below-margin';
  bar.append(text, below);
  // info: clearanceAt() of the frame shown (null: no pair is checked).
  return (info) => {
    text.textContent = info ? `clearance ${info.min.toFixed(3)} m (${info.pair[0]} to ${info.pair[1]})` : 'clearance: no pair checked';
    text.style.color = info && info.below ? css(COLORS.flagged) : '';
    below.style.display = info && info.below ? '' : 'none';
  };
}

export function showError(message) {
  document.body.append(el('pre', { ...PANEL, top: '20px', left: '20px', right: '20px', color: '#a00',
                                   whiteSpace: 'pre-wrap' },
                          `ccma view: cannot show this page\n${message}`));
}
