// The interactive page of an fhr run (spec/page.md): every stage of the paper on this run's
// meshes, drawn with three.js, beside the paper's words and the run's numbers. Everything it shows
// was computed by fhr and embedded in the page (data.js); this script only draws it.
//
//   §2  T, and D over it (or D alone, flat)
//   §3  T′ with its patches coloured and the network of curves (geodesic, restricted, boundary);
//       T′'s added edges on demand
//   §4  the checkerboard of D carried onto T by φ, or each face's σ₁/σ₂ or stretch; a click on a
//       face shows its patch in its domain triangle (patch_panel.js)
//   §5  f^j or D^j for j = 0..J (level slider); the surface from the largest coefficients
//       (coefficients slider over the rate–distortion points)
//   run the timings beside the paper's table; the oracle's verdict, check by check
//
// Test hook (window.fhrPage, spec/page.md PAGE-7): when T was first drawn, the stage, and where a
// face of T′ is seen on the screen, so that a test can click it.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { loadData } from './data.js';
import { PatchPanel, HIGHLIGHT } from './patch_panel.js';
import { PAPER_TIMINGS, STAGES } from './stages.js';
import { CSS } from './style.js';

const CURVE_KINDS = [
  { name: 'exact geodesic', colour: '#d62728' },
  { name: 'restricted curve', colour: '#c99a00' },
  { name: 'boundary arc', colour: '#2ca02c' },
];
const SURFACE = '#c9c6bd', D_COLOUR = '#27408b', ADDED = '#202020';
const CHECKER = ['#f5f3ec', '#3a5a8c'], CHECKER_CELLS = 4;

const data = loadData();
const report = data.report;
const decimated = data.decimated;

// ---------------------------------------------------------------------------------------- page
const style = document.createElement('style');
style.textContent = CSS;
document.head.append(style);
document.body.insertAdjacentHTML('beforeend', `
<div id="app">
  <div id="side">
    <h1></h1>
    <div class="sub" id="verdict-badge"></div>
    <div id="stages" role="toolbar"></div>
    <div id="text"></div>
    <div class="controls" id="controls"></div>
    <div class="readout" id="readout"></div>
    <div class="legend" id="legend"></div>
    <div id="tables"></div>
  </div>
  <div id="view">
    <button id="reset" title="reset the view (key r)">Reset view</button>
    <div id="note" hidden></div>
    <div id="patch-panel" hidden>
      <button class="close" title="close">×</button>
      <div class="panel-title"></div>
      <canvas></canvas>
    </div>
  </div>
</div>`);
const $ = (selector) => document.querySelector(selector);
$('h1').textContent = `fhr: ${data.title}`;
const oracle = report.parameterization.oracle;
$('#verdict-badge').textContent = `${report.parameterization.certified ? 'certified one-to-one' : 'NOT certified'} · ` +
  `oracle: ${oracle.valid ? 'valid' : 'INVALID'} · T′ ${data.refined_faces.toLocaleString('en-US')} faces`;
if (decimated) {
  $('#note').hidden = false;
  $('#note').textContent = `T′ has ${data.refined_faces.toLocaleString('en-US')} faces: drawn is a display copy of ` +
    `${(data.arrays.tp_faces.count / 3).toLocaleString('en-US')} (a click names the face of T′ it stands for)`;
}

// ----------------------------------------------------------------------------------- 3D view
const view = $('#view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor('#fafaf7');
renderer.domElement.className = 'three';
view.prepend(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(30, 1, 1e-3, 1e3);
const up = [0, 0, 0];
up[data.up] = 1;
camera.up.set(...up);
scene.add(new THREE.HemisphereLight('#ffffff', '#555555', 1.6));
const light = new THREE.DirectionalLight('#ffffff', 1.4);
light.position.set(0.3, 0.5, 1);
camera.add(light);
scene.add(camera);

// The view of T's bounding box from in front, a little to the right and above.
const box = data.arrays.tp_positions;
const lo = new THREE.Vector3(...box.min), hi = new THREE.Vector3(...box.max);
const centre = lo.clone().add(hi).multiplyScalar(0.5);
const radius = Math.max(hi.clone().sub(lo).length() / 2, 1e-9);
camera.near = radius / 100;
camera.far = radius * 100;
const right = [0, 0, 0], front = [0, 0, 0];
right[(data.up + 2) % 3] = 1;
front[(data.up + 1) % 3] = 1;
const direction = new THREE.Vector3(...right).multiplyScalar(0.45)
  .add(new THREE.Vector3(...up).multiplyScalar(0.35)).add(new THREE.Vector3(...front)).normalize();
camera.position.copy(centre).addScaledVector(direction, radius / Math.sin(THREE.MathUtils.degToRad(15)) * 0.9);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.copy(centre);
controls.update();
controls.saveState();

let frameWanted = false;
function render() {
  if (frameWanted) return;
  frameWanted = true;
  requestAnimationFrame(() => {
    frameWanted = false;
    renderer.render(scene, camera);
    hook.frames++;
  });
}
function resize() {
  const { clientWidth: w, clientHeight: h } = view;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  render();
}
controls.addEventListener('change', render);
window.addEventListener('resize', resize);
const reset = () => { controls.reset(); render(); };
$('#reset').addEventListener('click', reset);
window.addEventListener('keydown', (e) => { if (e.key === 'r' && e.target === document.body) reset(); });

// ------------------------------------------------------------------------------- geometry
const surfaceMaterial = (colour) => new THREE.MeshLambertMaterial({
  color: colour, flatShading: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
const lines = (colour) => new THREE.LineBasicMaterial({ color: colour });

function indexedMesh(positions, index, material) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setIndex(new THREE.BufferAttribute(index, 1));
  return new THREE.Mesh(g, material);
}

/** Each undirected edge of a triangle list once, as index pairs. */
function edgesOf(faces) {
  const seen = new Set(), out = [];
  for (let f = 0; f < faces.length; f += 3)
    for (let k = 0; k < 3; k++) {
      const a = faces[f + k], b = faces[f + (k + 1) % 3];
      const key = a < b ? a * 4294967296 + b : b * 4294967296 + a;
      if (!seen.has(key)) { seen.add(key); out.push(a, b); }
    }
  return new Uint32Array(out);
}

function segments(positions, pairs, colour) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setIndex(new THREE.BufferAttribute(pairs, 1));
  return new THREE.LineSegments(g, lines(colour));
}

const build = new Map();
/** Scene parts, made the first time a stage needs them. */
function part(name) {
  if (!build.has(name)) {
    const object = PARTS[name]();
    scene.add(object);
    build.set(name, object);
  }
  return build.get(name);
}

const patchColour = (d) => new THREE.Color().setHSL((d * 0.6180339887) % 1, 0.5, 0.62);

// T′ as drawn, one vertex per corner: its colours (per face) and checkerboard coordinates (β1, β2).
function refinedGeometry() {
  const p = data.array('tp_positions'), faces = data.array('tp_faces'), beta = data.array('tp_beta');
  const n = faces.length;
  const position = new Float32Array(3 * n), uv = new Float32Array(2 * n);
  for (let c = 0; c < n; c++) {
    position.set(p.subarray(3 * faces[c], 3 * faces[c] + 3), 3 * c);
    uv[2 * c] = beta[2 * c] * CHECKER_CELLS;
    uv[2 * c + 1] = beta[2 * c + 1] * CHECKER_CELLS;
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(position, 3));
  g.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
  g.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(3 * n), 3, true));
  return g;
}

const checkerTexture = (() => {
  const a = new THREE.Color(CHECKER[0]), b = new THREE.Color(CHECKER[1]);
  const texels = new Uint8Array([a, b, b, a].flatMap((c) => [c.r * 255, c.g * 255, c.b * 255, 255]));
  const t = new THREE.DataTexture(texels, 2, 2);
  t.wrapS = t.wrapT = THREE.RepeatWrapping;
  t.magFilter = THREE.NearestFilter;
  t.colorSpace = THREE.SRGBColorSpace;
  t.needsUpdate = true;
  return t;
})();

const PARTS = {
  T: () => indexedMesh(data.array('tp_positions'), decimated ? data.array('tp_faces') : data.array('t_faces'), surfaceMaterial(SURFACE)),
  D: () => indexedMesh(data.array('d_positions'), data.array('d_faces'), surfaceMaterial('#b9c4dc')),
  DEdges: () => segments(data.array('d_positions'), edgesOf(data.array('d_faces')), D_COLOUR),
  DVertices: () => new THREE.Points(
    new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(data.array('d_positions'), 3)),
    new THREE.PointsMaterial({ color: D_COLOUR, size: 5, sizeAttenuation: false })),
  refined: () => new THREE.Mesh(refinedGeometry(), new THREE.MeshLambertMaterial({
    vertexColors: true, flatShading: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  })),
  curves: () => {
    const group = new THREE.Group();
    const points = data.array('curve_points'), offsets = data.array('curve_offsets'), kinds = data.array('curve_kinds');
    CURVE_KINDS.forEach((kind, k) => {
      const pairs = [];
      for (let e = 0; e < kinds.length; e++)
        if (kinds[e] === k) for (let i = offsets[e]; i + 1 < offsets[e + 1]; i++) pairs.push(i, i + 1);
      if (pairs.length) group.add(segments(points, new Uint32Array(pairs), kind.colour));
    });
    return group;
  },
  added: () => segments(data.array('tp_positions'), data.array('tp_added_edges'), ADDED),
  highlight: () => {
    const g = new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3));
    return new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: HIGHLIGHT, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2 }));
  },
  level: () => new THREE.Group(),
};

// ----------------------------------------------------------------------------------- stages
const stageState = { s2: { flatD: false }, s3: { added: false }, s4: { colouring: 'checker' }, s5: { level: data.levels, flat: false, keep: null } };
let current = null;

function colourRefined(mode) {
  const mesh = part('refined');
  const colour = mesh.geometry.getAttribute('color');
  const out = colour.array, n = out.length / 3;
  if (mode === 'checker') {
    mesh.material.map = checkerTexture;
    mesh.material.vertexColors = false;
  } else {
    mesh.material.map = null;
    mesh.material.vertexColors = true;
    if (mode === 'patch') {
      const patch = data.array('tp_patch');
      const cache = new Map();
      for (let c = 0; c < n; c++) {
        const d = patch[Math.floor(c / 3)];
        if (!cache.has(d)) cache.set(d, patchColour(d).toArray().map((x) => Math.round(x * 255)));
        out.set(cache.get(d), 3 * c);
      }
    } else {
      const rgb = data.array(mode === 'anisotropy' ? 'tp_anisotropy_rgb' : 'tp_stretch_rgb');
      for (let c = 0; c < n; c++) out.set(rgb.subarray(3 * Math.floor(c / 3), 3 * Math.floor(c / 3) + 3), 3 * c);
    }
    colour.needsUpdate = true;
  }
  mesh.material.needsUpdate = true;
}

function showOnly(names) {
  for (const [name, object] of build) object.visible = names.includes(name);
  for (const name of names) part(name).visible = true;
}

const legendRow = (colour, label, kind = 'swatch') => `<div class="row"><span class="${kind}" style="background:${colour}"></span>${label}</div>`;
function colourBar(legend, title) {
  return `<div>${title}</div><div class="bar">${legend.colours.map((c) => `<span style="background:${c}"></span>`).join('')}</div>` +
    `<div class="ticks">${legend.ticks.map((t) => `<span>${t}</span>`).join('')}</div>`;
}
const curveLegend = () => CURVE_KINDS.map((k) => legendRow(k.colour, k.name)).join('');

function checkbox(id, label, checked, onChange) {
  $('#controls').insertAdjacentHTML('beforeend', `<label><input type="checkbox" id="${id}" ${checked ? 'checked' : ''}> ${label}</label>`);
  $(`#${id}`).addEventListener('change', (e) => { onChange(e.target.checked); render(); });
}
function slider(id, label, max, value, onInput) {
  $('#controls').insertAdjacentHTML('beforeend', `<label>${label} <input type="range" id="${id}" min="0" max="${max}" step="1" value="${value}"></label>`);
  $(`#${id}`).addEventListener('input', (e) => { onInput(Number(e.target.value)); render(); });
}

const STAGE_VIEWS = {
  s2() {
    const s = stageState.s2;
    const draw = () => {
      showOnly(s.flatD ? ['D', 'DEdges', 'DVertices'] : ['T', 'DEdges', 'DVertices']);
      $('#legend').innerHTML = (s.flatD ? legendRow('#b9c4dc', 'D, its faces flat') : legendRow(SURFACE, 'T')) +
        legendRow(D_COLOUR, 'D: its edges (straight) and vertices');
    };
    checkbox('flat-d', 'D alone, its faces flat', s.flatD, (v) => { s.flatD = v; draw(); });
    draw();
  },
  s3() {
    const s = stageState.s3;
    const draw = () => {
      colourRefined('patch');
      showOnly(['refined', 'curves', ...(s.added ? ['added'] : [])]);
      $('#legend').innerHTML = legendRow(patchColour(0).getStyle(), 'T′: each patch its own colour') + curveLegend() +
        (s.added ? legendRow(ADDED, 'edges of T′ inside faces of T') : '');
    };
    if (data.has('tp_added_edges')) checkbox('added-edges', 'T′\'s added edges', s.added, (v) => { s.added = v; draw(); });
    draw();
  },
  s4() {
    const s = stageState.s4;
    const draw = () => {
      colourRefined(s.colouring);
      showOnly(['refined', 'highlight', ...(s.colouring === 'checker' ? [] : ['curves'])]);
      const legends = data.legends;
      $('#legend').innerHTML = (s.colouring === 'checker'
        ? legendRow(CHECKER[0], 'the checkerboard of D carried by φ:') + legendRow(CHECKER[1], `${CHECKER_CELLS}×${CHECKER_CELLS} squares in each triangle's (β₁, β₂)`)
        : s.colouring === 'anisotropy'
          ? colourBar(legends.anisotropy, 'σ₁/σ₂ per face (log scale; grey: degenerate)') + curveLegend()
          : colourBar(legends.stretch, 'stretch per face, √((σ₁² + σ₂²)/2) normalised (log scale)') + curveLegend()) +
        legendRow(HIGHLIGHT, 'the clicked face');
    };
    $('#controls').insertAdjacentHTML('beforeend', ['checker', 'anisotropy', 'stretch'].map((mode) =>
      `<label><input type="radio" name="colouring" id="colour-${mode}" value="${mode}" ${s.colouring === mode ? 'checked' : ''}> ` +
      `${{ checker: 'checkerboard through φ', anisotropy: 'σ₁/σ₂', stretch: 'stretch' }[mode]}</label>`).join(''));
    document.querySelectorAll('input[name=colouring]').forEach((input) =>
      input.addEventListener('change', (e) => { s.colouring = e.target.value; draw(); render(); }));
    draw();
  },
  s5() {
    if (!data.levels) {
      showOnly(['T']);
      $('#legend').innerHTML = '';
      return;
    }
    const s = stageState.s5;
    const group = part('level');
    const draw = () => {
      group.clear();
      const j = s.keep === null ? s.level : data.levels;
      const faces = data.array(`level_faces_${j}`);
      const positions = s.keep !== null ? data.array(`rate_${s.keep}`) : data.array(s.flat ? 'dj_positions' : 'fj_positions');
      const mesh = indexedMesh(positions, faces, surfaceMaterial(s.keep !== null ? '#ffffff' : SURFACE));
      if (s.keep !== null) {
        mesh.geometry.setAttribute('color', new THREE.BufferAttribute(data.array(`rate_rgb_${s.keep}`), 3, true));
        mesh.material.vertexColors = true;
      }
      group.add(mesh);
      if (s.keep === null) group.add(segments(positions, edgesOf(faces), '#555555'));
      showOnly(['level']);
      let readout;
      if (s.keep === null) {
        readout = `${s.flat ? 'D' : 'f'}^${j}: ${(faces.length / 3).toLocaleString('en-US')} faces` +
          (j === data.levels ? `; f^${j}'s Hausdorff distance to T ${report.remesh.hausdorff.toPrecision(3)}` : '');
      } else {
        const r = data.rate[s.keep];
        readout = `${r.percent} % of the coefficients (${r.count.toLocaleString('en-US')}): L2 error ${r.l2.toPrecision(3)}, ` +
          `Hausdorff ${r.hausdorff.toPrecision(3)}`;
      }
      $('#readout').textContent = readout;
      $('#legend').innerHTML = s.keep === null
        ? legendRow(SURFACE, s.flat ? 'D^j: D split j times, flat' : 'f^j = φ at the vertices of D^j') + legendRow('#555555', 'edges of D^j')
        : colourBar({ ...data.legends.error, ticks: data.legends.error.ticks.map((t) => t.toPrecision(2)) },
          'f^J from the largest coefficients, each vertex by its distance from f^J');
    };
    slider('level', 'level j', data.levels, s.level, (j) => { s.level = j; s.keep = null; draw(); });
    checkbox('flat-dj', 'D^j (flat, in D) instead of f^j', s.flat, (v) => { s.flat = v; s.keep = null; draw(); });
    slider('keep', 'coefficients kept', data.rate.length - 1, s.keep ?? data.rate.length - 1, (k) => { s.keep = k; draw(); });
    draw();
  },
  run() {
    showOnly(['refined', 'curves']);
    colourRefined('patch');
    $('#legend').innerHTML = legendRow(patchColour(0).getStyle(), 'T′: each patch its own colour') + curveLegend();
    const t = data.timings;
    $('#tables').innerHTML = '<table id="timings"><tr><th>stage</th><th>fhr (s)</th><th>paper (s)</th></tr>' +
      PAPER_TIMINGS.map(([key, label, paper]) => `<tr><td>${label}</td><td class="timing">${key in t ? t[key].toFixed(3) : '–'}</td><td>${paper}</td></tr>`).join('') +
      '</table>' +
      `<table id="verdict" data-valid="${oracle.valid}"><tr><th>check</th><th>status</th><th>checked</th><th>failures</th></tr>` +
      oracle.checks.map((c) => `<tr data-check="${c.id}"><td>${c.id}</td><td class="${c.status === 'fail' ? 'fail' : 'pass'}">${c.status}</td>` +
        `<td>${c.checked.toLocaleString('en-US')}</td><td>${c.failures}</td></tr>`).join('') + '</table>';
  },
};

function setStage(id) {
  current = id;
  const stage = STAGES.find((s) => s.id === id);
  document.querySelectorAll('#stages button').forEach((b) => b.setAttribute('aria-pressed', String(b.dataset.stage === id)));
  $('#text').innerHTML = stage.text(report).map((p) => `<p>${p}</p>`).join('');
  for (const id of ['#controls', '#readout', '#legend', '#tables']) $(id).innerHTML = '';
  panel.hide();
  STAGE_VIEWS[id]();
  render();
}

for (const stage of STAGES) {
  const b = document.createElement('button');
  b.dataset.stage = stage.id;
  b.textContent = stage.title;
  b.addEventListener('click', () => setStage(stage.id));
  $('#stages').append(b);
}

// --------------------------------------------------------------------------------- picking
const panel = new PatchPanel($('#patch-panel'), data);
$('#patch-panel .close').addEventListener('click', () => { panel.hide(); part('highlight').visible = false; render(); });
const raycaster = new THREE.Raycaster();
const original = (f) => (decimated ? data.array('tp_original')[f] : f);

/** The face of T′ (as drawn) seen at client point (x, y), or -1. */
function faceAt(x, y) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObject(part('refined'), false)[0];
  return hit ? hit.faceIndex : -1;
}

function select(f) {
  const p = part('refined').geometry.getAttribute('position').array;
  const h = part('highlight');
  h.geometry.getAttribute('position').array.set(p.subarray(9 * f, 9 * f + 9));
  h.geometry.getAttribute('position').needsUpdate = true;
  h.geometry.computeBoundingSphere();
  h.visible = true;
  panel.show(f, original(f));
  render();
}

let down = null;
renderer.domElement.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4 || current !== 's4') return;
  const f = faceAt(e.clientX, e.clientY);
  if (f >= 0) select(f);
});

// ----------------------------------------------------------------------------------- hook
const hook = {
  firstFrame: null, // performance.now() (ms since navigation start) when T was first on the screen
  frames: 0,
  stage: () => current,
  faces: () => data.arrays.tp_faces.count / 3,
  /** Client coordinates of the centroid of face f of T′ (as drawn) when that face is seen there, else null. */
  project(f) {
    part('refined');
    const p = part('refined').geometry.getAttribute('position').array;
    const c = new THREE.Vector3(0, 0, 0);
    for (let k = 0; k < 3; k++) c.add(new THREE.Vector3(p[9 * f + 3 * k], p[9 * f + 3 * k + 1], p[9 * f + 3 * k + 2]));
    c.multiplyScalar(1 / 3).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    const x = rect.left + (c.x + 1) / 2 * rect.width, y = rect.top + (1 - c.y) / 2 * rect.height;
    if (Math.abs(c.x) > 1 || Math.abs(c.y) > 1) return null;
    return faceAt(x, y) === f ? { x, y } : null;
  },
  original,
};
window.fhrPage = hook;

resize();
setStage('s2');
requestAnimationFrame(() => requestAnimationFrame(() => { hook.firstFrame = performance.now(); }));
