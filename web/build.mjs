// Bundles the viewer (src/viewer.js and the parts of three.js it imports)
// into one minified script for the pages minksum writes:
//   node web/build.mjs OUT.js
// CMakeLists.txt runs it at build time; cli/page.cpp inlines the result.
import * as esbuild from 'esbuild';
import { fileURLToPath } from 'node:url';

const out = process.argv[2];
if (!out) {
  console.error('usage: node build.mjs OUT.js');
  process.exit(2);
}
await esbuild.build({
  entryPoints: [fileURLToPath(new URL('./src/viewer.js', import.meta.url))],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  legalComments: 'inline',
  outfile: out,
  logLevel: 'warning',
});
