// Browser test of 'minksum play': the server started with --no-open, its
// page loaded in chromium with every request refused but those to the
// server itself, P dragged and turned with simulated mouse moves.  After each
// move the answer the page shows (state, exact squared distance or depth,
// closest or common point, separating translation) is checked exactly
// against 'minksum query' on M (of the turned P) for the pose the page
// reports, and a turned P's answer names its certificate; the round-trip
// latency of the queries, measured in the page, is printed.
//   node test_play.mjs --minksum BIN --out DIR
import { spawn } from 'node:child_process';
import { join } from 'node:path';
import { check, checkDecimals, checkPage, fail, launch, minksumJson, options } from './lib.mjs';

const o = options();
const P = 'dodecahedron@rot:5', Q = 'truncated-cube@scale:3/2';

// The server; its first line is the URL.
const server = spawn(o.minksum, ['play', P, Q, '--no-open'], { stdio: ['ignore', 'pipe', 'pipe'] });
let serverErr = '';
server.stderr.on('data', (d) => { serverErr += d; });
// A failed check exits at once: the server goes with it.
process.on('exit', () => { if (server.exitCode === null && server.signalCode === null) server.kill('SIGKILL'); });
const exited = new Promise((res) => server.on('exit', (code, signal) => res({ code, signal })));
const url = await new Promise((res, rej) => {
  let out = '';
  const timer = setTimeout(() => rej(new Error(`no URL from minksum play within 60 s (stderr: ${serverErr})`)), 60000);
  server.stdout.on('data', (d) => {
    out += d;
    const nl = out.indexOf('\n');
    if (nl >= 0) { clearTimeout(timer); res(out.slice(0, nl)); }
  });
  server.on('exit', () => rej(new Error(`minksum play exited: ${serverErr}`)));
}).catch((e) => fail(e.message));
check(/^http:\/\/127\.0\.0\.1:\d+\/$/.test(url), `play: the first line is not the loopback URL: ${url}`);
const origin = url.replace(/\/$/, '');

// The same pose answered on M of the turned operand (play answers a turned
// P on the placed bodies, without M: the same exact values, but a common
// point of penetrating bodies may be another one than M's).
const turnedP = (pose) => (pose.rotate_p ? `${P}@rot:${pose.rotate_p}` : P);
function query(kind, pose) {
  return minksumJson(o.minksum, ['query', kind, turnedP(pose), Q, '--translate-p', pose.translate_p, '--json']);
}
// Whether the exact point "x  y  z" (as the page shows it) lies in the body
// SPEC translated by T: 'minksum query collide' of the point and the body.
function pointIn(text, spec, t) {
  const r = minksumJson(o.minksum, ['query', 'collide', `point:${text.trim().split(/\s+/).join(',')}`, spec, '--translate-q', t, '--json']);
  return r.status !== 'separate';
}

const browser = await launch({ offline: false });
let failed = null;
try {
  const page = await browser.context.newPage();
  const log = { errors: [], blocked: [], files: [] };
  page.on('console', (m) => { if (m.type() === 'error') log.errors.push(m.text()); });
  page.on('pageerror', (e) => log.errors.push(String(e)));
  await page.route('**/*', (route) => {
    const u = route.request().url();
    if (u.startsWith(origin + '/')) {
      if (route.request().resourceType() === 'document') log.files.push(u);
      return route.continue();
    }
    log.blocked.push(u);
    return route.abort();
  });
  const t0 = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => window.minksumReady === true && window.minksum.play && window.minksum.play.answer,
                             null, { timeout: 120000, polling: 50 });
  console.log(`play: page ready with its first answer in ${Date.now() - t0} ms`);
  await checkPage(page, log, 'play');
  const stats = { p: minksumJson(o.minksum, ['stats', P, '--json']), q: minksumJson(o.minksum, ['stats', Q, '--json']) };
  const drawn = await page.evaluate(() => window.minksum.drawnFacets);
  check(drawn.p === stats.p.facets && drawn.q === stats.q.facets, `play: facets drawn ${JSON.stringify(drawn)}, minksum stats says ${stats.p.facets} and ${stats.q.facets}`);

  // What the page shows once it is idle (no query under way or waiting), and
  // the pose it reports for that answer.
  async function shown() {
    await page.waitForFunction(() => {
      const p = window.minksum.play;
      return p.idle && p.answeredPose && JSON.stringify(p.answeredPose) === JSON.stringify(p.pose);
    }, null, { timeout: 30000, polling: 20 });
    return page.evaluate(() => {
      const t = (id) => { const e = document.getElementById(id); return e ? e.textContent : null; };
      return { pose: window.minksum.play.answeredPose, status: t('play-status'), value: t('play-value'),
        point: t('play-point-p'), pointQ: t('play-point-q'), direction: t('play-direction'),
        recomputed: window.minksum.play.answer.recomputed, certificate: window.minksum.play.answer.certificate,
        m: window.minksum.play.answer.m, how: t('play-m'), errors: window.minksum.play.errors.slice() };
    });
  }
  const seen = { separate: 0, touching: 0, penetrating: 0 };
  let checked = 0, turned = 0;
  async function checkShown(what) {
    const s = await shown();
    check(s.errors.length === 0, `play: ${what}: the page could not query: ${s.errors.join(' | ')}`);
    const d = query('distance', s.pose);
    const ctx = `play: ${what}, pose ${JSON.stringify(s.pose)}`;
    check(s.status === d.status, `${ctx}: the page shows ${s.status}, minksum query says ${d.status}`);
    if (d.status === 'penetrating' && s.pose.rotate_p)
      check(pointIn(s.point, turnedP(s.pose), s.pose.translate_p) && pointIn(s.point, Q, '0,0,0'),
            `${ctx}: the common point ${s.point} shown is not in both bodies`);
    else
      check(s.point === d.point_p_exact.join('  '), `${ctx}: the page shows the point ${s.point}, minksum query ${d.point_p_exact}`);
    if (s.pose.rotate_p)
      check(s.certificate && s.m === null && s.how.includes(`certificate: ${s.certificate}`),
            `${ctx}: a turned P answered without a certificate named (${s.certificate}, ${s.how})`);
    else
      check(s.certificate === null && s.m && !s.recomputed, `${ctx}: P as given not answered on M (${s.certificate})`);
    await checkDecimals(page, ctx, 0, '#play-answer');  // each fraction shown (value, points) with its decimal
    if (d.status === 'penetrating') {
      const dp = query('depth', s.pose);
      check(s.value === dp.squared_depth, `${ctx}: squared depth ${s.value} shown, minksum query depth says ${dp.squared_depth}`);
      check(s.direction === dp.direction.join('  '), `${ctx}: translation ${s.direction} shown, minksum query depth says ${dp.direction}`);
    } else {
      check(s.value === d.squared_distance, `${ctx}: squared distance ${s.value} shown, minksum query says ${d.squared_distance}`);
      if (d.status === 'separate')
        check(s.pointQ === d.point_q_exact.join('  '), `${ctx}: the page shows the point of Q ${s.pointQ}, minksum query ${d.point_q_exact}`);
    }
    ++seen[d.status];
    ++checked;
    if (s.pose.rotate_p) ++turned;
    return s;
  }

  const first = await checkShown('start');
  check(first.status === 'separate', `play: P starts ${first.status}, not apart from Q`);
  check(!first.pose.rotate_p, 'play: P starts turned');

  // Drag P to the right, through Q, in steps.
  const at = await page.evaluate(() => window.minksum.play && window.minksum.playScreenPoint());
  await page.mouse.move(at.x, at.y);
  await page.mouse.down();
  const width = await page.evaluate(() => document.querySelector('#view canvas').clientWidth);
  const steps = 14, dx = Math.round(width * 0.45 / steps);
  let x = at.x;
  for (let i = 0; i < steps; ++i) {
    x += dx;
    await page.mouse.move(x, at.y + (i % 3) - 1);
    await checkShown(`drag step ${i + 1}`);
  }
  await page.mouse.up();
  check(seen.penetrating > 0, `play: dragging P across Q never showed it penetrating (${JSON.stringify(seen)})`);
  await page.screenshot({ path: join(o.out, 'play-penetrating.png') });

  // Turn P with shift-drag: answered on the placed bodies (no M built for
  // the rotation), the answers stay exact.
  const at2 = await page.evaluate(() => window.minksum.playScreenPoint());
  await page.keyboard.down('Shift');
  await page.mouse.move(at2.x, at2.y);
  await page.mouse.down();
  for (let i = 0; i < 5; ++i) {
    await page.mouse.move(at2.x + 12 * (i + 1), at2.y - 7 * (i + 1));
    const s = await checkShown(`turn step ${i + 1}`);
    check(s.pose.rotate_p && s.certificate,
          `play: turning P sent no rotation, or its answer named no certificate (${JSON.stringify(s.pose)}, ${s.certificate})`);
  }
  await page.mouse.up();
  await page.keyboard.up('Shift');

  // And drag it back out, turned.
  const at3 = await page.evaluate(() => window.minksum.playScreenPoint());
  await page.mouse.move(at3.x, at3.y);
  await page.mouse.down();
  let last = null;
  for (let i = 0; i < 2 * steps; ++i) {
    await page.mouse.move(at3.x - dx * (i + 1), at3.y);
    last = await checkShown(`drag back step ${i + 1}`);
  }
  await page.mouse.up();
  check(last.status === 'separate', `play: dragged back twice as far, P is still ${last.status}`);
  const colour = await page.evaluate(() => document.querySelector('#play-answer .sw').style.background);
  check(colour === 'rgb(42, 143, 58)', `play: the state's swatch is ${colour}, not the green of separate`);
  await page.screenshot({ path: join(o.out, 'play-separate.png') });
  await checkPage(page, log, 'play (after the drags)');

  // A burst of moves as a user makes them (no waiting): the page sends the
  // latest pose when the previous answer arrives and ends on the last one.
  const at4 = await page.evaluate(() => window.minksum.playScreenPoint());
  await page.mouse.move(at4.x, at4.y);
  await page.mouse.down();
  for (let i = 0; i < 40; ++i) await page.mouse.move(at4.x + 3 * Math.sin(i / 4) * 10, at4.y + 2 * i);
  await page.mouse.up();
  await checkShown('after a burst of moves');

  const lat = await page.evaluate(() => window.minksum.play.latencies);
  const sorted = [...lat].sort((a, b) => a - b);
  const mean = lat.reduce((a, b) => a + b, 0) / lat.length;
  console.log(`play: ${checked} answers checked against minksum query (${JSON.stringify(seen)}, ${turned} with P turned)`);
  console.log(`play: round trip per query in the browser: median ${sorted[Math.floor(sorted.length / 2)].toFixed(2)} ms, ` +
              `mean ${mean.toFixed(2)} ms, max ${sorted[sorted.length - 1].toFixed(2)} ms over ${lat.length} queries`);
} catch (e) {
  failed = e;
} finally {
  await browser.close();
  server.kill('SIGINT');
}
const { code, signal } = await exited;
if (failed) fail(failed.stack || String(failed));
check(code === 0, `play: minksum play exited with ${code ?? signal} after SIGINT (stderr: ${serverErr})`);
console.log('play: ok');
