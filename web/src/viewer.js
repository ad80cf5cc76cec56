// The viewer of the pages minksum writes ('minksum view', 'minksum cgm --html',
// 'minksum simulate --html'): reads the JSON in <script id="minksum-data">
// (cli/page.cpp writes it; docs/viewer.md documents it) and draws it with
// three.js.  Exact values (coordinates, planes, volumes) are shown as the
// strings the page holds; the doubles are for drawing only.
//
// For the tests and for scripting, window.minksum exposes the state
// (drawnFacets, picked, loadMs, ...) and a few actions (pickAt, facetScreenPoint,
// measureFrames, setFrame); window.minksumReady is true once the first frame
// is drawn.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { initPlay } from './play.js';
import { decimalText, decimalsText, exactWithDecimal } from './exact.js';

const parseStart = performance.now();
const data = JSON.parse(document.getElementById('minksum-data').textContent);
const api = {
  data, ready: false, drawnFacets: {}, drawnEdges: {}, picked: null, loadMs: null,
  cgmRealVertices: 0, cgmDrawnFacets: 0,
  // Milliseconds from navigation: script start, data parsed, scene built, first frame drawn.
  timing: { scriptMs: parseStart },
};
api.timing.parsedMs = performance.now();
window.minksum = api;

// ---------------------------------------------------------------------------
// Page layout and style.

const css = `
html, body { margin: 0; height: 100%; font: 14px/1.4 system-ui, sans-serif; color: #1d2430; background: #f4f6f9; }
#app { display: flex; height: 100vh; }
#view { flex: 1; position: relative; min-width: 0; }
#view canvas { display: block; width: 100%; height: 100%; }
#title { position: absolute; left: 12px; top: 8px; margin: 0; font-size: 18px; font-weight: 600; pointer-events: none;
  background: rgba(244,246,249,.8); padding: 2px 6px; border-radius: 4px; }
#hint { position: absolute; left: 12px; bottom: 8px; font-size: 12px; color: #566; pointer-events: none; }
#side { width: 340px; overflow-y: auto; border-left: 1px solid #ccd3dd; background: #fff; padding: 10px 12px; box-sizing: border-box; }
#side h2 { font-size: 14px; margin: 12px 0 4px; text-transform: uppercase; letter-spacing: .04em; color: #4a5668; }
.row { display: flex; align-items: center; gap: 6px; margin: 2px 0; }
.sw { display: inline-block; width: 14px; height: 14px; border-radius: 3px; border: 1px solid #0003; flex: none; }
.exact { font-family: ui-monospace, monospace; font-size: 12px; word-break: break-all; }
.decimal { font-family: ui-monospace, monospace; font-size: 12px; color: #2c3a4d; }
.fold summary { cursor: pointer; font-size: 12px; color: #566; }
.value { margin: 1px 0 4px; }
table { border-collapse: collapse; width: 100%; font-size: 13px; }
td, th { text-align: left; padding: 1px 4px; vertical-align: top; }
#pick .exact { margin: 2px 0; }
#timeline { position: relative; height: 18px; margin: 4px 0; background: #e8ecf1; border-radius: 3px; }
#timeline .mark { position: absolute; top: 0; width: 3px; height: 18px; margin-left: -1px; }
#slider { width: 100%; }
button { font: inherit; padding: 2px 10px; }
`;
const style = document.createElement('style');
style.textContent = css;
document.head.appendChild(style);

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'text') e.textContent = v;
    else if (k === 'style') e.style.cssText = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

const app = el('div', { id: 'app' });
const view = el('div', { id: 'view' });
const side = el('div', { id: 'side' });
app.append(view, side);
document.body.append(app);
view.append(el('h1', { id: 'title', text: data.title }));
view.append(el('div', { id: 'hint', text: 'drag: turn · wheel: zoom · right-drag or shift-drag: pan · click a facet: its exact data' }));

// ---------------------------------------------------------------------------
// Renderer, camera, lights.

// Multisampling costs much in a software renderer; big scenes go without.
const totalFacets = (data.solids || []).concat((data.cgms || []).map((c) => c.solid)).reduce((n, s) => n + s.facets.length, 0);
const renderer = new THREE.WebGLRenderer({ antialias: totalFacets <= 30000 });
renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
renderer.setClearColor(0xf4f6f9);
view.append(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
scene.add(camera);
scene.add(new THREE.AmbientLight(0xffffff, 1.1));
const light = new THREE.DirectionalLight(0xffffff, 1.9);
light.position.set(0.6, 0.9, 1.4);
camera.add(light);  // the light turns with the camera
const controls = new OrbitControls(camera, renderer.domElement);
controls.enableDamping = false;
controls.screenSpacePanning = true;

let needsRender = true;
function requestRender() { needsRender = true; }
controls.addEventListener('change', requestRender);

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  requestRender();
}
window.addEventListener('resize', resize);

// ---------------------------------------------------------------------------
// Colours and names.

const COLOURS = {
  // sum: a sum without provenance (a non-convex sum, a big one), in the
  // colour of its swatch in the list of solids, not A's blue.
  a: 0x3b7dd8, b: 0xe8862a, sum: 0x3aa655, polytope: 0x5b8fd0, obstacle: 0x8fa9cf,
  translated: 0x3b7dd8, corner: 0xe8862a, edge: 0x3aa655, facet_edge: 0x9b59b6, facet_facet: 0x8a8f99,
  separate: 0x2a8f3a, touching: 0xe08a00, penetrating: 0xd02020,
  p: 0xd0312d, q: 0x2563c9, both: 0x8e44ad, real: 0x1d2430, artificial: 0x7a8594, cobstacle: 0x9b59b6,
};
const ORIGIN_TEXT = {
  translated: 'facet of A ⊕ vertex of B (translated facet of A)',
  corner: 'vertex of A ⊕ facet of B (translated facet of B)',
  edge: 'edge of A ⊕ edge of B',
  facet_edge: 'facet ⊕ edge (parallel)',
  facet_facet: 'facet of A ⊕ facet of B (parallel)',
};
const DIM_NAME = ['vertex', 'edge', 'facet'];
const hex = (c) => '#' + c.toString(16).padStart(6, '0');

// "a b c d" -> "a·x + b·y + c·z = d", terms with a zero coefficient left out.
function planeText(plane) {
  const [a, b, c, d] = plane.split(' ');
  let s = '';
  for (const [k, v] of [[a, 'x'], [b, 'y'], [c, 'z']]) {
    if (k === '0') continue;
    const neg = k.startsWith('-'), mag = neg ? k.slice(1) : k;
    s += s ? (neg ? ' − ' : ' + ') : (neg ? '−' : '');
    s += (mag === '1' ? '' : mag + '·') + v;
  }
  return s + ' = ' + d;
}

// A plane with a coefficient too long to read: the same with each
// coefficient's decimal (its rounding to 12 digits); '' when all are short.
function planeDecimalText(plane) {
  const parts = plane.split(' ');
  if (parts.every((k) => decimalText(k) === '')) return '';
  const short = (k) => { const t = decimalText(k); return t ? t.slice(2) : k; };
  return '≈ ' + planeText(parts.map(short).join(' '));
}

// An exact value (an element holding its exact text) with its decimal.
const withDecimal = (exactElement) => exactWithDecimal(el, exactElement, decimalText(exactElement.textContent));
const pointWithDecimal = (exactElement, point) => exactWithDecimal(el, exactElement, decimalsText(point));

// ---------------------------------------------------------------------------
// Solids: one BufferGeometry each (facets fanned into triangles, or, for a
// solid that is not convex, the triangles its data gives; one colour per
// facet through vertex colours), the facet of every triangle kept for
// picking, the edges as one LineSegments.

const solids = [];  // { data, group, mesh, edges, triFacet, highlight, key }

function facetColours(s) {
  if (s.role === 'sum' && s.origin) return (f) => COLOURS[data.origins[s.origin[f]]];
  const c = COLOURS[s.role] ?? COLOURS.polytope;
  return () => c;
}

function buildSolid(s, key) {
  const xyz = s.xyz, facets = s.facets;
  let tris = 0;
  if (s.triangles) tris = s.triangle_facet.length;
  else for (const f of facets) tris += f.length - 2;
  const pos = new Float32Array(tris * 9), col = new Float32Array(tris * 9), nor = new Float32Array(tris * 9);
  const triFacet = new Uint32Array(tris);
  const colourOf = facetColours(s);
  const colour = new THREE.Color();
  let t = 0, last = -1, normal = null;
  // Triangle t: corners u, v, w of facet f.
  function put(f, u, v, w) {
    if (f !== last) {
      last = f;
      colour.setHex(colourOf(f), THREE.SRGBColorSpace);
      const p = s.planes[f].split(' ').map(Number);
      const len = Math.hypot(p[0], p[1], p[2]) || 1;
      normal = [p[0] / len, p[1] / len, p[2] / len];
    }
    triFacet[t] = f;
    const corners = [u, v, w];
    for (let k = 0; k < 3; ++k) {
      const o = t * 9 + k * 3, c = corners[k] * 3;
      pos[o] = xyz[c]; pos[o + 1] = xyz[c + 1]; pos[o + 2] = xyz[c + 2];
      col[o] = colour.r; col[o + 1] = colour.g; col[o + 2] = colour.b;
      nor[o] = normal[0]; nor[o + 1] = normal[1]; nor[o + 2] = normal[2];
    }
    ++t;
  }
  if (s.triangles) {
    const tv = s.triangles, tf = s.triangle_facet;
    for (let i = 0; i < tf.length; ++i) put(tf[i], tv[3 * i], tv[3 * i + 1], tv[3 * i + 2]);
  } else {
    for (let f = 0; f < facets.length; ++f)
      for (let i = 1; i + 1 < facets[f].length; ++i) put(f, facets[f][0], facets[f][i], facets[f][i + 1]);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(nor, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const material = new THREE.MeshLambertMaterial({
    vertexColors: true, side: THREE.FrontSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });
  const mesh = new THREE.Mesh(geometry, material);

  // Each edge once: the halfedge u -> v with u < v (every edge of a closed
  // surface is seen once in each direction).
  const seg = [];
  for (const loop of facets)
    for (let i = 0; i < loop.length; ++i) {
      const u = loop[i], v = loop[(i + 1) % loop.length];
      if (u < v) seg.push(xyz[3 * u], xyz[3 * u + 1], xyz[3 * u + 2], xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    }
  const eg = new THREE.BufferGeometry();
  eg.setAttribute('position', new THREE.Float32BufferAttribute(seg, 3));
  const edges = new THREE.LineSegments(eg, new THREE.LineBasicMaterial({ color: 0x1d2430, transparent: true, opacity: 0.55 }));
  edges.visible = facets.length <= 20000;

  const group = new THREE.Group();
  group.add(mesh, edges);
  // A point (a sweep's operand or the sum of two points) has neither area
  // nor edge: its vertex is drawn as a dot of constant size on the screen.
  if (s.counts && s.counts.dimension === 0) {
    const pg = new THREE.BufferGeometry();
    pg.setAttribute('position', new THREE.Float32BufferAttribute(Array.from(xyz.slice(0, 3)), 3));
    group.add(new THREE.Points(pg, new THREE.PointsMaterial({ color: 0x1d2430, size: 9, sizeAttenuation: false })));
  }
  scene.add(group);
  const solid = { data: s, key, group, mesh, edges, triFacet, highlight: null };
  mesh.userData.solid = solid;
  solids.push(solid);

  // What is drawn, counted from the geometry itself: the distinct facets of
  // its triangles and its line segments.
  const seen = new Uint8Array(facets.length);
  let n = 0;
  for (const f of triFacet) if (!seen[f]) { seen[f] = 1; ++n; }
  api.drawnFacets[key] = n;
  api.drawnEdges[key] = seg.length / 6;
  return solid;
}

// Side by side along x, in the order given, or all at their true positions.
function layout(sideBySide) {
  let x = 0;
  const shown = solids.filter((s) => s.group.visible || !sideBySide);
  for (const s of solids) {
    const box = s.mesh.geometry.boundingBox;
    if (!sideBySide) { s.group.position.set(0, 0, 0); continue; }
    if (!s.group.visible) continue;
    const gap = 0.25 * (box.max.x - box.min.x);
    s.group.position.set(x - box.min.x + (x === 0 ? 0 : gap), 0, 0);
    x = s.group.position.x + box.max.x;
  }
  if (sideBySide && shown.length) {  // centre the row on the origin
    const mid = x / 2;
    for (const s of solids) if (s.group.visible) s.group.position.x -= mid;
  }
  requestRender();
}

// Looks at the objects (or at a Box3) from the front-right, above.
function fitCamera(objects, from = new THREE.Vector3(0.55, -1.0, 0.65)) {
  const box = new THREE.Box3();
  if (objects.isBox3) box.copy(objects);
  else for (const o of objects) box.expandByObject(o);
  if (box.isEmpty()) return;
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const r = sphere.radius || 1;
  const dist = r / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05;
  const dir = from.clone().normalize();
  camera.position.copy(sphere.center).addScaledVector(dir, dist);
  camera.near = dist / 100;
  camera.far = dist * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(sphere.center);
  controls.update();
  requestRender();
}

// ---------------------------------------------------------------------------
// Picking: the triangle under the pointer, its facet, the facet's exact data.

const raycaster = new THREE.Raycaster();
const pickPanel = el('div', { id: 'pick' }, el('div', { text: 'Click a facet to see its exact plane and vertices.' }));

function pickable() { return solids.filter((s) => s.group.visible && s.mesh.visible).map((s) => s.mesh); }

function pickAt(clientX, clientY) {
  const r = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObjects(pickable(), false)[0];
  if (!hit) { showPick(null); return null; }
  const solid = hit.object.userData.solid;
  const facet = solid.triFacet[hit.faceIndex];
  showPick(solid, facet);
  return api.picked;
}
api.pickAt = pickAt;

function provenanceText(s, f) {
  if (!s.origin) return null;
  const kind = data.origins[s.origin[f]];
  const fr = s.from.slice(4 * f, 4 * f + 4);
  return { kind, text: `${ORIGIN_TEXT[kind]}: ${DIM_NAME[fr[0]]} ${fr[1]} of A ⊕ ${DIM_NAME[fr[2]]} ${fr[3]} of B` };
}

function showPick(solid, facet) {
  for (const s of solids) if (s.highlight) { s.group.remove(s.highlight); s.highlight.geometry.dispose(); s.highlight = null; }
  pickPanel.replaceChildren();
  if (!solid) {
    api.picked = null;
    pickPanel.append(el('div', { text: 'No facet under the pointer.' }));
    requestRender();
    return;
  }
  const s = solid.data, loop = s.facets[facet];
  const prov = provenanceText(s, facet);
  api.picked = { solid: solid.key, name: s.name, facet, plane: s.planes[facet], vertices: loop.slice(),
                 exact: loop.map((v) => s.exact[v]), provenance: prov ? prov.kind : null };
  pickPanel.append(el('div', {}, el('b', { text: `${s.name}` }), ` — facet ${facet} (${loop.length} vertices)`));
  pickPanel.append(el('div', { text: 'plane:' }), exactWithDecimal(el, el('div', { class: 'exact', id: 'pick-plane', 'data-plane': s.planes[facet], text: planeText(s.planes[facet]) }), planeDecimalText(s.planes[facet])));
  if (prov) pickPanel.append(el('div', { id: 'pick-provenance', 'data-kind': prov.kind }, el('span', { class: 'sw', style: `background:${hex(COLOURS[prov.kind])}` }), ' ' + prov.text));
  pickPanel.append(el('div', { text: 'vertices (exact x y z):' }));
  const list = el('div', { id: 'pick-vertices' });
  for (const v of loop) {
    const exact = el('div', { class: 'exact', 'data-vertex': String(v), text: `${v}: ${s.exact[v]}` });
    list.append(exactWithDecimal(el, exact, decimalsText(s.exact[v].split(' '))));
  }
  pickPanel.append(list);
  // The picked facet outlined on top of the solid.
  const pts = [];
  for (let i = 0; i < loop.length; ++i) {
    const u = loop[i], v = loop[(i + 1) % loop.length];
    pts.push(s.xyz[3 * u], s.xyz[3 * u + 1], s.xyz[3 * u + 2], s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
  solid.highlight = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0xffd000, depthTest: false }));
  solid.highlight.renderOrder = 10;
  solid.group.add(solid.highlight);
  requestRender();
}

// The window coordinates of the centroid of facet f of solid `key` when it
// faces the camera and nothing hides it there, else null (for tests).
api.facetScreenPoint = function (key, f) {
  const solid = solids.find((s) => s.key === key);
  if (!solid) return null;
  const s = solid.data, loop = s.facets[f];
  const c = new THREE.Vector3();
  for (const v of loop) c.add(new THREE.Vector3(s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]));
  c.divideScalar(loop.length);
  solid.group.updateMatrixWorld();
  c.applyMatrix4(solid.group.matrixWorld);
  const p = c.clone().project(camera);
  if (Math.abs(p.x) > 0.95 || Math.abs(p.y) > 0.95) return null;
  const r = renderer.domElement.getBoundingClientRect();
  const x = r.left + (p.x + 1) / 2 * r.width, y = r.top + (1 - p.y) / 2 * r.height;
  raycaster.setFromCamera(new THREE.Vector2(p.x, p.y), camera);
  const hit = raycaster.intersectObjects(pickable(), false)[0];
  if (!hit || hit.object !== solid.mesh || solid.triFacet[hit.faceIndex] !== f) return null;
  return { x, y };
};

let downAt = null;
renderer.domElement.addEventListener('pointerdown', (e) => { downAt = { x: e.clientX, y: e.clientY }; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (downAt && Math.hypot(e.clientX - downAt.x, e.clientY - downAt.y) < 4 && e.button === 0) pickAt(e.clientX, e.clientY);
  downAt = null;
});

// ---------------------------------------------------------------------------
// Side panel pieces.

function checkbox(id, label, checked, onChange) {
  const box = el('input', { type: 'checkbox', id });
  box.checked = checked;
  box.addEventListener('change', () => { onChange(box.checked); requestRender(); });
  return el('label', { class: 'row', for: id }, box, label);
}

function solidControls(solid, colour) {
  const row = el('div', { class: 'row' });
  const sw = el('span', { class: 'sw', style: `background:${hex(colour)}` });
  row.append(checkbox(`show-${solid.key}`, '', true, (on) => { solid.group.visible = on; layout(sideBySide); }), sw, el('span', { text: solid.data.name }));
  return row;
}

function countsTable(list) {
  const t = el('table', { id: 'counts' });
  t.append(el('tr', {}, el('th', { text: '' }), el('th', { text: 'V' }), el('th', { text: 'E' }), el('th', { text: 'F' })));
  for (const s of list)
    t.append(el('tr', {}, el('td', { text: s.name }), el('td', { text: String(s.counts.vertices) }), el('td', { text: String(s.counts.edges) }), el('td', { text: String(s.counts.facets) })));
  return t;
}

function volumes(list) {
  const d = el('div', { id: 'volumes' });
  for (const s of list) d.append(el('div', { text: `volume of ${s.name} (exact):` }), withDecimal(el('div', { class: 'exact', 'data-volume': s.volume, text: s.volume })));
  return d;
}

let sideBySide = true;
function displayControls(list) {
  const d = el('div');
  d.append(checkbox('edges', 'edges', list.every((s) => s.edges.visible), (on) => { for (const s of list) s.edges.visible = on || wire; }));
  let wire = false;
  d.append(checkbox('wireframe', 'wireframe (edges only)', false, (on) => {
    wire = on;
    for (const s of list) { s.mesh.visible = !on; if (on) s.edges.visible = true; else s.edges.visible = document.getElementById('edges').checked; }
  }));
  d.append(checkbox('transparent', 'transparent', false, (on) => {
    for (const s of list) { s.mesh.material.transparent = on; s.mesh.material.opacity = on ? 0.35 : 1; s.mesh.material.depthWrite = !on; s.mesh.material.needsUpdate = true; }
  }));
  return d;
}

// ---------------------------------------------------------------------------
// The kinds of page.

function initPolytope() {
  const s = buildSolid(data.solids[0], 'polytope');
  side.append(el('h2', { text: data.kind === 'solid' ? 'Solid' : 'Polytope' }), solidControls(s, COLOURS.polytope), countsTable([s.data]), volumes([s.data]));
  side.append(el('h2', { text: 'Display' }), displayControls([s]));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);
  layout(false);
  fitCamera([s.group]);
}

function initSum() {
  const [da, db, ds] = data.solids;
  const a = buildSolid(da, 'a'), b = buildSolid(db, 'b'), s = buildSolid(ds, 'sum');
  side.append(el('h2', { text: 'Solids' }), solidControls(a, COLOURS.a), solidControls(b, COLOURS.b), solidControls(s, COLOURS.sum));
  side.append(el('div', { text: `method: ${data.method}` }));
  side.append(countsTable([da, db, ds]));
  const legend = el('div', { id: 'legend' });
  legend.append(el('h2', { text: 'Facets of the sum, by provenance' }));
  if (ds.origin) {
    const count = new Array(data.origins.length).fill(0);
    for (const o of ds.origin) ++count[o];
    data.origins.forEach((name, i) => {
      legend.append(el('div', { class: 'row', 'data-origin': name, 'data-count': String(count[i]) },
        el('span', { class: 'sw', style: `background:${hex(COLOURS[name])}` }), `${ORIGIN_TEXT[name]}: ${count[i]}`));
    });
    if (data.provenance === 'computed') legend.append(el('div', { text: `(method ${data.method} does not record provenance; computed from the operands)` }));
  } else if (data.provenance === 'nonconvex') {
    legend.append(el('div', { text: 'not shown: the sum of a non-convex solid is the union of the sums of its pieces (docs/nonconvex.md)' }));
  } else {
    legend.append(el('div', { text: `not shown: method ${data.method} does not record it (use --method walk)` }));
  }
  side.append(legend);
  side.append(el('h2', { text: 'Display' }));
  side.append(checkbox('side-by-side', 'side by side (else at true positions, overlaid)', true, (on) => { sideBySide = on; layout(on); fitCamera(solids.map((x) => x.group)); }));
  side.append(displayControls([a, b, s]));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);
  side.append(el('h2', { text: 'Volumes' }), volumes([da, db, ds]));
  layout(true);
  fitCamera([a.group, b.group, s.group]);
}

// The Cubical Gaussian Map: the cube [-1,1]^3 with the six planar maps on its
// faces (real arcs solid, coloured by operand; artificial edges dashed; real
// vertices as dots), and the polytope it encodes beside it.
const CGM_FACE_NAMES = ['0: x = −1', '1: y = −1', '2: z = −1', '3: x = +1', '4: y = +1', '5: z = +1'];

// The cube of one map `d` ({ maps, origins }), added to the scene.
function buildCgmCube(d) {
  const cube = new THREE.Group();
  const faces = new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2), new THREE.MeshLambertMaterial({
    color: 0xffffff, transparent: true, opacity: 0.55, polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 2 }));
  cube.add(faces);
  const kinds = { artificial: [], real: [], p: [], q: [], both: [] };
  const dots = [], dotColours = [];
  const facetSeen = new Set();
  let realVertices = 0;
  const colour = new THREE.Color();
  for (const m of d.maps) {
    for (let e = 0; e < m.edges.length; e += 3) {
      const u = m.edges[e], v = m.edges[e + 1], code = m.edges[e + 2];
      const kind = code === 0 ? 'artificial' : code === 1 ? 'real' : code === 2 ? 'p' : code === 3 ? 'q' : 'both';
      kinds[kind].push(m.xyz[3 * u], m.xyz[3 * u + 1], m.xyz[3 * u + 2], m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
    }
    for (let v = 0; v < m.facet.length; ++v) {
      if (m.facet[v] < 0) continue;
      ++realVertices;
      facetSeen.add(m.facet[v]);
      dots.push(m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
      colour.setHex(m.origin && m.origin[v] >= 0 ? COLOURS[d.origins[m.origin[v]]] : COLOURS.real, THREE.SRGBColorSpace);
      dotColours.push(colour.r, colour.g, colour.b);
    }
  }
  const lineKinds = {};
  for (const [kind, seg] of Object.entries(kinds)) {
    if (!seg.length) continue;
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(seg, 3));
    const mat = kind === 'artificial'
      ? new THREE.LineDashedMaterial({ color: COLOURS.artificial, dashSize: 0.04, gapSize: 0.03 })
      : new THREE.LineBasicMaterial({ color: COLOURS[kind] });
    const lines = new THREE.LineSegments(g, mat);
    if (kind === 'artificial') lines.computeLineDistances();
    cube.add(lines);
    lineKinds[kind] = seg.length / 6;
  }
  const dg = new THREE.BufferGeometry();
  dg.setAttribute('position', new THREE.Float32BufferAttribute(dots, 3));
  dg.setAttribute('color', new THREE.Float32BufferAttribute(dotColours, 3));
  const points = new THREE.Points(dg, new THREE.PointsMaterial({ size: 5, sizeAttenuation: false, vertexColors: true }));
  cube.add(points);
  // Face names: the map id and its plane, written on each cube face.
  const names = CGM_FACE_NAMES;
  for (let k = 0; k < 6; ++k) {
    const c = document.createElement('canvas');
    c.width = 256; c.height = 64;
    const ctx = c.getContext('2d');
    ctx.fillStyle = '#4a5668';
    ctx.font = 'bold 34px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(names[k], 128, 32);
    const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(c), depthTest: false, transparent: true }));
    const axis = k % 3, sign = k < 3 ? -1 : 1;
    const p = [0, 0, 0];
    p[axis] = sign * 1.35;
    sprite.position.set(p[0], p[1], p[2]);
    sprite.scale.set(0.8, 0.2, 1);
    cube.add(sprite);
  }
  scene.add(cube);
  return { cube, realVertices, facets: facetSeen.size, lineKinds };
}

// The polytope of a map beside its cube (centred at x = cubeX), scaled to
// the cube's size (drawing only).
function placeBesideCube(s, cubeX) {
  const box = s.mesh.geometry.boundingBox;
  const size = Math.max(box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z) || 1;
  const scale = 2 / size;
  s.group.scale.setScalar(scale);
  const centre = box.getCenter(new THREE.Vector3()).multiplyScalar(scale);
  s.group.position.set(cubeX + 3.4 - centre.x, -centre.y, -centre.z);
}

function initCgm() {
  const { cube, realVertices, facets, lineKinds } = buildCgmCube(data);
  api.cgmRealVertices = realVertices;
  api.cgmDrawnFacets = facets;
  api.cgmEdges = lineKinds;
  const names = CGM_FACE_NAMES;
  const s = buildSolid(data.solids[0], data.solids[0].role);
  placeBesideCube(s, 0);

  side.append(el('h2', { text: 'Cubical Gaussian Map' }));
  const legend = el('div', { id: 'legend' });
  const row = (colourHex, text, dashed) => el('div', { class: 'row' },
    el('span', { class: 'sw', style: dashed ? `background:repeating-linear-gradient(90deg,${hex(colourHex)} 0 4px,#fff 4px 7px)` : `background:${hex(colourHex)}` }), text);
  if (data.operands) {
    legend.append(row(COLOURS.p, `arcs of P = ${data.operands[0]}`), row(COLOURS.q, `arcs of Q = ${data.operands[1]}`), row(COLOURS.both, 'arcs of both (overlapping)'));
  } else {
    legend.append(row(COLOURS.real, 'arcs (edges of the polytope)'));
  }
  legend.append(row(COLOURS.artificial, 'artificial edges (cube-face boundaries)', true));
  if (data.origins && data.maps.some((m) => m.origin)) {
    legend.append(el('div', { text: 'dots: facet normals (vertices of the overlay), by provenance:' }));
    for (const name of data.origins) legend.append(row(COLOURS[name], ORIGIN_TEXT[name].replace(/A/g, 'P').replace(/B/g, 'Q')));
  } else {
    legend.append(row(COLOURS.real, 'dots: facet normals (real vertices)'));
  }
  side.append(legend);
  const t = el('table', { id: 'maps' });
  t.append(el('tr', {}, ...['map', 'V', 'HE', 'F', 'real V', 'real E'].map((h) => el('th', { text: h }))));
  for (const m of data.maps)
    t.append(el('tr', {}, ...[names[m.id], m.counts.vertices, m.counts.halfedges, m.counts.faces, m.counts.real_vertices, m.counts.real_edges].map((x) => el('td', { text: String(x) }))));
  side.append(t);
  side.append(el('h2', { text: 'Polytope' }), solidControls(s, COLOURS[s.data.role] ?? COLOURS.polytope), countsTable([s.data]), volumes([s.data]));
  side.append(el('h2', { text: 'Display' }));
  side.append(checkbox('show-cgm', 'the cube and its maps', true, (on) => { cube.visible = on; }));
  side.append(displayControls([s]));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);
  fitCamera([cube, s.group]);
}

// A VRML scene (minksum view scene.wrl, docs/vrml.md): its ExactPolyhedron
// shapes as solids in a row, at one common scale (the largest 2 units wide),
// and below them each CubicalGaussianMap as its cube with the polytope it
// encodes beside it, as on the page of 'cgm --html'; both rows centred.
function initScene() {
  const list = [];
  data.solids.forEach((d, i) => list.push(buildSolid(d, `solid${i}`)));
  let largest = 0;
  for (const s of list) {
    const b = s.mesh.geometry.boundingBox;
    largest = Math.max(largest, b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z);
  }
  const scale = largest > 0 ? 2 / largest : 1;
  const rowZ = data.cgms.length && list.length ? 1.8 : 0;
  let x = 0;
  for (const s of list) {
    const b = s.mesh.geometry.boundingBox;
    s.group.scale.setScalar(scale);
    s.group.position.set(x - b.min.x * scale, -(b.min.y + b.max.y) / 2 * scale, rowZ - (b.min.z + b.max.z) / 2 * scale);
    x += (b.max.x - b.min.x) * scale + 0.8;
  }
  for (const s of list) s.group.position.x -= (x - 0.8) / 2;
  api.sceneCgms = [];
  const cgmX = (i) => 6.2 * i - (6.2 * data.cgms.length - 1.8) / 2 + 1;  // a cube's centre
  const cgms = data.cgms.map((d, i) => {
    const c = buildCgmCube({ maps: d.maps, origins: data.origins });
    c.cube.position.set(cgmX(i), 0, -rowZ);
    const s = buildSolid(d.solid, `cgm${i}`);
    placeBesideCube(s, cgmX(i));
    s.group.position.z -= rowZ;
    api.sceneCgms.push({ name: d.name, realVertices: c.realVertices, facets: c.facets, edges: c.lineKinds });
    return { d, cube: c.cube, solid: s };
  });
  const all = list.concat(cgms.map((c) => c.solid));
  // Each polytope named, in the colour of what it is in the scene (an
  // operand of a sum, the sum, or a polytope alone): the legend of the row.
  side.append(el('h2', { text: 'Shapes' }));
  const roles = data.roles || [];
  list.forEach((s, i) => {
    const r = roles[i] || { role: 'polytope', caption: '' };
    side.append(el('div', { class: 'row', 'data-shape': s.data.name, 'data-role': r.role },
      checkbox(`show-${s.key}`, '', true, (on) => { s.group.visible = on; }),
      el('span', { class: 'sw', style: `background:${hex(COLOURS[r.role] ?? COLOURS.polytope)}` }),
      el('span', { text: `polytope ${s.data.name}` + (r.caption ? ` — ${r.caption}` : '') })));
  });
  cgms.forEach((c) => side.append(el('div', { class: 'row' },
    checkbox(`show-${c.solid.key}`, '', true, (on) => { c.cube.visible = on; c.solid.group.visible = on; }),
    el('span', { class: 'sw', style: `background:${hex(COLOURS.real)}` }),
    el('span', { text: `CubicalGaussianMap ${c.d.name}` + (c.d.operands ? ` (of ${c.d.operands[0]} ⊕ ${c.d.operands[1]})` : '') }))));
  side.append(countsTable(all.map((s) => s.data)));
  if (cgms.length) {
    const legend = el('div', { id: 'legend' });
    const row = (colourHex, text, dashed) => el('div', { class: 'row' },
      el('span', { class: 'sw', style: dashed ? `background:repeating-linear-gradient(90deg,${hex(colourHex)} 0 4px,#fff 4px 7px)` : `background:${hex(colourHex)}` }), text);
    legend.append(row(COLOURS.real, 'arcs (edges of the polytope)'));
    if (cgms.some((c) => c.d.operands)) legend.append(row(COLOURS.p, 'arcs of the first operand'), row(COLOURS.q, 'arcs of the second operand'), row(COLOURS.both, 'arcs of both (overlapping)'));
    legend.append(row(COLOURS.artificial, 'artificial edges (cube-face boundaries)', true), row(COLOURS.real, 'dots: facet normals'));
    // A map of a sum colours its dots, and its polytope its facets, by provenance.
    if (cgms.some((c) => c.d.solid.origin)) {
      legend.append(el('div', { text: 'facets of a sum beside its map, and their dots, by provenance:' }));
      for (const name of data.origins) legend.append(row(COLOURS[name], ORIGIN_TEXT[name]));
    }
    side.append(el('h2', { text: 'Cubical Gaussian Maps' }), legend);
  }
  side.append(el('h2', { text: 'Display' }), displayControls(all));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);
  side.append(el('h2', { text: 'Volumes' }), volumes(all.map((s) => s.data)));
  fitCamera(all.map((s) => s.group).concat(cgms.map((c) => c.cube)), new THREE.Vector3(0.2, -1.0, 0.35));
}

// The motion: obstacle fixed, robot moved frame by frame, coloured by its
// exact state; play/pause, a timeline with the event frames marked, speed.
function initMotion() {
  const obstacle = buildSolid(data.obstacle, 'obstacle');
  const robot = buildSolid(data.robot, 'robot');
  // With --show-m: the C-obstacle Q ⊕ (−P_k) of each orientation k (the
  // robot meets Q exactly when its reference point, drawn as a dot, is in it).
  const cob = (data.cobstacles || []).map((c, k) => {
    const s = buildSolid(c, `cobstacle${k}`);
    s.group.visible = false;
    s.mesh.material.transparent = true; s.mesh.material.opacity = 0.28; s.mesh.material.depthWrite = false;
    s.edges.material.opacity = 0.3;
    return s;
  });
  let showCob = cob.length > 0;
  const rsize = robot.mesh.geometry.boundingSphere.radius;
  const refPoint = new THREE.Mesh(new THREE.SphereGeometry(0.12 * rsize, 16, 8), new THREE.MeshBasicMaterial({ color: 0x1d2430 }));
  refPoint.visible = showCob;
  scene.add(refPoint);
  const statuses = ['separate', 'touching', 'penetrating'];
  const frames = data.frames;
  let frame = 0, playing = false, speed = 1, last = 0, acc = 0;
  const info = el('div', { id: 'frame-info' });
  const slider = el('input', { type: 'range', id: 'slider', min: '0', max: String(frames.length - 1), value: '0', step: '1' });
  const playButton = el('button', { id: 'play', text: 'play' });
  const speedSelect = el('select', { id: 'speed' });
  for (const v of [0.25, 0.5, 1, 2, 4]) {
    const o = el('option', { value: String(v), text: `${v}×` });
    if (v === 1) o.selected = true;
    speedSelect.append(o);
  }
  const timeline = el('div', { id: 'timeline', title: 'event frames: the state changes' });
  for (const e of data.events) {
    const f = frames[e];
    timeline.append(el('span', { class: 'mark', 'data-frame': String(e), title: `frame ${e}: ${statuses[f.status]}`,
      style: `left:${(100 * e) / Math.max(frames.length - 1, 1)}%;background:${hex(COLOURS[statuses[f.status]])}` }));
  }
  const robotColour = new THREE.Color();
  function setFrame(i) {
    frame = Math.max(0, Math.min(frames.length - 1, i));
    const f = frames[frame];
    const shape = data.shapes[f.o];
    const pos = robot.mesh.geometry.attributes.position;
    // Re-place the robot's triangles with orientation f.o (same facets, same fan order).
    let t = 0;
    for (const loop of data.robot.facets)
      for (let i = 1; i + 1 < loop.length; ++i, ++t)
        [loop[0], loop[i], loop[i + 1]].forEach((v, k) => pos.setXYZ(3 * t + k, shape[3 * v], shape[3 * v + 1], shape[3 * v + 2]));
    pos.needsUpdate = true;
    robot.mesh.geometry.computeVertexNormals();
    robot.mesh.geometry.computeBoundingSphere();
    const ep = robot.edges.geometry.attributes.position;
    let k = 0;
    for (const loop of data.robot.facets)
      for (let i = 0; i < loop.length; ++i) {
        const u = loop[i], v = loop[(i + 1) % loop.length];
        if (u < v) { ep.setXYZ(k++, shape[3 * u], shape[3 * u + 1], shape[3 * u + 2]); ep.setXYZ(k++, shape[3 * v], shape[3 * v + 1], shape[3 * v + 2]); }
      }
    ep.needsUpdate = true;
    robot.group.position.set(f.t[0], f.t[1], f.t[2]);
    cob.forEach((c, k) => { c.group.visible = showCob && k === f.o; });
    refPoint.position.set(f.t[0], f.t[1], f.t[2]);
    robot.mesh.material.vertexColors = false;
    robot.mesh.material.color.setHex(COLOURS[statuses[f.status]], THREE.SRGBColorSpace);
    robot.mesh.material.needsUpdate = true;
    slider.value = String(frame);
    const what = f.status === 2 ? 'squared penetration depth' : 'squared distance';
    info.replaceChildren(
      el('div', {}, el('b', { text: `frame ${frame}` }), ` of ${frames.length} (pass ${f.pass}, orientation ${f.o})`),
      el('div', { class: 'row' }, el('span', { class: 'sw', style: `background:${hex(COLOURS[statuses[f.status]])}` }), el('span', { id: 'frame-status', text: statuses[f.status] })),
      el('div', { text: 'translation of the robot (exact):' }), pointWithDecimal(el('div', { class: 'exact', id: 'frame-translation', text: f.exact.join('  ') }), f.exact),
      el('div', { text: `${what} (exact):` }), withDecimal(el('div', { class: 'exact', id: 'frame-value', text: f.value })));
    api.frame = frame;
    requestRender();
  }
  api.setFrame = setFrame;
  slider.addEventListener('input', () => { playing = false; playButton.textContent = 'play'; setFrame(Number(slider.value)); });
  playButton.addEventListener('click', () => {
    playing = !playing;
    playButton.textContent = playing ? 'pause' : 'play';
    if (playing && frame === frames.length - 1) setFrame(0);
    last = performance.now(); acc = 0;
  });
  speedSelect.addEventListener('change', () => { speed = Number(speedSelect.value); });
  api.tick = (now) => {
    if (!playing) return;
    acc += (now - last) * speed * data.fps / 1000;
    last = now;
    if (acc >= 1) {
      const n = Math.floor(acc);
      acc -= n;
      if (frame + n >= frames.length - 1) { setFrame(frames.length - 1); playing = false; playButton.textContent = 'play'; }
      else setFrame(frame + n);
    }
  };
  api.isPlaying = () => playing;

  side.append(el('h2', { text: 'Motion' }), el('div', { class: 'row' }, playButton, el('label', { for: 'speed', text: 'speed' }), speedSelect), slider, timeline, info);
  const legend = el('div', { id: 'legend' });
  for (const st of statuses) legend.append(el('div', { class: 'row' }, el('span', { class: 'sw', style: `background:${hex(COLOURS[st])}` }), `robot ${st}`));
  legend.append(el('div', { text: 'timeline marks: the frames where the state changes' }));
  side.append(el('h2', { text: 'Legend' }), legend);
  side.append(el('h2', { text: 'Solids' }), solidControls(obstacle, COLOURS.obstacle), solidControls(robot, COLOURS.separate));
  if (cob.length) {
    side.append(checkbox('show-cobstacle', 'C-obstacle Q ⊕ (−P) of the orientation, and the robot\'s reference point', true,
                         (on) => { showCob = on; refPoint.visible = on; setFrame(frame); }));
  }
  side.append(countsTable([data.obstacle, data.robot]));
  side.append(el('h2', { text: 'Display' }), displayControls([obstacle, robot]));
  side.append(el('h2', { text: 'Picked facet' }), pickPanel);
  // Frame bounds: the obstacle and every position of the robot.
  const box = new THREE.Box3().setFromObject(obstacle.group);
  const rb = robot.mesh.geometry.boundingBox;
  for (const f of frames) {
    box.expandByPoint(new THREE.Vector3(f.t[0] + rb.min.x, f.t[1] + rb.min.y, f.t[2] + rb.min.z));
    box.expandByPoint(new THREE.Vector3(f.t[0] + rb.max.x, f.t[1] + rb.max.y, f.t[2] + rb.max.z));
  }
  setFrame(0);
  fitCamera(box, new THREE.Vector3(0.1, -0.45, 1));  // the x-y plane of the motion, seen from above, tilted
}

// ---------------------------------------------------------------------------
// Frame timing, for the tests and docs/viewer.md: n frames drawn while the
// camera turns, each waited for (a one-pixel read back); milliseconds per frame.
api.measureFrames = function (n = 60) {
  const gl = renderer.getContext();
  const px = new Uint8Array(4);
  const times = [];
  for (let i = 0; i < n; ++i) {
    const t0 = performance.now();
    camera.position.sub(controls.target).applyAxisAngle(camera.up, (2 * Math.PI) / n).add(controls.target);
    camera.lookAt(controls.target);
    renderer.render(scene, camera);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  controls.update();
  return { frames: n, meanMs: times.reduce((a, b) => a + b, 0) / n, medianMs: times[Math.floor(n / 2)], maxMs: times[n - 1] };
};

// 'minksum play': P and Q, P moved by the mouse, answers from the server (play.js).
const initPlayPage = () => initPlay({ THREE, data, api, scene, camera, controls, renderer, view, side, el, hex, COLOURS,
  buildSolid, fitCamera, requestRender, countsTable, displayControls, pickPanel });
const init = { polytope: initPolytope, solid: initPolytope, sum: initSum, cgm: initCgm, motion: initMotion, play: initPlayPage, scene: initScene }[data.kind];
if (!init) throw new Error(`minksum: unknown page kind '${data.kind}'`);
init();
resize();
api.timing.builtMs = performance.now();
// Draws the scene now (the tests read the canvas in the same task).
api.render = () => renderer.render(scene, camera);

function loop(now) {
  if (api.tick) api.tick(now);
  if (needsRender) {
    needsRender = false;
    renderer.render(scene, camera);
    if (!api.ready) {
      api.ready = true;
      api.loadMs = api.timing.readyMs = performance.now();
      window.minksumReady = true;
    }
  }
  requestAnimationFrame(loop);
}
requestAnimationFrame(loop);
