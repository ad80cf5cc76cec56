// The page of 'minksum play' (cli/cmd_play.cpp, docs/viewer.md): P and Q
// drawn by the viewer, P dragged (translation in the view plane) and turned
// (shift-drag) with the mouse; on every move the page sends P's exact pose
// to the server it came from (POST /query) and shows the exact answer: the
// state in colour, the squared distance or depth, the closest points and the
// witness features, drawn in the scene, and how the answer was found (on M
// of P as given, or, P turned, on the placed bodies with its certificate).
//
// Exact poses: P's translation lives on a grid of step 2^k (three integers
// n, the translation n·2^k, written as exact rationals); its orientation is
// turned as a double quaternion and sent rounded to an integer quaternion
// A+Bi+Cj+Dk of norm about 64, whose rational rotation matrix is both the one
// the server applies and the one P is drawn with.
//
// For the tests: window.minksum.play holds the pose (exact strings), the last
// answer and the pose it answers, the latencies of the round trips (ms), and
// `idle` (no request under way nor waiting).
const QUATERNION_SCALE = 64;

import { decimalText, decimalsText, exactWithDecimal } from './exact.js';

export function initPlay(v) {
  const { THREE, data, api, scene, camera, controls, renderer, view, side, el, hex, COLOURS, buildSolid, fitCamera,
    requestRender, countsTable, displayControls, pickPanel } = v;
  const [dp, dq] = data.solids;
  const p = buildSolid(dp, 'p'), q = buildSolid(dq, 'q');
  p.group.matrixAutoUpdate = false;
  p.mesh.material.vertexColors = false;
  const hint = document.getElementById('hint');
  if (hint) hint.textContent = 'drag P: move it · shift-drag P: turn it · drag elsewhere: turn the view · wheel: zoom';

  // The grid of translations: a power of two about 1/256 of the scene's size.
  const pbox = p.mesh.geometry.boundingBox, qbox = q.mesh.geometry.boundingBox;
  const size = Math.max(pbox.max.x - pbox.min.x, qbox.max.x - qbox.min.x, pbox.max.y - pbox.min.y,
    qbox.max.y - qbox.min.y, pbox.max.z - pbox.min.z, qbox.max.z - qbox.min.z) || 1;
  const exponent = Math.round(Math.log2(size / 256));
  const step = 2 ** exponent;
  const start = [qbox.min.x - pbox.max.x - 0.3 * size, 0, 0];
  const state = {
    t: start.slice(),                 // the translation P is dragged to (doubles)
    n: [0, 0, 0],                     // ... on the grid: n·step
    turn: new THREE.Quaternion(),     // the orientation P is turned to
    rotation: null,                   // ... as an integer quaternion [A, B, C, D], null before the first turn
  };
  const play = { pose: null, answer: null, answeredPose: null, latencies: [], queries: 0, errors: [], idle: false, step };
  api.play = play;

  // An integer times 2^exponent, as an exact rational string.
  function gridText(n) {
    if (n === 0) return '0';
    let num = BigInt(n), e = exponent;
    while (e < 0 && num % 2n === 0n) { num /= 2n; ++e; }
    return e >= 0 ? String(num * 2n ** BigInt(e)) : `${num}/${2n ** BigInt(-e)}`;
  }
  function rotationMatrix(r) {  // the rational matrix of @rot:A,B,C,D, in doubles (row-major)
    const [a, b, c, d] = r, n = a * a + b * b + c * c + d * d;
    return [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
      2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
      2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d].map((x) => x / n);
  }
  // Snaps the pose, places P as the server sees it, returns the request.
  function pose() {
    state.n = state.t.map((x) => Math.round(x / step));
    const m = state.rotation ? rotationMatrix(state.rotation) : [1, 0, 0, 0, 1, 0, 0, 0, 1];
    const [tx, ty, tz] = state.n.map((k) => k * step);
    p.group.matrix.set(m[0], m[1], m[2], tx, m[3], m[4], m[5], ty, m[6], m[7], m[8], tz, 0, 0, 0, 1);
    p.group.matrixWorldNeedsUpdate = true;
    requestRender();
    const request = { translate_p: state.n.map(gridText).join(',') };
    if (state.rotation) request.rotate_p = state.rotation.join(',');
    play.pose = request;
    return request;
  }

  // ---------------------------------------------------------------------------
  // The panel.
  const statusBox = el('div', { id: 'play-answer' });
  const poseBox = el('div', { class: 'exact', id: 'play-pose' });
  const latencyBox = el('div', { id: 'play-latency' });
  const resetButton = el('button', { id: 'play-reset', text: 'reset P' });
  side.append(el('h2', { text: 'Proximity' }), statusBox);
  side.append(el('h2', { text: 'Pose of P (exact)' }), poseBox, el('div', { class: 'row' }, resetButton), latencyBox);
  const legend = el('div', { id: 'legend' });
  for (const st of ['separate', 'touching', 'penetrating'])
    legend.append(el('div', { class: 'row' }, el('span', { class: 'sw', style: `background:${hex(COLOURS[st])}` }), `P ${st}`));
  legend.append(el('div', { class: 'row' }, el('span', { class: 'sw', style: `background:${hex(COLOURS.q)}` }), 'Q (fixed)'));
  legend.append(el('div', { class: 'row' }, el('span', { class: 'sw', style: 'background:#ffd000' }), 'witness feature of P, closest point of P'));
  legend.append(el('div', { class: 'row' }, el('span', { class: 'sw', style: 'background:#e040c0' }), 'witness feature of Q, closest point of Q'));
  side.append(el('h2', { text: 'Legend' }), legend);
  side.append(el('h2', { text: 'Solids' }), countsTable([dp, dq]));
  side.append(el('h2', { text: 'Display' }), displayControls([p, q]));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);

  // ---------------------------------------------------------------------------
  // The witnesses in the scene: the closest points (or the common point) and
  // the segment between them, the features of P and Q, the separating
  // translation when they overlap.
  const witness = new THREE.Group();
  witness.renderOrder = 20;
  scene.add(witness);
  const radius = 0.015 * size;
  function clearWitness() {
    for (const c of [...witness.children]) {
      witness.remove(c);
      c.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
  }
  function dot(x, colour) {
    const m = new THREE.Mesh(new THREE.SphereGeometry(radius, 12, 8), new THREE.MeshBasicMaterial({ color: colour, depthTest: false }));
    m.position.set(x[0], x[1], x[2]);
    m.renderOrder = 21;
    return m;
  }
  function lines(points, closed, colour) {
    const seg = [];
    const k = points.length / 3;
    for (let i = 0; i + 1 < k || (closed && i < k && k > 2); ++i) {
      const j = (i + 1) % k;
      seg.push(points[3 * i], points[3 * i + 1], points[3 * i + 2], points[3 * j], points[3 * j + 1], points[3 * j + 2]);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(seg, 3));
    const l = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colour, depthTest: false }));
    l.renderOrder = 21;
    return l;
  }
  function feature(f, colour) {
    if (f.points.length === 3) witness.add(dot(f.points, colour));
    else if (f.points.length >= 6) witness.add(lines(f.points, true, colour));
  }
  function drawWitness(a) {
    clearWitness();
    feature(a.features.p, 0xffd000);
    feature(a.features.q, 0xe040c0);
    witness.add(dot(a.point_p, 0xffd000), dot(a.point_q, 0xe040c0));
    if (a.status === 'separate') witness.add(lines([...a.point_p, ...a.point_q], false, 0x1d2430));
    if (a.status === 'penetrating' && a.depth > 0) {
      const d = new THREE.Vector3(...a.depth_direction_double);
      witness.add(new THREE.ArrowHelper(d.clone().normalize(), new THREE.Vector3(...a.point_p), d.length(), 0xd02020));
    }
    requestRender();
  }

  // ---------------------------------------------------------------------------
  // The answer.
  const queryLine = (r) => `--translate-p ${r.translate_p}` + (r.rotate_p ? ` --rotate-p ${r.rotate_p}` : '');
  function show(a, request, ms) {
    play.answer = a;
    play.answeredPose = request;
    p.mesh.material.color.setHex(COLOURS[a.status], THREE.SRGBColorSpace);
    p.mesh.material.needsUpdate = true;
    const penetrating = a.status === 'penetrating';
    // Each exact value with its decimal (a point: its three decimals).
    const exactRow = (label, id, value) => {
      const text = Array.isArray(value) ? value.join('  ') : value;
      const decimal = Array.isArray(value) ? decimalsText(value) : decimalText(value);
      return [el('div', { text: label }), exactWithDecimal(el, el('div', { class: 'exact', id, text }), decimal)];
    };
    const featureText = (name, f) => (f.index === null ? `none of ${name} (the answer was found on M)`
      : `${f.type} ${f.index} of ${name}: ${f.exact.join('; ')}`);
    // How the answer was found: on M of P as given, or, P turned, on the
    // placed bodies with the certificates that prove it (M built for this
    // pose only when one of them is "exact").
    const certificates = a.certificate === null ? ''
      : a.depth_certificate === null ? a.certificate : `${a.certificate}, depth: ${a.depth_certificate}`;
    const howText = a.m
      ? `M = P ⊕ (−Q): ${a.m.vertices} vertices, ${a.m.edges} edges, ${a.m.facets} facets (computed once, for P as given)`
      : a.recomputed ? `P turned: M built exactly for this pose (certificate: ${certificates})`
        : `P turned: answered on the placed bodies without M (certificate: ${certificates})`;
    statusBox.replaceChildren(
      el('div', { class: 'row' }, el('span', { class: 'sw', style: `background:${hex(COLOURS[a.status])}` }),
        el('b', { id: 'play-status', 'data-status': a.status, text: a.status })),
      ...(penetrating
        ? [...exactRow('squared penetration depth (exact):', 'play-value', a.squared_depth),
          el('div', { id: 'play-double', text: `depth ≈ ${a.depth}` }),
          ...exactRow('translate P by (exact), to touch:', 'play-direction', a.depth_direction)]
        : [...exactRow('squared distance (exact):', 'play-value', a.squared_distance),
          el('div', { id: 'play-double', text: `distance ≈ ${a.distance}` })]),
      ...exactRow(penetrating ? 'a common point (exact):' : a.status === 'touching' ? 'the contact point (exact):' : 'closest point of P (exact):',
        'play-point-p', a.point_p_exact),
      ...(a.status === 'separate' ? exactRow('closest point of Q (exact):', 'play-point-q', a.point_q_exact) : []),
      el('div', { text: 'witness features:' }),
      el('div', { class: 'exact', id: 'play-feature-p', text: featureText('P', a.features.p) }),
      el('div', { class: 'exact', id: 'play-feature-q', text: featureText('Q', a.features.q) }),
      el('div', { id: 'play-m', text: howText }));
    poseBox.replaceChildren(el('div', { text: `minksum query distance ${dp.name} ${dq.name} ${queryLine(request)}` }));
    const sorted = [...play.latencies].sort((x, y) => x - y);
    latencyBox.textContent = `round trip ${ms.toFixed(1)} ms (median ${sorted[Math.floor(sorted.length / 2)].toFixed(1)} ms over ${sorted.length} queries)`;
    drawWitness(a);
  }

  let inFlight = false, pending = false;
  async function send() {
    if (inFlight) { pending = true; play.idle = false; return; }
    inFlight = true;
    pending = false;
    play.idle = false;
    const request = pose();
    const t0 = performance.now();
    try {
      const res = await fetch('/query', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(request) });
      const text = await res.text();
      if (!res.ok) throw new Error(`the server answered ${res.status}: ${text.trim()}`);
      const a = JSON.parse(text);
      const ms = performance.now() - t0;
      play.latencies.push(ms);
      ++play.queries;
      show(a, request, ms);
    } catch (e) {
      play.errors.push(String(e.message || e));
      statusBox.replaceChildren(el('div', { id: 'play-error', text: `no answer: ${e.message || e} (is 'minksum play' still running?)` }));
    }
    inFlight = false;
    if (pending) send();
    else play.idle = true;
  }
  api.playSend = send;

  // ---------------------------------------------------------------------------
  // The mouse: a drag that starts on P moves or turns P (the camera's
  // controls are off until the button is released); elsewhere it turns the view.
  const raycaster = new THREE.Raycaster();
  function onP(x, y) {
    const r = renderer.domElement.getBoundingClientRect();
    raycaster.setFromCamera(new THREE.Vector2(((x - r.left) / r.width) * 2 - 1, -((y - r.top) / r.height) * 2 + 1), camera);
    p.group.updateMatrixWorld(true);
    return raycaster.intersectObject(p.mesh, false).length > 0;
  }
  let drag = null;
  view.addEventListener('pointerdown', (e) => {
    if (e.button !== 0 || !onP(e.clientX, e.clientY)) return;
    controls.enabled = false;
    drag = { x: e.clientX, y: e.clientY, turn: e.shiftKey };
  }, true);
  window.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (dx === 0 && dy === 0) return;
    camera.updateMatrixWorld();
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
    if (drag.turn || e.shiftKey) {
      const axis = up.clone().multiplyScalar(dx).addScaledVector(right, dy).normalize();
      const dq2 = new THREE.Quaternion().setFromAxisAngle(axis, 0.01 * Math.hypot(dx, dy));
      state.turn.premultiply(dq2).normalize();
      const t = state.turn;
      let r = [t.w, t.x, t.y, t.z].map((c) => Math.round(c * QUATERNION_SCALE));
      if (r.every((c) => c === 0)) r = [1, 0, 0, 0];
      state.rotation = r;
    } else {
      const at = new THREE.Vector3(...state.t);
      const dist = camera.position.distanceTo(at);
      const perPixel = (2 * dist * Math.tan(THREE.MathUtils.degToRad(camera.fov / 2))) / renderer.domElement.clientHeight;
      const d = right.multiplyScalar(dx * perPixel).addScaledVector(up, -dy * perPixel);
      state.t = [state.t[0] + d.x, state.t[1] + d.y, state.t[2] + d.z];
    }
    send();
  });
  window.addEventListener('pointerup', () => {
    if (!drag) return;
    drag = null;
    controls.enabled = true;
  });
  resetButton.addEventListener('click', () => {
    state.t = start.slice();
    state.turn.identity();
    state.rotation = null;
    send();
  });

  // The screen point of P's centre (for the tests' simulated drags).
  api.playScreenPoint = () => {
    p.group.updateMatrixWorld(true);
    const c = pbox.getCenter(new THREE.Vector3()).applyMatrix4(p.group.matrixWorld).project(camera);
    const r = renderer.domElement.getBoundingClientRect();
    return { x: r.left + (c.x + 1) / 2 * r.width, y: r.top + (1 - c.y) / 2 * r.height };
  };

  pose();
  fitCamera(new THREE.Box3().setFromObject(q.group).union(new THREE.Box3(
    new THREE.Vector3(start[0] + pbox.min.x, pbox.min.y, pbox.min.z), new THREE.Vector3(start[0] + pbox.max.x, pbox.max.y, pbox.max.z))));
  send();
}
