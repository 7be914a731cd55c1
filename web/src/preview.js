// relief preview's page: the model relief serves (model.glb) in the still's
// frame, seen from the still's camera (page.json), orbited, panned, zoomed and
// flown by the user; "Use this view" sends the view back, and relief writes
// the [camera] keys that make the still of exactly this view.
//
// Axes: the model's are glTF's (x east, y up, z south, metres), three.js's
// own; POV-Ray's are left-handed (z north), which relief converts. three.js's
// fov is vertical, POV-Ray's angle horizontal: the page keeps the horizontal
// one (fovDeg) and gives three.js the vertical one of the still's aspect.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const $ = (id) => document.getElementById(id);
const timings = {};  // milliseconds since the navigation started, by step (the first time only)
const mark = (step) => { if (!(step in timings)) timings[step] = performance.now(); };
const state = { page: null, generation: -1, fovDeg: 40, keyframes: [], firstFrameMs: null, model: null };

mark('module');
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, alpha: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.shadowMap.enabled = true;
renderer.shadowMap.type = THREE.PCFShadowMap;
mark('webgl');
const scene = new THREE.Scene();
const sky = new THREE.Color(0x9fc3e6);
scene.background = sky;
const camera = new THREE.PerspectiveCamera(30, 1.5, 1, 1e6);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = false;
controls.screenSpacePanning = true;
const sun = new THREE.DirectionalLight(0xffffff, 2.4);
sun.castShadow = true;
sun.shadow.mapSize.set(2048, 2048);
scene.add(sun, sun.target, new THREE.HemisphereLight(0xdfe9f5, 0x4a4136, 0.9));
let water = null;

function setStatus(text) { $('status').textContent = text; }
function setDiagnostics(text) { $('diagnostics').textContent = text || ''; }

async function post(path, body) {
  const r = await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  const reply = await r.json();
  if (!r.ok) throw new Error(reply.error || `${path}: HTTP ${r.status}`);
  return reply;
}

// The still's frame: the largest box of its aspect the stage holds.
function fitFrame() {
  if (!state.page) return;
  const { width, height } = state.page.still;
  const stage = $('stage');
  const scale = state.fixedFrame ? 1 : Math.min(stage.clientWidth / width, stage.clientHeight / height);
  const w = Math.max(1, Math.floor(width * scale)), h = Math.max(1, Math.floor(height * scale));
  $('frame').style.width = `${w}px`;
  $('frame').style.height = `${h}px`;
  renderer.setSize(w, h, false);
  camera.aspect = width / height;
  applyFov();
}

// three.js's vertical fov from the still's horizontal one.
function applyFov() {
  const tanH = Math.tan(state.fovDeg * Math.PI / 360);
  camera.fov = 2 * Math.atan(tanH / camera.aspect) * 180 / Math.PI;
  camera.updateProjectionMatrix();
  $('fov').value = state.fovDeg;
}

function clipPlanes() {
  const d = camera.position.distanceTo(controls.target);
  const [lo, hi] = state.page.bounds;
  const span = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  camera.near = Math.max(1e-3 * Math.min(d, span), 0.01);
  camera.far = 20 * (d + span);
  camera.updateProjectionMatrix();
}

// A view: the eye, the point looked at (model axes) and the horizontal fov.
function setView(view) {
  camera.position.fromArray(view.eye);
  controls.target.fromArray(view.target);
  // Straight down has no heading: nudge the eye a millionth of the distance south, as the still
  // then reads north up (relief does the same with the keys this view writes).
  const d = camera.position.distanceTo(controls.target);
  const horizontal = Math.hypot(camera.position.x - controls.target.x, camera.position.z - controls.target.z);
  if (horizontal < 1e-6 * d) camera.position.z = controls.target.z + 1e-6 * d;
  state.fovDeg = view.fovDeg;
  camera.lookAt(controls.target);
  applyFov();
  clipPlanes();
  controls.update();
  changed();
}
function currentView() {
  return { eye: camera.position.toArray(), target: controls.target.toArray(), fovDeg: state.fovDeg };
}

function placeSun(azimuthDeg, altitudeDeg) {
  const a = azimuthDeg * Math.PI / 180, e = altitudeDeg * Math.PI / 180;
  const dir = new THREE.Vector3(Math.sin(a) * Math.cos(e), Math.sin(e), -Math.cos(a) * Math.cos(e));
  const [lo, hi] = state.page.bounds;
  const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  const span = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  sun.target.position.copy(centre);
  sun.position.copy(centre).addScaledVector(dir, span);
  const cam = sun.shadow.camera;
  cam.left = cam.bottom = -span / 2;
  cam.right = cam.top = span / 2;
  cam.near = span * 0.01;
  cam.far = span * 2;
  cam.updateProjectionMatrix();
  $('sunAz').value = azimuthDeg;
  $('sunEl').value = altitudeDeg;
  changed();
}

function placeWater(page) {
  if (water) { scene.remove(water); water.geometry.dispose(); water = null; }
  if (!page.water) return;
  const [lo, hi] = page.bounds;
  const geometry = new THREE.PlaneGeometry(hi[0] - lo[0], hi[2] - lo[2]);
  geometry.rotateX(-Math.PI / 2);
  const [r, g, b] = page.water.colour;
  water = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
    color: new THREE.Color(r, g, b), transparent: true, opacity: 1 - page.water.transparency, roughness: 0.15 }));
  water.position.set((lo[0] + hi[0]) / 2, page.water.y, (lo[2] + hi[2]) / 2);
  scene.add(water);
}

// The still's furniture as outlines on the frame, where relief places it from the scene's camera
// (names set as text, never markup).
function drawFurniture(page) {
  const svg = $('furniture');
  const ns = 'http://www.w3.org/2000/svg';
  svg.replaceChildren();
  svg.setAttribute('viewBox', `0 0 ${page.still.width} ${page.still.height}`);
  svg.setAttribute('preserveAspectRatio', 'none');
  for (const { item, box: [x0, y0, x1, y1] } of page.furniture || []) {
    const rect = document.createElementNS(ns, 'rect');
    for (const [k, v] of Object.entries({ x: x0, y: y0, width: x1 - x0, height: y1 - y0 })) rect.setAttribute(k, v);
    rect.setAttribute('fill', 'none');
    rect.setAttribute('stroke', 'rgba(255,255,255,0.85)');
    rect.setAttribute('stroke-dasharray', '6 4');
    rect.setAttribute('vector-effect', 'non-scaling-stroke');
    const label = document.createElementNS(ns, 'text');
    label.setAttribute('x', x0 + 3);
    label.setAttribute('y', y0 + 14);
    label.setAttribute('fill', 'rgba(255,255,255,0.9)');
    label.setAttribute('font-size', 12 * page.still.width / Math.max(1, $('frame').clientWidth));
    label.textContent = item;
    svg.append(rect, label);
  }
}

let frameRequested = false;
function changed() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(draw);
}
function draw() {
  frameRequested = false;
  if (!state.page) return;
  renderer.render(scene, camera);
  if (state.model && state.firstFrameMs === null) {
    mark('first frame');
    state.firstFrameMs = performance.now();
    window.reliefPreview.firstFrameMs = state.firstFrameMs;
    window.reliefPreview.ready = true;
  }
  showKeysSoon();
}

// The [camera] keys this view writes, asked of relief a moment after the view stops changing.
let keysTimer = null;
function showKeysSoon() {
  clearTimeout(keysTimer);
  keysTimer = setTimeout(async () => {
    try {
      const reply = await post('keys', currentView());
      $('keys').textContent = `[camera]\n${reply.toml}`;
    } catch (e) { $('keys').textContent = String(e.message); }
  }, 150);
}

async function loadModel(generation) {
  const loader = new GLTFLoader();
  const gltf = await loader.loadAsync(`model.glb?g=${generation}`);
  if (state.model) scene.remove(state.model);
  state.model = gltf.scene;
  state.model.traverse((o) => { if (o.isMesh) { o.castShadow = true; o.receiveShadow = true; } });
  scene.add(state.model);
}

// The scene as relief has it now (first, and after the file changed).
async function load() {
  mark('script');
  const page = await (await fetch('page.json')).json();
  mark('page.json');
  state.generation = page.generation;
  setDiagnostics(page.diagnostics);
  if (!page.preview) { setStatus('the scene does not compile: its diagnostics below'); return; }
  const first = !state.page;
  state.page = page.preview;
  $('title').textContent = `relief preview: ${state.page.scene}`;
  fitFrame();
  await loadModel(page.generation);
  mark('model');
  placeWater(state.page);
  drawFurniture(state.page);
  if (first) {
    setView(state.page.camera);
    placeSun(state.page.sun.azimuthDeg, state.page.sun.altitudeDeg);
  }
  const m = state.page.model;
  setStatus(`${m.triangles.toLocaleString('en')} triangles` +
            (m.toleranceM > 0 ? ` (an adaptive mesh within ${m.toleranceM.toPrecision(3)} m)` : '') +
            (state.page.camera.perspective ? '' : '\nthe still\'s projection is not a perspective: the preview shows one'));
  changed();
}

// relief rebuilds the preview when the scene file changes: reload then.
async function watch() {
  try {
    const s = await (await fetch('state')).json();
    if (s.generation !== state.generation && !s.building) await load();
    if (s.building) setStatus('the scene changed: rebuilding');
  } catch (e) { setStatus(`relief preview has stopped (${e.message})`); }
  setTimeout(watch, 1000);
}

// Flying: W A S D along and across the view, Q E down and up, + and - the field of view.
const flyKeys = { KeyW: [0, 0, -1], KeyS: [0, 0, 1], KeyA: [-1, 0, 0], KeyD: [1, 0, 0], KeyQ: [0, -1, 0], KeyE: [0, 1, 0] };
window.addEventListener('keydown', (ev) => {
  if (ev.target.tagName === 'INPUT') return;
  if (flyKeys[ev.code] && state.page) {
    const step = 0.02 * camera.position.distanceTo(controls.target) * (ev.shiftKey ? 5 : 1);
    const move = new THREE.Vector3(...flyKeys[ev.code]).applyQuaternion(camera.quaternion).multiplyScalar(step);
    if (ev.code === 'KeyQ' || ev.code === 'KeyE') move.set(0, flyKeys[ev.code][1] * step, 0);
    camera.position.add(move);
    controls.target.add(move);
    controls.update();
    clipPlanes();
    changed();
  } else if (ev.key === '+' || ev.key === '-') {
    state.fovDeg = Math.min(120, Math.max(5, state.fovDeg * (ev.key === '+' ? 1 / 1.05 : 1.05)));
    applyFov();
    changed();
  } else if (ev.code === 'KeyK') addKeyframe();
});
controls.addEventListener('change', () => { clipPlanes(); changed(); });
$('fov').addEventListener('input', () => { state.fovDeg = Number($('fov').value); applyFov(); changed(); });
const sunInput = () => placeSun(Number($('sunAz').value), Number($('sunEl').value));
$('sunAz').addEventListener('input', sunInput);
$('sunEl').addEventListener('input', sunInput);
window.addEventListener('resize', () => { fitFrame(); changed(); });

$('use').addEventListener('click', async () => {
  try {
    const reply = await post('use', currentView());
    setStatus(reply.written ? `wrote the view into ${reply.written}` : 'the view\'s keys are printed in the terminal');
  } catch (e) { setDiagnostics(e.message); }
});

function addKeyframe() {
  state.keyframes.push(currentView());
  $('keyframes').textContent = `${state.keyframes.length} keyframe${state.keyframes.length === 1 ? '' : 's'}`;
}
$('key').addEventListener('click', addKeyframe);
$('savePath').addEventListener('click', async () => {
  try {
    const reply = await post('path', { keyframes: state.keyframes });
    setStatus(`wrote the ${state.keyframes.length} keyframes as [animation] into ${reply.written}`);
  } catch (e) { setDiagnostics(e.message); }
});

$('render').addEventListener('click', async () => {
  try {
    await post('render', currentView());
    setStatus('rendering the still of this view');
    const poll = async () => {
      const s = await (await fetch('still')).json();
      if (s.running) return setTimeout(poll, 1000);
      if (s.error) return setDiagnostics(s.error);
      $('still').src = `still.png?t=${Date.now()}`;
      $('still').style.display = 'block';
      setStatus(`rendered the still of this view (${s.seconds.toFixed(1)} s)`);
    };
    poll();
  } catch (e) { setDiagnostics(e.message); }
});

// What a test (or a user's console) drives: the view, the page's own chrome hidden.
window.reliefPreview = {
  ready: false,
  firstFrameMs: null,
  setView: (view) => { setView(view); renderer.render(scene, camera); },
  currentView,
  page: () => state.page,
  timings,
  // The terrain alone against nothing, the frame `width` x `height` pixels (the still's, for a
  // test comparing the two): the sky transparent, the page's chrome hidden.
  hideFurniture: (width, height) => {
    scene.background = null;
    document.documentElement.style.background = document.body.style.background = 'transparent';
    $('frame').style.boxShadow = 'none';
    $('furniture').style.display = 'none';
    if (width && height) {
      // At the stage's corner, on whole pixels, so that a screenshot of the canvas is the still's size.
      $('stage').style.alignItems = $('stage').style.justifyContent = 'flex-start';
      document.querySelector('header').style.display = 'none';
      state.fixedFrame = { width, height };
      fitFrame();
    }
    renderer.render(scene, camera);
  },
};

load().then(() => setTimeout(watch, 1000)).catch((e) => setDiagnostics(String(e.message)));
