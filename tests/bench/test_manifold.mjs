#!/usr/bin/env node
// Test of bench/nonconvex/manifold.mjs, Manifold's side of `make
// bench-nonconvex`: its answers on sums with closed forms, and its contract
// (exit statuses, one stderr line naming the file).
//
// Usage: node test_manifold.mjs --minksum PATH --out DIR
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const script = join(here, '..', '..', 'bench', 'nonconvex', 'manifold.mjs');
const lock = join(here, '..', '..', 'bench', 'nonconvex', 'package-lock.json');

const arg = (name) => {
  const i = process.argv.indexOf(name);
  if (i < 0 || i + 1 >= process.argv.length) {
    process.stderr.write(`usage: node test_manifold.mjs --minksum PATH --out DIR (missing ${name})\n`);
    process.exit(2);
  }
  return process.argv[i + 1];
};
const minksum = arg('--minksum');
const out = arg('--out');
mkdirSync(out, { recursive: true });

function gen(spec, file) {
  const path = join(out, file);
  const r = spawnSync(minksum, ['gen', spec, '-o', path, '--binary'], { encoding: 'utf8' });
  assert.equal(r.status, 0, `minksum gen ${spec}: ${r.stderr}`);
  return path;
}

function manifold(args, stdout = 'pipe') {
  return spawnSync(process.execPath, [script, ...args], { encoding: 'utf8', stdio: ['ignore', stdout, 'pipe'] });
}

function sum(a, b) {
  const r = manifold([a, b, '--reps', '2']);
  assert.equal(r.status, 0, r.stderr);
  const lines = r.stdout.trim().split('\n');
  assert.equal(lines.length, 1, r.stdout);
  return JSON.parse(lines[0]);
}

const cube = gen('cube', 'cube.stl');              // [-1, 1]^3
const quarter = gen('cube@scale:1/4', 'quarter.stl');  // [-1/4, 1/4]^3
const tube = gen('tube', 'tube.stl');              // [-1, 1]^3 minus a hole of side 1 along z

// cube ⊕ cube = [-2, 2]^3: volume 64, 8 vertices, 12 triangles.  Every
// coordinate is a float, so Manifold's input is exact and so is its answer.
const cc = sum(cube, cube);
assert.equal(cc.volume, 64);
assert.equal(cc.vertices, 8);
assert.equal(cc.triangles, 12);
assert.equal(cc.genus, 0);
assert.equal(cc.status, 'NoError');
assert.equal(cc.call, 'Manifold.minkowskiSum');
assert.equal(cc.reps, 2);
assert.equal(cc.runs.length, 2);
assert.ok(cc.seconds >= Math.min(...cc.runs) && cc.seconds <= Math.max(...cc.runs), JSON.stringify(cc.runs));
assert.deepEqual(cc.a, { vertices: 8, triangles: 12, volume: 8 });
// The version reported is the one pinned in the lock file.
const pinned = JSON.parse(readFileSync(lock, 'utf8')).packages['node_modules/manifold-3d'].version;
assert.equal(cc.manifold, pinned);

// tube ⊕ [-1/4, 1/4]^3 = [-5/4, 5/4]^3 minus a hole of side 1/2 through its
// height 5/2: volume 125/8 − 5/8 = 15, genus 1 (a non-convex sum).
const tq = sum(tube, quarter);
assert.ok(Math.abs(tq.volume - 15) <= 15 * 1e-12, `tube ⊕ cube/4: volume ${tq.volume}, expected 15`);
assert.equal(tq.genus, 1);
assert.deepEqual(tq.a, { vertices: 16, triangles: 32, volume: 6 });

// The contract: usage errors exit 2, bad files exit 3 with one line naming
// the file and the place, an unwritable standard output exits 1.
const oneLine = (r, ...needles) => {
  const lines = r.stderr.trim().split('\n');
  for (const n of needles) assert.ok(lines[0].includes(n), `${JSON.stringify(r.stderr)} lacks ${n}`);
  return lines;
};
let r = manifold([cube]);
assert.equal(r.status, 2, r.stderr);
r = manifold([cube, cube, '--reps', '0']);
assert.equal(r.status, 2, r.stderr);
r = manifold([cube, cube, '--bogus']);
assert.equal(r.status, 2, r.stderr);
const truncated = join(out, 'truncated.stl');
writeFileSync(truncated, readFileSync(cube).subarray(0, 100));
r = manifold([truncated, cube]);
assert.equal(r.status, 3, r.stderr);
assert.equal(oneLine(r, truncated, 'byte 80', 'triangles need').length, 1);
const missing = join(out, 'missing.stl');
r = manifold([cube, missing]);
assert.equal(r.status, 3, r.stderr);
assert.equal(oneLine(r, missing, 'cannot read').length, 1);
// An open surface: the cube without its last two triangles.
const open = join(out, 'open.stl');
const bytes = Buffer.from(readFileSync(cube).subarray(0, 84 + 50 * 10));
bytes.writeUInt32LE(10, 80);
writeFileSync(open, bytes);
r = manifold([open, cube]);
assert.equal(r.status, 3, r.stderr);
assert.equal(oneLine(r, open, 'Manifold refuses the mesh').length, 1);
const full = spawnSync('sh', ['-c', `"${process.execPath}" "${script}" "${cube}" "${cube}" > /dev/full`],
                       { encoding: 'utf8' });
assert.equal(full.status, 1, full.stderr);
assert.equal(oneLine(full, 'cannot write standard output').length, 1);
process.stdout.write('test_manifold: cube ⊕ cube = 64, tube ⊕ cube/4 = 15, contract ok\n');
