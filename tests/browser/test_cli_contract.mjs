// The pages' command-line contract, without a browser: usage errors exit 2,
// bad input exit 3 with one line naming the file and no page written, an
// unwritable page exit 1; a page is one file holding its data as valid JSON
// (every facet's vertices exactly on its plane, the provenance counts of
// 'minksum sum --json' also when the method does not record them), three.js's
// licence, and a Content-Security-Policy that forbids every request.
//   node test_cli_contract.mjs --minksum BIN --out DIR
import { check, options, planeValue, rat } from './lib.mjs';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const o = options();
function run(args) {
  const r = spawnSync(o.minksum, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
  return { status: r.status, out: r.stdout, err: r.stderr };
}
const page = join(o.out, 'contract.html');

// Usage errors: exit 2, nothing written.
for (const args of [['view'], ['view', 'cube'], ['view', 'cube', '-o', join(o.out, 'x.svg')],
                    ['view', 'cube', '-o', page, '--method', 'walk'], ['view', 'cube', 'cube', '-o', page, '--method', 'nope'],
                    ['view', 'a', 'b', 'c', '-o', page], ['cgm', 'cube', '--html', join(o.out, 'x.svg')],
                    ['simulate', '--html', join(o.out, 'x.png')], ['simulate', '-o', page, '--html', page]]) {
  rmSync(page, { force: true });
  const r = run(args);
  check(r.status === 2, `'minksum ${args.join(' ')}' exits ${r.status}, not 2 (${r.err.trim()})`);
  check(r.err.trim().split('\n').length === 1, `'minksum ${args.join(' ')}': not one line on stderr: ${r.err}`);
  check(!existsSync(page), `'minksum ${args.join(' ')}' wrote ${page}`);
}

// Bad input: exit 3, one line naming the file, no page.
const bad = join(o.out, 'open.off');
// Two triangles of an open surface (one face alone would be a flat polygon: docs/sweeps.md).
writeFileSync(bad, 'OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 3 1\n');
for (const args of [['view', bad, '-o', page], ['view', 'cube', bad, '-o', page], ['cgm', bad, '--html', page]]) {
  rmSync(page, { force: true });
  const r = run(args);
  check(r.status === 3, `'minksum ${args.join(' ')}' exits ${r.status}, not 3`);
  check(r.err.trim().split('\n').length === 1 && r.err.includes(bad), `'minksum ${args.join(' ')}': stderr does not name ${bad} in one line: ${r.err}`);
  check(!existsSync(page), `'minksum ${args.join(' ')}' wrote ${page}`);
}

// Output not writable: exit 1.
for (const args of [['view', 'cube', '-o', join(o.out, 'no-such-dir', 'p.html')],
                    ['simulate', '--frames', '4', '--html', join(o.out, 'no-such-dir', 'p.html')]]) {
  const r = run(args);
  check(r.status === 1, `'minksum ${args.join(' ')}' exits ${r.status}, not 1`);
}

function pageData(file) {
  const text = readFileSync(file, 'utf8');
  const marker = '<script type="application/json" id="minksum-data">';
  const start = text.indexOf(marker);
  check(start >= 0, `${file}: no data`);
  const body = text.slice(start + marker.length, text.indexOf('</script>', start));
  check(/Content-Security-Policy" content="default-src 'none'/.test(text), `${file}: no Content-Security-Policy forbidding requests`);
  check(text.includes('Copyright © 2010-') && text.includes('three.js authors') && text.includes('Permission is hereby granted'), `${file}: three.js's licence is missing`);
  check(!/<script[^>]*\ssrc=|<link[^>]*\shref=/i.test(text), `${file}: the page loads another file`);
  return JSON.parse(body);
}

// Every facet's vertices lie exactly on its plane.
function checkPlanes(s, name) {
  s.facets.forEach((loop, f) => {
    for (const v of loop) check(planeValue(s.planes[f], s.exact[v].split(' '))[0] === 0n, `${name}: vertex ${v} is not on the plane of facet ${f}`);
  });
  check(s.facets.length === s.counts.facets && s.exact.length === s.counts.vertices && s.xyz.length === 3 * s.counts.vertices, `${name}: counts differ from the arrays`);
  s.exact.forEach((e, v) => {
    const [x] = e.split(' ').map(rat);
    check(Math.abs(Number(x[0]) / Number(x[1]) - s.xyz[3 * v]) <= 1e-9 * (1 + Math.abs(s.xyz[3 * v])), `${name}: vertex ${v} drawn far from its exact place`);
  });
}

// A method that does not record provenance: computed afterwards, same counts.
for (const method of ['chms', 'walk']) {
  const r = run(['view', 'cube@rot:2', 'octahedron', '--method', method, '-o', page, '--json']);
  check(r.status === 0, `view --method ${method}: exit ${r.status} ${r.err}`);
  JSON.parse(r.out);
  const d = pageData(page);
  const sum = JSON.parse(run(['sum', 'cube@rot:2', 'octahedron', '--method', 'walk', '--json']).out);
  const s = d.solids[2];
  check(s.counts.facets === sum.facets && s.counts.vertices === sum.vertices, `view --method ${method}: counts differ from minksum sum`);
  const count = {};
  for (const name of d.origins) count[name] = 0;
  for (const k of s.origin) ++count[d.origins[k]];
  check(JSON.stringify(count) === JSON.stringify(sum.facet_types), `view --method ${method}: provenance ${JSON.stringify(count)}, minksum sum says ${JSON.stringify(sum.facet_types)}`);
  check(s.volume === sum.volume, `view --method ${method}: volume ${s.volume}, minksum sum says ${sum.volume}`);
  for (const x of d.solids) checkPlanes(x, `view --method ${method} ${x.name}`);
}

// Non-convex solids (docs/nonconvex.md): alone and in a sum, valid JSON, the
// planes exact, and each face cut into its corners' number less two
// triangles of its own vertices (which the page draws instead of a fan).
for (const args of [['view', 'tube'], ['view', 'tube', 'box:1/2:1/2:1/2'], ['view', 'lshape', 'tube@scale:1/4']]) {
  const r = run([...args, '-o', page, '--json']);
  check(r.status === 0, `'minksum ${args.join(' ')}': exit ${r.status} ${r.err}`);
  JSON.parse(r.out);
  const d = pageData(page);
  for (const x of d.solids) {
    const name = `${args.join(' ')}: ${x.name}`;
    checkPlanes(x, name);
    if (!x.triangles) continue;
    check(x.triangles.length === 3 * x.triangle_facet.length, `${name}: ${x.triangles.length} triangle corners for ${x.triangle_facet.length} triangles`);
    const per = new Array(x.facets.length).fill(0);
    x.triangle_facet.forEach((f, t) => {
      ++per[f];
      for (let k = 0; k < 3; ++k)
        check(x.facets[f].includes(x.triangles[3 * t + k]), `${name}: triangle ${t} has a corner off its facet ${f}`);
    });
    per.forEach((n, f) => check(n === x.facets[f].length - 2, `${name}: facet ${f} of ${x.facets[f].length} corners cut into ${n} triangles`));
  }
}

// A title with '</script>' in it stays inside the data.
const r = run(['view', 'tetra', '-o', page, '--title', 'a </script><b>title</b>']);
check(r.status === 0, `view --title: exit ${r.status}`);
const d = pageData(page);
check(d.title === 'a </script><b>title</b>', `the title came back as ${d.title}`);
checkPlanes(d.solids[0], 'tetra');
console.log('PASS: the pages\' command-line contract');
