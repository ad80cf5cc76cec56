// Browser test of the pages of 'minksum view': one polytope, and a sum with its
// operands.  node test_view.mjs polytope|sum|big --minksum BIN --out DIR
// Checked against the CLI: the counts of every solid drawn (facets and edges
// of the geometry the page built) equal 'minksum stats/sum --json', the
// legend's provenance counts equal the sum's facet_types, the volume shown is
// the exact volume, and a facet clicked in the canvas is a face of the
// polytope 'minksum sum/gen --exact' writes, with its exact plane.
import { check, checkPage, checkPickedFacet, clickFacet, launch, minksum, minksumJson, open, options, readOff, visibleFacet } from './lib.mjs';
import { join } from 'node:path';

const kind = process.argv[2];
process.argv.splice(2, 1);
const o = options();
const CASES = {
  polytope: { operands: ['dodecahedron@rot:3'] },
  sum: { operands: ['truncated-cube', 'sphere:2@rot:1'] },
  big: { operands: ['sphere:6', 'sphere:6@rot:1'] },
};
const c = CASES[kind];
check(c, `unknown case '${kind}' (polytope, sum, big)`);
const html = join(o.out, `view-${kind}.html`);
minksum(o.minksum, ['view', ...c.operands, '-o', html]);

const browser = await launch();
try {
  const { page, log } = await open(browser.context, html);
  const variance = await checkPage(page, log, kind);
  const drawn = await page.evaluate(() => ({ facets: window.minksum.drawnFacets, edges: window.minksum.drawnEdges, loadMs: window.minksum.loadMs, timing: window.minksum.timing }));
  let target, off;
  if (kind === 'polytope') {
    const st = minksumJson(o.minksum, ['stats', c.operands[0], '--json']);
    check(drawn.facets.polytope === st.facets, `polytope: ${drawn.facets.polytope} facets drawn, minksum stats says ${st.facets}`);
    check(drawn.edges.polytope === st.edges, `polytope: ${drawn.edges.polytope} edges drawn, minksum stats says ${st.edges}`);
    const volume = await page.getAttribute('#volumes .exact', 'data-volume');
    check(volume === st.volume, `polytope: the page shows volume ${volume}, minksum stats says ${st.volume}`);
    const offFile = join(o.out, `view-${kind}.off`);
    minksum(o.minksum, ['gen', c.operands[0], '--exact', '-o', offFile]);
    off = readOff(offFile);
    target = 'polytope';
  } else {
    const offFile = join(o.out, `view-${kind}.off`);
    const sum = minksumJson(o.minksum, ['sum', ...c.operands, '--exact', '-o', offFile, '--json']);
    for (const [key, want] of [['a', sum.a], ['b', sum.b], ['sum', sum]]) {
      check(drawn.facets[key] === want.facets, `${kind}: ${drawn.facets[key]} facets of ${key} drawn, minksum sum says ${want.facets}`);
      check(drawn.edges[key] === want.edges, `${kind}: ${drawn.edges[key]} edges of ${key} drawn, minksum sum says ${want.edges}`);
    }
    const legend = await page.$$eval('#legend [data-origin]', (rows) => Object.fromEntries(rows.map((r) => [r.dataset.origin, Number(r.dataset.count)])));
    check(JSON.stringify(legend) === JSON.stringify(sum.facet_types), `${kind}: legend ${JSON.stringify(legend)}, minksum sum says ${JSON.stringify(sum.facet_types)}`);
    const volumes = await page.$$eval('#volumes .exact', (v) => v.map((e) => e.dataset.volume));
    check(volumes[2] === sum.volume, `${kind}: the page shows volume ${volumes[2]} for the sum, minksum sum says ${sum.volume}`);
    off = readOff(offFile);
    target = 'sum';
  }
  await page.screenshot({ path: join(o.out, `view-${kind}.png`) });
  // A facet seen by the camera, clicked where it shows.
  const f = kind === 'big' ? await page.evaluate(() => { const m = window.minksum; for (let f = 0; f < 5000; f += 7) if (m.facetScreenPoint('sum', f)) return f; return -1; })
                           : await visibleFacet(page, target);
  check(f >= 0, `${kind}: no facet of ${target} is visible`);
  const picked = await clickFacet(page, target, f, kind);
  checkPickedFacet(picked, off, kind);
  if (kind !== 'polytope') {
    const shownKind = await page.getAttribute('#pick-provenance', 'data-kind');
    check(shownKind === picked.provenance && shownKind, `${kind}: provenance shown '${shownKind}'`);
  }
  await page.screenshot({ path: join(o.out, `view-${kind}-picked.png`) });
  // Toggles: the sum hidden leaves A and B; the transparency toggle draws.
  await page.click('#transparent');
  await page.waitForTimeout(50);
  await checkPage(page, log, `${kind} (transparent)`);
  const frames = await page.evaluate(() => window.minksum.measureFrames(30));
  const t = drawn.timing;
  console.log(`${kind}: page ready in ${Math.round(drawn.loadMs)} ms (navigation to first frame; ${log.wallMs} ms wall; ` +
              `script start ${Math.round(t.scriptMs)}, data parsed ${Math.round(t.parsedMs)}, scene built ${Math.round(t.builtMs)}), ` +
              `${frames.meanMs.toFixed(1)} ms per frame (median ${frames.medianMs.toFixed(1)}, max ${frames.maxMs.toFixed(1)}, ${frames.frames} frames), ` +
              `canvas variance ${variance.toFixed(0)}; picked facet ${picked.facet}: ${picked.plane}`);
} finally {
  await browser.close();
}
console.log(`PASS: view ${kind}`);
