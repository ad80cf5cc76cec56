// The screenshots of the README (docs/images/*.png), taken from pages minksum
// writes, in Debian's headless chromium (as the browser tests):
//   node web/screenshots.mjs --minksum build/bin/minksum --out docs/images
// ('make screenshots').  The pages are written beside the screenshots' build
// directory, under build/screenshots/.
import { check, clickFacet, launch, minksum, open, options, visibleFacet } from '../tests/browser/lib.mjs';
import { mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';

const o = options();
const pages = join(dirname(o.minksum), '..', 'screenshots');
mkdirSync(pages, { recursive: true });
const shots = [
  { name: 'view-sum', args: ['view', 'truncated-cube', 'sphere:3@rot:1', '-o'], pick: 'sum' },
  { name: 'cgm-sum', args: ['cgm', 'dioctagonal:17', 'dioctagonal:17@rot:100,0,0,99', '--html'] },
  { name: 'simulate', args: ['simulate', '--frames', '40', '--html'], frame: 9 },
  // A VRML scene (docs/vrml.md) written by 'cgm -o', then shown by 'view'.
  { name: 'vrml-scene', before: ['cgm', 'truncated-cube@rot:2', 'octahedron@rot:1,2,3,7', '-o', join(pages, 'vrml-scene.wrl')],
    args: ['view', join(pages, 'vrml-scene.wrl'), '--title', 'vrml-scene.wrl: P, Q, P ⊕ Q and their Cubical Gaussian Maps', '-o'] },
];
const browser = await launch();
try {
  for (const s of shots) {
    const html = join(pages, `${s.name}.html`);
    if (s.before) minksum(o.minksum, s.before);
    minksum(o.minksum, [...s.args, html]);
    const { page, log } = await open(browser.context, html);
    check(log.errors.length === 0, `${s.name}: ${log.errors.join(' | ')}`);
    if (s.pick) await clickFacet(page, s.pick, await visibleFacet(page, s.pick), s.name);
    if (s.frame !== undefined) await page.evaluate((k) => window.minksum.setFrame(k), s.frame);
    await page.waitForTimeout(100);
    const file = join(o.out, `${s.name}.png`);
    await page.screenshot({ path: file });
    console.log(`wrote ${file}`);
  }
} finally {
  await browser.close();
}
