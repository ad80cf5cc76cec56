// Browser test of the pages of 'minksum view': one polytope, and a sum with its
// operands.  node test_view.mjs polytope|sum|big --minksum BIN --out DIR
// Checked against the CLI: the counts of every solid drawn (facets and edges
// of the geometry the page built) equal 'minksum stats/sum --json', the
// legend's provenance counts equal the sum's facet_types, the volume shown is
// the exact volume, and a facet clicked in the canvas is a face of the
// polytope 'minksum sum/gen --exact' writes, with its exact plane.  'sweep':
// a solid swept along a segment (docs/sweeps.md), the segment drawn as its
// one edge; 'point': a point alone, drawn as a dot; 'solid': a non-convex
// solid and its sum (docs/nonconvex.md), faces drawn from their exact
// triangulation, counts as 'minksum stats' gives them.  Every exact number
// shown has its decimal beside it, checked exactly, long ones folded.
import { check, checkDecimals, checkPage, checkPickedFacet, clickFacet, launch, minksum, minksumJson, open, options, readOff, visibleFacet } from './lib.mjs';
import { join } from 'node:path';

const kind = process.argv[2];
process.argv.splice(2, 1);
const o = options();
const CASES = {
  polytope: { operands: ['dodecahedron@rot:3'] },
  sum: { operands: ['truncated-cube', 'sphere:2@rot:1'] },
  big: { operands: ['sphere:6', 'sphere:6@rot:1'] },
  sweep: { operands: ['truncated-cube', 'segment:0,0,0:1,2,3'] },
  point: { operands: ['point:1,2,3'] },
  solid: { operands: ['tube', 'box:1/2:1/2:1/2'] },
};
const c = CASES[kind];
check(c, `unknown case '${kind}' (polytope, sum, big, sweep, point, solid)`);
const html = join(o.out, `view-${kind}.html`);
minksum(o.minksum, ['view', ...c.operands, '-o', html]);

const browser = await launch();
try {
  const { page, log } = await open(browser.context, html);
  // A point is one dot on a plain background: its own check below.
  const variance = await checkPage(page, log, kind, kind === 'point' ? 0 : 20);
  const drawn = await page.evaluate(() => ({ facets: window.minksum.drawnFacets, edges: window.minksum.drawnEdges, loadMs: window.minksum.loadMs, timing: window.minksum.timing }));
  let target, off;
  if (kind === 'point') {
    // Nothing to click: the dot is the only thing drawn, at the point.
    const dot = await page.evaluate(() => {
      const m = window.minksum, c = document.querySelector('#view canvas');
      m.render();
      const tmp = document.createElement('canvas');
      tmp.width = c.width; tmp.height = c.height;
      const ctx = tmp.getContext('2d');
      ctx.drawImage(c, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      let dark = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 80 && d[i + 1] < 80 && d[i + 2] < 80) ++dark;
      return { dark, facets: m.drawnFacets, edges: m.drawnEdges };
    });
    check(dot.dark >= 9, `point: ${dot.dark} dark pixels drawn, a dot has at least 9`);
    check(dot.edges.polytope === 0, `point: ${dot.edges.polytope} edges drawn`);
    await page.screenshot({ path: join(o.out, `view-${kind}.png`) });
    await browser.close();
    console.log(`PASS: view ${kind}`);
    process.exit(0);
  }
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
    const keys = kind === 'sweep' ? [['a', sum.a], ['sum', sum]]
               : kind === 'solid' ? [['a', minksumJson(o.minksum, ['stats', c.operands[0], '--json'])],
                                     ['b', minksumJson(o.minksum, ['stats', c.operands[1], '--json'])], ['sum', sum]]
               : [['a', sum.a], ['b', sum.b], ['sum', sum]];
    if (kind === 'sweep') check(drawn.edges.b === 1, `sweep: ${drawn.edges.b} edges of the segment drawn`);
    for (const [key, want] of keys) {
      check(drawn.facets[key] === want.facets, `${kind}: ${drawn.facets[key]} facets of ${key} drawn, minksum sum says ${want.facets}`);
      check(drawn.edges[key] === want.edges, `${kind}: ${drawn.edges[key]} edges of ${key} drawn, minksum sum says ${want.edges}`);
    }
    if (kind === 'solid') {
      const note = await page.textContent('#legend');
      check(note.includes('non-convex'), `solid: the legend says '${note}'`);
    }
    if (kind !== 'sweep' && kind !== 'solid') {
    const legend = await page.$$eval('#legend [data-origin]', (rows) => Object.fromEntries(rows.map((r) => [r.dataset.origin, Number(r.dataset.count)])));
    check(JSON.stringify(legend) === JSON.stringify(sum.facet_types), `${kind}: legend ${JSON.stringify(legend)}, minksum sum says ${JSON.stringify(sum.facet_types)}`);
    }
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
  checkPickedFacet(picked, off, kind, kind !== 'solid');
  // Every exact number shown (the volumes, the picked facet's vertices) has its decimal beside it.
  await checkDecimals(page, kind, 1);
  if (kind !== 'polytope' && kind !== 'sweep' && kind !== 'solid') {
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
