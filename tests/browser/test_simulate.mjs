// Browser test of the page of 'minksum simulate --html': the motion played
// back.  node test_simulate.mjs --minksum BIN --out DIR
// Checked against 'minksum simulate --json' (same frames): every frame's
// state, exact translation and exact squared distance or depth as the page
// shows them, the timeline's marks on exactly the frames where the state
// changes, play/pause and the slider; the solids' drawn facets against
// 'minksum stats --json', a facet of the obstacle clicked against
// 'minksum gen --exact'.
import { check, checkDecimals, checkPage, checkPickedFacet, clickFacet, launch, minksum, minksumJson, open, options, planeValue, readOff, visibleFacet } from './lib.mjs';
import { join } from 'node:path';

const o = options();
const FRAMES = '40';
const html = join(o.out, 'simulate.html');
minksum(o.minksum, ['simulate', '--frames', FRAMES, '--html', html]);
const frames = minksum(o.minksum, ['simulate', '--frames', FRAMES, '--json']).trim().split('\n').map((l) => JSON.parse(l));
const events = frames.map((f, i) => (i > 0 && f.status !== frames[i - 1].status ? i : -1)).filter((i) => i >= 0);
check(events.length >= 2, `simulate: the motion has ${events.length} state changes; the test needs a touch and a penetration`);
const obstacleOff = join(o.out, 'simulate-obstacle.off');
minksum(o.minksum, ['gen', 'dodecahedron@scale:2', '--exact', '-o', obstacleOff]);
const obstacle = minksumJson(o.minksum, ['stats', 'dodecahedron@scale:2', '--json']);
const robot = minksumJson(o.minksum, ['stats', 'cube@scale:1/2', '--json']);

const browser = await launch();
try {
  const { page, log } = await open(browser.context, html);
  await checkPage(page, log, 'simulate');
  const drawn = await page.evaluate(() => window.minksum.drawnFacets);
  check(drawn.obstacle === obstacle.facets && drawn.robot === robot.facets, `simulate: facets drawn ${JSON.stringify(drawn)}, minksum stats says ${obstacle.facets} and ${robot.facets}`);
  const marks = await page.$$eval('#timeline .mark', (m) => m.map((e) => Number(e.dataset.frame)));
  check(JSON.stringify(marks) === JSON.stringify(events), `simulate: timeline marks ${marks}, the state changes at ${events}`);
  const n = await page.evaluate(() => window.minksum.data.frames.length);
  check(n === frames.length, `simulate: ${n} frames in the page, minksum simulate printed ${frames.length}`);
  for (let i = 0; i < frames.length; ++i) {
    await page.evaluate((k) => window.minksum.setFrame(k), i);
    const shown = await page.evaluate(() => ({ status: document.getElementById('frame-status').textContent,
      value: document.getElementById('frame-value').textContent, t: document.getElementById('frame-translation').textContent }));
    const f = frames[i];
    const value = f.squared_depth ?? f.squared_distance;
    check(shown.status === f.status && shown.value === value && shown.t === f.translation.join('  '),
          `simulate: frame ${i} shows ${JSON.stringify(shown)}, minksum simulate says ${f.status} ${value} ${f.translation}`);
    // The exact value and translation with their decimals (the value is a fraction).
    if (i < 4) await checkDecimals(page, `simulate: frame ${i}`, 1, '#frame-info');
  }
  // The slider, then play and pause.
  await page.fill('#slider', String(events[0]));
  await page.dispatchEvent('#slider', 'input');
  check(await page.evaluate(() => window.minksum.frame) === events[0], 'simulate: the slider does not move to its frame');
  await page.screenshot({ path: join(o.out, `simulate-frame${events[0]}.png`) });
  await checkPage(page, log, 'simulate (slider)');
  await page.evaluate(() => window.minksum.setFrame(0));
  await page.selectOption('#speed', '4');
  await page.click('#play');
  await page.waitForFunction(() => window.minksum.frame >= 3, null, { timeout: 20000 });
  await page.click('#play');
  const paused = await page.evaluate(() => [window.minksum.isPlaying(), window.minksum.frame]);
  await page.waitForTimeout(400);
  const later = await page.evaluate(() => window.minksum.frame);
  check(!paused[0] && later === paused[1], `simulate: pause did not stop at frame ${paused[1]} (now ${later})`);
  const penetrating = frames.findIndex((f) => f.status === 'penetrating');
  await page.evaluate((k) => window.minksum.setFrame(k), penetrating);
  await page.screenshot({ path: join(o.out, `simulate-frame${penetrating}.png`) });
  const f = await visibleFacet(page, 'obstacle');
  check(f >= 0, 'simulate: no facet of the obstacle is visible');
  const picked = await clickFacet(page, 'obstacle', f, 'simulate');
  checkPickedFacet(picked, readOff(obstacleOff), 'simulate');
  console.log(`simulate: ${frames.length} frames, state changes at ${events}; picked obstacle facet ${picked.facet}: ${picked.plane}`);
  // --show-m: the C-obstacle Q ⊕ (−P_k) of each frame's orientation.  The
  // robot's state is exactly where its reference point u lies against it
  // (outside, on the boundary, inside): checked with the page's exact planes
  // and translations against minksum simulate's own state, frame by frame.
  const htmlM = join(o.out, 'simulate-m.html');
  minksum(o.minksum, ['simulate', '--frames', FRAMES, '--show-m', '--html', htmlM]);
  const m = await open(browser.context, htmlM);
  await checkPage(m.page, m.log, 'simulate --show-m');
  const data = await m.page.evaluate(() => ({ cob: window.minksum.data.cobstacles.map((c) => ({ planes: c.planes, facets: c.counts.facets })),
                                              drawn: window.minksum.drawnFacets, frames: window.minksum.data.frames.map((f) => ({ o: f.o, exact: f.exact })) }));
  check(data.cob.length === Math.ceil(frames.length / 2), `simulate --show-m: ${data.cob.length} C-obstacles for ${frames.length} frames`);
  data.cob.forEach((c, k) => check(data.drawn[`cobstacle${k}`] === c.facets, `simulate --show-m: C-obstacle ${k}: ${data.drawn[`cobstacle${k}`]} facets drawn of ${c.facets}`));
  data.frames.forEach((f, i) => {
    let worst = -1;  // the largest sign of a x + b y + c z - d over the facets
    for (const plane of data.cob[f.o].planes) {
      const [num] = planeValue(plane, f.exact);
      worst = Math.max(worst, num > 0n ? 1 : num === 0n ? 0 : -1);
    }
    const state = worst > 0 ? 'separate' : worst === 0 ? 'touching' : 'penetrating';
    check(state === frames[i].status, `simulate --show-m: frame ${i}: the reference point is ${state} against Q ⊕ (−P), minksum simulate says ${frames[i].status}`);
  });
  await m.page.evaluate((k) => window.minksum.setFrame(k), events[0]);
  await m.page.screenshot({ path: join(o.out, 'simulate-m.png') });
} finally {
  await browser.close();
}
console.log('PASS: simulate');
