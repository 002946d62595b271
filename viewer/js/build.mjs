// Bundles the viewer (src/main.js and three.js) into one script for the HTML
// page `ccma view` writes:  node build.mjs --out PATH
// Minified IIFE, ES2020; licence comments of the bundled code (three.js: MIT)
// are kept at the end of the file. The build (viewer/CMakeLists.txt) runs
// esbuild's binary with these options, without Node.js; the test
// viewer_bundle_matches_build_mjs checks that both give the same file.
import { build } from 'esbuild';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const i = process.argv.indexOf('--out');
if (i < 0 || !process.argv[i + 1]) {
  console.error('usage: node build.mjs --out PATH');
  process.exit(2);
}
await build({
  entryPoints: [resolve(here, 'src/main.js')],
  outfile: resolve(process.argv[i + 1]),
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  charset: 'ascii',
  legalComments: 'eof',
  logLevel: 'error',
});
