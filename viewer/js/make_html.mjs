// Writes the page `ccma view` writes (viewer/scene_format.md: the same HTML
// shell, byte for byte, as viewer/html.cc) from a scene file and a bundle, so
// that the viewer can be developed and tested without the C++ tool:
//   node make_html.mjs --scene test/sample_scene.json --bundle /tmp/b.js --out /tmp/p.html
// The scene is parsed and written again compactly, with <, > and & as \u
// escapes so that no "</script>" can end the JSON block early.
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
const [scenePath, bundlePath, out] = ['--scene', '--bundle', '--out'].map(option);
if (!scenePath || !bundlePath || !out) {
  console.error('usage: node make_html.mjs --scene SCENE.json --bundle BUNDLE.js --out PAGE.html');
  process.exit(2);
}

const scene = JSON.parse(readFileSync(scenePath, 'utf8'));
const json = JSON.stringify(scene).replace(/[<>&]/g, (c) => '\\u' + c.charCodeAt(0).toString(16).padStart(4, '0'));
const bundle = readFileSync(bundlePath, 'utf8');
if (bundle.includes('</script')) {
  console.error(`make_html: ${bundlePath} contains "</script", which would end the page's script early`);
  process.exit(1);
}
const escapeHtml = (text) => String(text).replace(/[<>&"]/g, (c) => ({ '<': '&lt;', '>': '&gt;', '&': '&amp;', '"': '&quot;' })[c]);

const html =
  '<!DOCTYPE html>\n' +
  '<html lang="en"><head><meta charset="utf-8">\n' +
  '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; script-src \'unsafe-inline\'; ' +
  'style-src \'unsafe-inline\'; img-src data: blob:">\n' +
  '<meta name="viewport" content="width=device-width, initial-scale=1">\n' +
  `<title>ccma view: ${escapeHtml(scene.model ?? '')}</title></head>\n<body>\n` +
  `<script type="application/json" id="ccma-scene">${json}</script>\n` +
  `<script>${bundle}</script>\n` +
  '</body></html>\n';
mkdirSync(dirname(resolve(out)), { recursive: true });
writeFileSync(out, html);
