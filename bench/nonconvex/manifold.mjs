#!/usr/bin/env node
// manifold.mjs: A ⊕ B by Manifold's minkowskiSum (npm manifold-3d, pinned in
// package-lock.json beside this file; WebAssembly under Node), the inexact
// competitor of bench/nonconvex (docs/nonconvex.md, "Speed"); with --op
// erode, A ⊖ B by its minkowskiDifference, and with --op open,
// (A ⊖ B) ⊕ B by minkowskiDifference then minkowskiSum.
//
// Usage: node manifold.mjs A.stl B.stl [--reps R] [--op sum|erode|open]
//
// A and B are binary STL files, as `minksum gen SPEC -o A.stl --binary`
// writes them: minksum's exact triangulation of every face, each coordinate
// the nearest float.  Floats are what Manifold's JavaScript API takes
// (Mesh.vertProperties is a Float32Array), so nothing is rounded here: the
// corners of the triangles are welded by equal coordinates into an indexed
// mesh and given to `new Manifold(mesh)`.
//
// Timed: `a.minkowskiSum(b)` (or the --op's calls) and the evaluation of its result (`status()`),
// R times (default 3), each time on operands built afresh; the median is
// reported.  Not timed: loading the module, reading the files, building the
// operands.  The WebAssembly build of manifold-3d runs on one thread.  Prints one JSON object on standard output:
//   {"manifold": version, "call": ..., "reps": R, "seconds": median,
//    "runs": [...], "volume": ..., "vertices": ..., "triangles": ...,
//    "genus": ..., "status": ..., "a": {...}, "b": {...}}
// where a and b give each operand's vertices, triangles and volume as
// Manifold sees them.  Exit status: 2 for a usage error, 3 for a file that is
// not a closed binary STL solid (one line on stderr naming the file, the
// place and the problem), 1 when standard output cannot be written.
import { readFileSync, writeSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';
import Module from 'manifold-3d';

const usage = 'usage: node manifold.mjs A.stl B.stl [--reps R] [--op sum|erode|open]';
const OPS = {
  sum: { call: 'Manifold.minkowskiSum', symbol: '⊕', run: (a, b) => a.minkowskiSum(b) },
  erode: { call: 'Manifold.minkowskiDifference', symbol: '⊖', run: (a, b) => a.minkowskiDifference(b) },
  open: {
    call: 'Manifold.minkowskiDifference, then minkowskiSum',
    symbol: 'opened by',
    run: (a, b) => {
      const e = a.minkowskiDifference(b);
      const o = e.minkowskiSum(b);
      e.delete();
      return o;
    },
  },
};

function die(status, message) {
  process.stderr.write(`manifold.mjs: ${message}\n`);
  process.exit(status);
}

function parseArgs(argv) {
  const files = [];
  let reps = 3;
  let op = 'sum';
  for (let i = 0; i < argv.length; ++i) {
    const arg = argv[i];
    if (arg === '--help' || arg === '-h') {
      writeSync(1, `${usage}\n\nA ⊕ B by Manifold's minkowskiSum (--op erode: A ⊖ B by minkowskiDifference; --op open: ` +
        'minkowskiDifference then minkowskiSum); A and B binary STL (minksum gen SPEC -o A.stl --binary).\n' +
        'Times minkowskiSum and status() R times (default 3) and prints the median, the volume, the counts\n' +
        'and Manifold\'s version as one JSON object.\n');
      process.exit(0);
    } else if (arg === '--reps') {
      const r = argv[++i];
      if (r === undefined || !/^[1-9][0-9]{0,3}$/.test(r)) die(2, `--reps needs an integer 1..9999, got '${r ?? ''}'\n${usage}`);
      reps = Number(r);
    } else if (arg === '--op') {
      op = argv[++i];
      if (!Object.hasOwn(OPS, op ?? '')) die(2, `--op needs sum, erode or open, got '${op ?? ''}'\n${usage}`);
    } else if (arg.startsWith('-')) {
      die(2, `unknown option '${arg}'\n${usage}`);
    } else {
      files.push(arg);
    }
  }
  if (files.length !== 2) die(2, `needs two files, got ${files.length}\n${usage}`);
  return { files, reps, op };
}

// A binary STL as an indexed mesh: corners welded by equal float coordinates.
function readBinaryStl(path) {
  let bytes;
  try {
    bytes = readFileSync(path);
  } catch (e) {
    die(3, `${path}: cannot read (${e.code ?? e.message})`);
  }
  if (bytes.length < 84) die(3, `${path}: byte ${bytes.length}: too short for a binary STL (84-byte header and count)`);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const count = view.getUint32(80, true);
  const expected = 84 + 50 * count;
  if (bytes.length !== expected)
    die(3, `${path}: byte 80: ${count} triangles need ${expected} bytes, the file has ${bytes.length} (not a binary STL?)`);
  if (count === 0) die(3, `${path}: byte 80: no triangles`);
  const index = new Map();
  const coords = [];
  const triVerts = new Uint32Array(3 * count);
  for (let t = 0; t < count; ++t) {
    const at = 84 + 50 * t + 12;  // after the normal
    for (let c = 0; c < 3; ++c) {
      const p = [0, 1, 2].map((k) => view.getFloat32(at + 12 * c + 4 * k, true));
      if (!p.every(Number.isFinite)) die(3, `${path}: triangle ${t + 1}: a coordinate is not finite`);
      const key = p.map((x) => (x === 0 ? 0 : x)).join(',');  // -0 and 0 are one point
      let v = index.get(key);
      if (v === undefined) {
        v = coords.length / 3;
        index.set(key, v);
        coords.push(...p);
      }
      triVerts[3 * t + c] = v;
    }
  }
  return { vertProperties: Float32Array.from(coords), triVerts };
}

function solid(wasm, path, mesh) {
  const { Manifold, Mesh } = wasm;
  let m;
  try {
    m = new Manifold(new Mesh({ numProp: 3, ...mesh }));
  } catch (e) {
    die(3, `${path}: Manifold refuses the mesh: ${e.code ?? e.message}`);
  }
  const status = m.status();
  if (status !== 'NoError') die(3, `${path}: Manifold refuses the mesh: ${status}`);
  return m;
}

function describe(m) {
  return { vertices: m.numVert(), triangles: m.numTri(), volume: m.volume() };
}

function median(xs) {
  const s = [...xs].sort((x, y) => x - y);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}

const { files, reps, op } = parseArgs(process.argv.slice(2));
// The installed version: the package.json of the directory the module was
// loaded from (the package exports neither that file nor a require() entry).
function manifoldVersion() {
  for (let dir = dirname(fileURLToPath(import.meta.resolve('manifold-3d'))); dir !== dirname(dir); dir = dirname(dir)) {
    try {
      const p = JSON.parse(readFileSync(join(dir, 'package.json'), 'utf8'));
      if (p.name === 'manifold-3d') return p.version;
    } catch {
      // no package.json here: look in the parent
    }
  }
  return 'unknown';
}
const version = manifoldVersion();
const wasm = await Module();
wasm.setup();
const meshes = files.map(readBinaryStl);

// Each repetition sums operands built afresh from the meshes (untimed), so
// that nothing Manifold caches on its objects carries over between runs.
const runs = [];
let a = null, b = null, result = null;
for (let r = 0; r < reps; ++r) {
  for (const m of [a, b, result]) if (m) m.delete();
  a = solid(wasm, files[0], meshes[0]);
  b = solid(wasm, files[1], meshes[1]);
  const t = performance.now();
  result = OPS[op].run(a, b);
  const status = result.status();
  runs.push((performance.now() - t) / 1000);
  if (status !== 'NoError') die(3, `${files[0]} ${OPS[op].symbol} ${files[1]}: ${OPS[op].call} gave status ${status}`);
}

const answer = {
  manifold: version,
  call: OPS[op].call,
  reps,
  seconds: median(runs),
  runs,
  volume: result.volume(),
  vertices: result.numVert(),
  triangles: result.numTri(),
  genus: result.genus(),
  status: result.status(),
  a: describe(a),
  b: describe(b),
};
try {
  writeSync(1, `${JSON.stringify(answer)}\n`);
} catch (e) {
  die(1, `cannot write standard output (${e.code ?? e.message})`);
}
