// Browser test of the page of 'minksum cgm --html': the Cubical Gaussian Map
// on the cube beside its polytope.  node test_cgm.mjs single|sum --minksum BIN --out DIR
// Checked against 'minksum cgm --json': the real vertices drawn (facet
// normals) and the distinct facets they stand for, the edges drawn (real ones
// and all), the table of maps; for a sum, arcs of P and of Q both drawn; the
// polytope's drawn facets, and a facet clicked on it against the exact
// polytope 'minksum sum --method cgm --exact' (or 'gen --exact') writes.
import { check, checkPage, checkPickedFacet, clickFacet, launch, minksum, minksumJson, open, options, readOff, visibleFacet } from './lib.mjs';
import { join } from 'node:path';

const kind = process.argv[2];
process.argv.splice(2, 1);
const o = options();
const CASES = {
  single: ['truncated-cube@rot:2'],
  sum: ['dioctagonal:17', 'dioctagonal:17@rot:100,0,0,99'],
};
const operands = CASES[kind];
check(operands, `unknown case '${kind}' (single, sum)`);
const html = join(o.out, `cgm-${kind}.html`);
minksum(o.minksum, ['cgm', ...operands, '--html', html]);
const cgm = minksumJson(o.minksum, ['cgm', ...operands, '--json']);
const offFile = join(o.out, `cgm-${kind}.off`);
if (operands.length === 2) minksum(o.minksum, ['sum', ...operands, '--method', 'cgm', '--exact', '-o', offFile]);
else minksum(o.minksum, ['gen', operands[0], '--exact', '-o', offFile]);
const off = readOff(offFile);

const browser = await launch();
try {
  const { page, log } = await open(browser.context, html);
  await checkPage(page, log, `cgm ${kind}`);
  const s = await page.evaluate(() => ({ real: window.minksum.cgmRealVertices, facets: window.minksum.cgmDrawnFacets,
                                         edges: window.minksum.cgmEdges, drawn: window.minksum.drawnFacets }));
  const sum = (f) => cgm.maps.reduce((t, m) => t + f(m), 0);
  check(s.real === sum((m) => m.real_vertices), `cgm ${kind}: ${s.real} real vertices drawn, minksum cgm says ${sum((m) => m.real_vertices)}`);
  check(s.facets === cgm.facets, `cgm ${kind}: the dots stand for ${s.facets} facets, the polytope has ${cgm.facets}`);
  const allEdges = Object.values(s.edges).reduce((a, b) => a + b, 0);
  check(allEdges === sum((m) => m.halfedges / 2), `cgm ${kind}: ${allEdges} edges drawn, the maps have ${sum((m) => m.halfedges / 2)}`);
  check(allEdges - (s.edges.artificial || 0) === sum((m) => m.real_edges), `cgm ${kind}: ${allEdges - (s.edges.artificial || 0)} real edges drawn, minksum cgm says ${sum((m) => m.real_edges)}`);
  if (operands.length === 2) check(s.edges.p > 0 && s.edges.q > 0, `cgm ${kind}: arcs of P and Q: ${JSON.stringify(s.edges)}`);
  const table = await page.$$eval('#maps tr', (rows) => rows.slice(1).map((r) => [...r.children].slice(1).map((c) => Number(c.textContent))));
  table.forEach((row, k) => {
    const m = cgm.maps[k];
    check(JSON.stringify(row) === JSON.stringify([m.vertices, m.halfedges, m.faces, m.real_vertices, m.real_edges]), `cgm ${kind}: map ${k} row ${row} differs from minksum cgm --json`);
  });
  const key = operands.length === 2 ? 'sum' : 'polytope';
  check(s.drawn[key] === cgm.facets, `cgm ${kind}: ${s.drawn[key]} facets drawn, minksum cgm says ${cgm.facets}`);
  await page.screenshot({ path: join(o.out, `cgm-${kind}.png`) });
  const f = await visibleFacet(page, key);
  check(f >= 0, `cgm ${kind}: no facet of the polytope is visible`);
  const picked = await clickFacet(page, key, f, `cgm ${kind}`);
  checkPickedFacet(picked, off, `cgm ${kind}`);
  console.log(`cgm ${kind}: ${s.real} facet normals, edges ${JSON.stringify(s.edges)}; picked facet ${picked.facet}: ${picked.plane}`);
} finally {
  await browser.close();
}
console.log(`PASS: cgm ${kind}`);
