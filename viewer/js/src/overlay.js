// The page's controls and labels, plain DOM over the canvas: title, legend,
// play/pause, the time slider and label, a badge for flagged frames.
import { COLORS, css } from './colors.js';

function el(tag, style, text) {
  const e = document.createElement(tag);
  Object.assign(e.style, style);
  if (text !== undefined) e.textContent = text;
  return e;
}

const PANEL = {
  position: 'absolute', background: 'rgba(255,255,255,0.88)', borderRadius: '6px', padding: '8px 12px',
  font: '13px system-ui, sans-serif', color: '#223', boxShadow: '0 1px 4px rgba(0,0,0,0.15)',
};

export function buildOverlay(scene, frames, hasPaths) {
  const title = el('div', { ...PANEL, top: '10px', left: '10px', maxWidth: '46%' });
  title.append(el('div', { fontWeight: '600', fontSize: '15px' }, `ccma view: ${scene.model}`));
  if (scene.description) title.append(el('div', { marginTop: '3px', color: '#556' }, scene.description));
  title.append(el('div', { marginTop: '3px', color: '#778' },
                  `${scene.bodies.length} bodies, ${(scene.joints || []).length} joints; drag to orbit, ` +
                  'scroll to zoom, right-drag to pan'));
  document.body.append(title);

  const legend = el('div', { ...PANEL, top: '10px', right: '10px' });
  const item = (color, label, dashed) => {
    const row = el('div', { display: 'flex', alignItems: 'center', gap: '6px', margin: '2px 0' });
    row.append(el('span', { display: 'inline-block', width: '22px', height: '0',
                            borderTop: `3px ${dashed ? 'dashed' : 'solid'} ${css(color)}` }), el('span', {}, label));
    legend.append(row);
  };
  const kinds = new Set(scene.bodies.map((b) => b.kind));
  if (kinds.has('omni')) item(COLORS.omni, 'omni base (arrow: heading)');
  if (kinds.has('differential')) item(COLORS.differential, 'differential base (arrow: heading)');
  item(COLORS.link, 'link');
  item(COLORS.joint, 'joint');
  if ((scene.joints || []).some((j) => j.actuated)) item(COLORS.actuated, 'actuated joint');
  item(COLORS.axisX, 'end-effector x (y green, z blue)');
  if (hasPaths) {
    item(COLORS.commanded, 'end-effector commanded', true);
    item(COLORS.tracked, 'end-effector tracked');
    item(COLORS.basePath, 'base paths (ground)');
    if ((scene.frames.flags || []).includes(1)) item(COLORS.flagged, 'flagged frame (not reached, torn, not assembled)');
  }
  document.body.append(legend);

  const bar = el('div', { ...PANEL, bottom: '10px', left: '10px', right: '10px', display: 'flex',
                          alignItems: 'center', gap: '10px' });
  const play = el('button', { font: 'inherit', padding: '3px 12px', minWidth: '70px' }, 'play');
  play.id = 'ccma-play';
  const slider = el('input', { flex: '1' });
  Object.assign(slider, { type: 'range', id: 'ccma-slider', min: 0, max: Math.max(frames - 1, 0), step: 1, value: 0 });
  const label = el('span', { minWidth: '220px', fontVariantNumeric: 'tabular-nums' });
  label.id = 'ccma-time';
  const badge = el('span', { color: '#fff', background: css(COLORS.flagged), borderRadius: '4px',
                             padding: '2px 8px', visibility: 'hidden' }, 'suspect frame');
  badge.id = 'ccma-flag';
  if (frames <= 1) {
    play.disabled = true;
    slider.disabled = true;
    play.textContent = 'static';
  }
  bar.append(play, slider, label, badge);
  document.body.append(bar);
  return { play, slider, label, badge };
}

export function showError(message) {
  document.body.append(el('pre', { ...PANEL, top: '20px', left: '20px', color: '#a00', whiteSpace: 'pre-wrap' },
                          `ccma view: cannot show this page\n${message}`));
}
