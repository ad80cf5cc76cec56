// What the browser tests share: minksum run as a child process, Debian's
// chromium driven by playwright-core (web/node_modules) with the network
// off, a page loaded from a file:// URL and the checks every page gets,
// and exact rational arithmetic on the strings the pages and the CLI print.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

export const CHROMIUM = process.env.MINKSUM_CHROMIUM || '/usr/bin/chromium';
const here = fileURLToPath(new URL('.', import.meta.url));
const require = createRequire(join(here, '../../web/package.json'));

export function fail(message) {
  console.error(`FAIL: ${message}`);
  process.exit(1);
}
export function check(condition, message) {
  if (!condition) fail(message);
}

// argv: --minksum BIN --out DIR
export function options() {
  const o = {};
  const a = process.argv.slice(2);
  for (let i = 0; i + 1 < a.length; i += 2) o[a[i].replace(/^--/, '')] = a[i + 1];
  if (!o.minksum || !o.out) fail('usage: node TEST.mjs --minksum BIN --out DIR');
  mkdirSync(o.out, { recursive: true });
  return o;
}

export function minksum(bin, args) {
  return execFileSync(bin, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
}
export function minksumJson(bin, args) {
  return JSON.parse(minksum(bin, args));
}

// Exit 77 (ctest: skipped) when the browser is missing.  The network is off
// unless `offline` is false (a page served on the loopback interface; the
// test then refuses every other request itself).
export async function launch({ offline = true } = {}) {
  if (!existsSync(CHROMIUM)) {
    console.log(`SKIP: ${CHROMIUM} is missing (Debian package chromium; 'make setup' installs it)`);
    process.exit(77);
  }
  const { chromium } = require('playwright-core');
  const profile = mkdtempSync(join(tmpdir(), 'minksum-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    offline,
    viewport: { width: 1280, height: 800 },
    args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
           '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
  });
  return { context, close: async () => { await context.close(); rmSync(profile, { recursive: true, force: true }); } };
}

// Opens the page file in a new tab with every request but file:// aborted,
// waits for window.minksumReady; returns the page and its log of errors and
// blocked requests.
export async function open(context, file, timeoutMs = 120000) {
  const page = await context.newPage();
  const log = { errors: [], blocked: [], files: [] };
  page.on('console', (m) => { if (m.type() === 'error') log.errors.push(m.text()); });
  page.on('pageerror', (e) => log.errors.push(String(e)));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:')) { log.files.push(url); return route.continue(); }
    log.blocked.push(url);
    return route.abort();
  });
  const t0 = Date.now();
  await page.goto(pathToFileURL(resolve(file)).href);
  await page.waitForFunction(() => window.minksumReady === true, null, { timeout: timeoutMs, polling: 50 });
  log.wallMs = Date.now() - t0;
  return { page, log };
}

// The checks every page gets: no console error, no request but the page's own
// file,
// a canvas that is not blank (variance of its pixels' grey levels).
export async function checkPage(page, log, name, minVariance = 20) {
  check(log.errors.length === 0, `${name}: console errors: ${log.errors.join(' | ')}`);
  check(log.blocked.length === 0, `${name}: the page asked for ${log.blocked.join(', ')}`);
  check(log.files.length === 1, `${name}: the page is not one file: it loaded ${log.files.join(', ')}`);
  const variance = await page.evaluate(() => {
    window.minksum.render();  // the drawing buffer is kept only until the task ends
    const src = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = src.width; c.height = src.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let s = 0, s2 = 0, n = 0;
    for (let i = 0; i < d.length; i += 16) {
      const g = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
      s += g; s2 += g * g; ++n;
    }
    return s2 / n - (s / n) * (s / n);
  });
  check(variance > minVariance, `${name}: the canvas looks blank (grey-level variance ${variance.toFixed(2)})`);
  return variance;
}

// ---------------------------------------------------------------------------
// Exact rationals as [numerator, denominator] BigInts (denominator > 0).

export function rat(text) {
  const [p, q] = text.split('/');
  const n = BigInt(p), d = q === undefined ? 1n : BigInt(q);
  return d < 0n ? [-n, -d] : [n, d];
}
export function ratCompare(a, b) {  // sign of a - b
  const x = a[0] * b[1] - b[0] * a[1];
  return x > 0n ? 1 : x < 0n ? -1 : 0;
}
function gcd(a, b) {
  a = a < 0n ? -a : a; b = b < 0n ? -b : b;
  while (b) [a, b] = [b, a % b];
  return a;
}
// a x + b y + c z - d for the plane "a b c d" at the point ["x","y","z"], as a rational.
export function planeValue(plane, point) {
  const [a, b, c, d] = plane.split(' ').map(BigInt);
  const [x, y, z] = point.map(rat);
  const den = x[1] * y[1] * z[1];
  const num = a * x[0] * y[1] * z[1] + b * y[0] * x[1] * z[1] + c * z[0] * x[1] * y[1] - d * den;
  return [num, den];
}
export function planeIsPrimitive(plane) {
  return plane.split(' ').map(BigInt).reduce((g, v) => gcd(g, v), 0n) === 1n;
}

// An OFF file as minksum writes it with --exact: the vertices' exact
// coordinate strings and the faces (vertex index loops).
export function readOff(file) {
  const tokens = readFileSync(file, 'utf8').split('\n').filter((l) => l.trim() && !l.startsWith('#'));
  check(tokens[0].trim() === 'OFF', `${file}: not an OFF file`);
  const [nv, nf] = tokens[1].trim().split(/\s+/).map(Number);
  const vertices = [], faces = [];
  for (let i = 0; i < nv; ++i) vertices.push(tokens[2 + i].trim().split(/\s+/));
  for (let i = 0; i < nf; ++i) faces.push(tokens[2 + nv + i].trim().split(/\s+/).slice(1).map(Number));
  return { vertices, faces };
}

// The facet the page shows, checked against a polytope minksum wrote (OFF,
// exact): the shown vertices are exactly the vertices of one face of the
// file, every one of them on the shown plane, every vertex of the file on
// its inner side, and the plane's integers primitive (the canonical plane).
// `convex`: every vertex of the solid lies on the inner side of the plane
// (not so for a solid that is not convex).
export function checkPickedFacet(picked, off, name, convex = true) {
  check(picked && picked.plane, `${name}: no facet was picked`);
  const key = (p) => p.map((t) => { const r = rat(t); return `${r[0]}/${r[1]}`; }).join(' ');
  const shown = new Set(picked.exact.map((s) => key(s.split(' '))));
  const match = off.faces.find((f) => f.length === shown.size && f.every((v) => shown.has(key(off.vertices[v]))));
  check(match, `${name}: facet ${picked.facet} (${[...shown].join('; ')}) is not a face of the polytope minksum wrote`);
  for (const s of picked.exact)
    check(planeValue(picked.plane, s.split(' '))[0] === 0n, `${name}: vertex ${s} is not on the shown plane ${picked.plane}`);
  for (const v of convex ? off.vertices : [])
    check(planeValue(picked.plane, v)[0] <= 0n, `${name}: vertex ${v.join(' ')} lies outside the shown plane ${picked.plane}`);
  check(planeIsPrimitive(picked.plane), `${name}: the shown plane ${picked.plane} is not primitive`);
}

// Clicks the canvas where facet f of solid `key` shows, checks the page
// picked that facet and shows its plane; returns what the page picked.
export async function clickFacet(page, key, f, name) {
  const at = await page.evaluate(([k, i]) => window.minksum.facetScreenPoint(k, i), [key, f]);
  check(at, `${name}: facet ${f} of ${key} is not visible`);
  await page.mouse.click(at.x, at.y);
  const picked = await page.evaluate(() => window.minksum.picked);
  check(picked && picked.solid === key && picked.facet === f, `${name}: clicking facet ${f} of ${key} picked ${JSON.stringify(picked && [picked.solid, picked.facet])}`);
  const shownPlane = await page.getAttribute('#pick-plane', 'data-plane');
  check(shownPlane === picked.plane, `${name}: the panel shows plane ${shownPlane}, the page's data ${picked.plane}`);
  return picked;
}

// A facet of solid `key` the camera sees (the one under the pointer at the
// centre of the solid's image, found by the page's own picking).
export async function visibleFacet(page, key) {
  return page.evaluate((k) => {
    const m = window.minksum;
    const solid = (m.data.solids || [m.data.obstacle, m.data.robot]).find((s) => s.role === k);
    const n = solid ? solid.facets.length : 0;
    for (let f = 0; f < n; ++f) if (m.facetScreenPoint(k, f)) return f;
    return -1;
  }, key);
}

// ---------------------------------------------------------------------------
// Exact values shown with their decimals (web/src/exact.js).

// A decimal as the page prints it ("58.6666666667", "-1.5e-30") as the
// exact rational M * 10^E: [M, E].
function decimalValue(text) {
  const m = /^(-?)([0-9]+)(?:\.([0-9]+))?(?:e(-?[0-9]+))?$/.exec(text);
  check(m, `'${text}' is not a decimal`);
  const frac = m[3] || '';
  return [BigInt(m[1] + m[2] + frac), Number(m[4] || 0) - frac.length];
}
// True when the decimal d is p/q rounded to its last digit (within half a
// unit of it), or, `exact`, equal to p/q.
function decimalMatches(text, [p, q], exact) {
  const [mant, e] = decimalValue(text);
  // |mant * 10^e - p/q| <= 10^e / 2, scaled by 2 q 10^-e (or by 2 q when e >= 0).
  const diff = e >= 0 ? mant * 10n ** BigInt(e) * q - p : mant * q - p * 10n ** BigInt(-e);
  const abs = diff < 0n ? -diff : diff;
  if (exact) return diff === 0n;
  return 2n * abs <= (e >= 0 ? q * 10n ** BigInt(e) : q);
}

// Every exact value on the page (or under `root`) with its decimal beside
// it: a fraction or a long integer has a decimal that is its value rounded
// to the digits shown ("≈") or equal to it ("="), checked exactly with
// BigInt; an exact text longer than 40 characters is folded in a <details>.
// Points ("x y z", "N: x y z", "x  y  z") have the decimals of each
// coordinate.  Returns the number of values checked, at least `atLeast`.
export async function checkDecimals(page, name, atLeast = 1, root = '#side') {
  const values = await page.$$eval(`${root} .value`, (vs) => vs.map((v) => {
    const exact = v.querySelector('.exact');
    const decimal = v.querySelector('.decimal');
    return { id: exact.id, exact: exact.textContent, decimal: decimal ? decimal.textContent : null,
             folded: !!exact.closest('details') };
  }));
  let checked = 0;
  for (const v of values) {
    if (v.id === 'pick-plane') continue;  // a plane: its decimal, when shown, is of its long coefficients
    const parts = v.exact.replace(/^[0-9]+: /, '').trim().split(/\s+/);
    const needs = parts.some((t) => t.includes('/') || t.replace('-', '').length > 15);
    check(!needs || v.decimal, `${name}: the exact value ${v.exact.slice(0, 80)} has no decimal beside it`);
    check((v.exact.length > 40) === v.folded, `${name}: the exact value ${v.exact.slice(0, 80)} (${v.exact.length} characters) is ${v.folded ? '' : 'not '}folded`);
    if (!v.decimal) continue;
    const exact = v.decimal.startsWith('= ');
    check(exact || v.decimal.startsWith('≈ '), `${name}: decimal '${v.decimal}'`);
    const shown = v.decimal.slice(2).replace(/^\(|\)$/g, '').split(', ');
    check(shown.length === parts.length, `${name}: ${shown.length} decimals for ${parts.length} exact values: ${v.decimal} / ${v.exact}`);
    parts.forEach((t, i) => check(decimalMatches(shown[i], rat(t), exact),
      `${name}: the decimal ${shown[i]} is not ${t} ${exact ? 'exactly' : 'rounded'}`));
    ++checked;
  }
  check(checked >= atLeast, `${name}: ${checked} exact values with decimals, expected at least ${atLeast}`);
  return checked;
}
