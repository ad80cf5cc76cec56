// Browser test of 'minksum view scene.wrl': a VRML scene with both node types
// (ExactPolyhedron and CubicalGaussianMap), written by 'minksum cgm P Q -o'.
// node test_scene.mjs --minksum BIN --out DIR
// Checked against the command line: the solids drawn and their facets (the
// scene's three polytopes against 'minksum sum/gen --json'), each map's facet
// normals and edges against 'minksum cgm --json' of its polytope (the sum's
// arcs of P and of Q both drawn), and a facet of the sum clicked against the
// exact polytope 'minksum sum --exact' writes.  Then the scene of 'minksum
// sum --scene': its shapes named by their comments, coloured as a sum's.
import { check, checkDecimals, checkPage, checkPickedFacet, clickFacet, launch, minksum, minksumJson, open, options, readOff } from './lib.mjs';
import { join } from 'node:path';

const o = options();
const P = 'truncated-cube@rot:2', Q = 'octahedron@rot:1,2,3,7';
const wrl = join(o.out, 'scene.wrl'), html = join(o.out, 'scene.html');
minksum(o.minksum, ['cgm', P, Q, '-o', wrl]);
const view = minksumJson(o.minksum, ['view', wrl, '-o', html, '--json']);
check(view.shapes.length === 6, `scene: ${view.shapes.length} shapes, expected P, Q, S and their three maps`);
const offFile = join(o.out, 'scene-sum.off');
minksum(o.minksum, ['sum', P, Q, '--exact', '-o', offFile]);
const off = readOff(offFile);
const expected = [minksumJson(o.minksum, ['stats', P, '--json']), minksumJson(o.minksum, ['stats', Q, '--json']),
                  minksumJson(o.minksum, ['sum', P, Q, '--json'])];
const maps = [minksumJson(o.minksum, ['cgm', P, '--json']), minksumJson(o.minksum, ['cgm', Q, '--json']),
              minksumJson(o.minksum, ['cgm', P, Q, '--json'])];

const browser = await launch();
try {
  const { page, log } = await open(browser.context, html);
  await checkPage(page, log, 'scene');
  const s = await page.evaluate(() => ({ drawn: window.minksum.drawnFacets, cgms: window.minksum.sceneCgms }));
  expected.forEach((e, i) => {
    check(s.drawn[`solid${i}`] === e.facets, `scene: solid ${i}: ${s.drawn[`solid${i}`]} facets drawn, minksum says ${e.facets}`);
    check(s.drawn[`cgm${i}`] === e.facets, `scene: the polytope of map ${i}: ${s.drawn[`cgm${i}`]} facets drawn, minksum says ${e.facets}`);
  });
  check(s.cgms.length === 3, `scene: ${s.cgms.length} maps drawn`);
  s.cgms.forEach((c, i) => {
    const m = maps[i];
    const sum = (f) => m.maps.reduce((t, x) => t + f(x), 0);
    check(c.realVertices === sum((x) => x.real_vertices), `scene: map ${c.name}: ${c.realVertices} facet normals drawn, minksum cgm says ${sum((x) => x.real_vertices)}`);
    check(c.facets === m.facets, `scene: map ${c.name}: the dots stand for ${c.facets} facets, the polytope has ${m.facets}`);
    const all = Object.values(c.edges).reduce((a, b) => a + b, 0);
    check(all === sum((x) => x.halfedges / 2), `scene: map ${c.name}: ${all} edges drawn, the maps have ${sum((x) => x.halfedges / 2)}`);
    check(all - (c.edges.artificial || 0) === sum((x) => x.real_edges), `scene: map ${c.name}: ${all - (c.edges.artificial || 0)} arcs drawn, minksum cgm says ${sum((x) => x.real_edges)}`);
  });
  check(s.cgms[2].edges.p > 0 && s.cgms[2].edges.q > 0, `scene: the sum's map has arcs of P and of Q: ${JSON.stringify(s.cgms[2].edges)}`);
  // Each polytope named with what it is, in a colour of its own that the
  // solid is drawn in; the legend names every colour of the maps and of the
  // sum's facets by provenance.
  const shapes = await page.$$eval('#side [data-shape]', (rows) => rows.map((r) => ({
    name: r.dataset.shape, role: r.dataset.role, text: r.textContent, swatch: getComputedStyle(r.querySelector('.sw')).backgroundColor })));
  check(JSON.stringify(shapes.map((r) => [r.name, r.role])) === JSON.stringify([['P', 'a'], ['Q', 'b'], ['S', 'sum']]),
        `scene: shapes ${JSON.stringify(shapes)}`);
  check(shapes[0].text.includes('first operand of S = P ⊕ Q') && shapes[1].text.includes('second operand of S = P ⊕ Q') &&
        shapes[2].text.includes('the sum S = P ⊕ Q'), `scene: shape captions ${shapes.map((r) => r.text).join(' | ')}`);
  check(new Set(shapes.map((r) => r.swatch)).size === 3, `scene: the shapes share colours ${shapes.map((r) => r.swatch)}`);
  const roles = await page.evaluate(() => window.minksum.data.solids.map((d) => d.role));
  check(JSON.stringify(roles) === JSON.stringify(['a', 'b', 'sum']), `scene: solids of the roles ${roles}`);
  const legend = await page.$$eval('#legend .row', (rows) => rows.map((r) => r.textContent));
  for (const want of ['arcs of the first operand', 'arcs of the second operand', 'artificial edges', 'dots: facet normals',
                      'edge of A ⊕ edge of B'])
    check(legend.some((t) => t.includes(want)), `scene: the legend lacks '${want}': ${legend.join(' | ')}`);
  await checkDecimals(page, 'scene', 1);
  await page.screenshot({ path: join(o.out, 'scene.png') });
  // A facet of S the camera sees (visibleFacet looks solids up by role; here every solid is a 'polytope').
  const f = await page.evaluate(() => {
    const n = window.minksum.data.solids[2].facets.length;
    for (let i = 0; i < n; ++i) if (window.minksum.facetScreenPoint('solid2', i)) return i;
    return -1;
  });
  check(f >= 0, 'scene: no facet of the sum S is visible');
  const picked = await clickFacet(page, 'solid2', f, 'scene');
  checkPickedFacet(picked, off, 'scene');
  console.log(`scene: ${view.shapes.length} shapes; maps ${s.cgms.map((c) => `${c.name} ${c.realVertices} normals`).join(', ')}; picked facet ${picked.facet} of S: ${picked.plane}`);

  // The scene 'minksum sum --scene' writes (ExactPolyhedron nodes only, with
  // comment lines "# A = NAME", "# S = A ⊕ B"): each shape named with its
  // file or catalog name and what it is, in the colours of a sum.
  const sumWrl = join(o.out, 'sum-scene.wrl'), sumHtml = join(o.out, 'sum-scene.html');
  minksum(o.minksum, ['sum', P, Q, '--scene', '-o', sumWrl]);
  minksum(o.minksum, ['view', sumWrl, '-o', sumHtml]);
  const second = await open(browser.context, sumHtml);
  await checkPage(second.page, second.log, 'sum scene');
  const rows = await second.page.$$eval('#side [data-shape]', (rs) => rs.map((r) => ({
    name: r.dataset.shape, role: r.dataset.role, text: r.textContent, swatch: getComputedStyle(r.querySelector('.sw')).backgroundColor })));
  check(JSON.stringify(rows.map((r) => [r.name, r.role])) === JSON.stringify([['A', 'a'], ['B', 'b'], ['S', 'sum']]),
        `sum scene: shapes ${JSON.stringify(rows)}`);
  check(rows[0].text.includes(`${P}, first operand of S = A ⊕ B`) && rows[1].text.includes(`${Q}, second operand of S = A ⊕ B`) &&
        rows[2].text.includes('the sum S = A ⊕ B'), `sum scene: shape captions ${rows.map((r) => r.text).join(' | ')}`);
  check(new Set(rows.map((r) => r.swatch)).size === 3, `sum scene: the shapes share colours ${rows.map((r) => r.swatch)}`);
  await second.page.screenshot({ path: join(o.out, 'sum-scene.png') });
} finally {
  await browser.close();
}
console.log('PASS: scene');
