// kerf's viewer: watches one session's cut over the server's WebSocket (see
// server/service/web_server.h), decoding the same Frame messages a gRPC observer gets.
// The link to a view carries the session and token in the fragment (#session=..&token=..), so
// they are not sent to any server in a request line.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import protobuf from 'protobufjs/light.js';
import descriptor from './generated/kerf.json';
import { FrameView } from './frame_view.js';

const Frame = protobuf.Root.fromJSON(descriptor).lookupType('kerf.v1.Frame');
const $ = (id) => document.getElementById(id);

// --- what the page shows, also read by the browser tests -----------------------------------
const state = { connected: false, triangles: 0, onCut: 0, sequence: 0, gaps: 0, fps: 0,
                latencyMs: 0, tets: 0, frames: 0, reconnects: 0, error: '', recent: [],
                forceFrames: 0, largestForce: 0 };
window.kerf = state;

// --- the scene ------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1b1d21);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 10);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(1, 2, 3);
scene.add(sun);
const geometry = new THREE.BufferGeometry();
const surface = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
  vertexColors: true, side: THREE.DoubleSide, roughness: 0.7, flatShading: true }));
scene.add(surface);
const blade = new THREE.Line(new THREE.BufferGeometry(),
                             new THREE.LineBasicMaterial({ color: 0xe0e0ff }));
blade.geometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(6), 3));
blade.visible = false;
scene.add(blade);
const force = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 0.01, 0xffb020);
force.visible = false;
scene.add(force);
let framed = false;

function resize() {
  renderer.setSize(window.innerWidth, window.innerHeight);
  camera.aspect = window.innerWidth / window.innerHeight;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

const TISSUE = new THREE.Color(0xc86464), CUT = new THREE.Color(0xf0e0a0);

// Rebuilds the triangles from the SURFACE view (colours from the FORCES view when asked).
function draw(view, forces) {
  const tris = [...view.elements.values()];
  const positions = new Float32Array(tris.length * 9), colors = new Float32Array(tris.length * 9);
  let largest = 0;
  if (forces) for (let i = 0; i < forces.values.length; i += 3) {
    largest = Math.max(largest, Math.hypot(forces.values[i], forces.values[i + 1], forces.values[i + 2]));
  }
  state.largestForce = largest;
  const heat = new THREE.Color();
  let cut = 0;
  tris.forEach((t, k) => {
    if (t.onCut) cut += 1;
    t.vertices.forEach((id, c) => {
      const p = view.value(id);
      if (p) positions.set(p, 9 * k + 3 * c);
      let color = t.onCut ? CUT : TISSUE;
      const f = forces?.value(id);
      if (f && largest > 0) color = heat.setHSL(0.66 * (1 - Math.hypot(f[0], f[1], f[2]) / largest), 0.9, 0.5);
      colors.set([color.r, color.g, color.b], 9 * k + 3 * c);
    });
  });
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  if (!framed && tris.length > 0) {  // look at the tissue once, then leave the camera to the user
    const { center, radius } = geometry.boundingSphere;
    controls.target.copy(center);
    camera.position.copy(center).add(new THREE.Vector3(1.2, 1.0, 2.0).multiplyScalar(radius * 1.6));
    controls.update();
    framed = true;
  }
  state.triangles = tris.length;
  state.onCut = cut;
}

function drawBlade(frame) {
  blade.visible = !!frame.bladeTip;
  force.visible = !!frame.bladeTip;
  if (!frame.bladeTip) return;
  const tip = frame.bladeTip, heel = frame.bladeHeel;
  blade.geometry.attributes.position.array.set([tip.x ?? 0, tip.y ?? 0, tip.z ?? 0,
                                                heel.x ?? 0, heel.y ?? 0, heel.z ?? 0]);
  blade.geometry.attributes.position.needsUpdate = true;
  const f = new THREE.Vector3(frame.toolForce?.x ?? 0, frame.toolForce?.y ?? 0, frame.toolForce?.z ?? 0);
  const length = f.length();
  force.visible = length > 1e-6;
  if (force.visible) {
    force.position.set(tip.x ?? 0, tip.y ?? 0, tip.z ?? 0);
    force.setDirection(f.normalize());
    force.setLength(0.005 * Math.min(length, 10), 0.002, 0.001);  // 5 mm per newton
  }
}

// --- the connection -------------------------------------------------------------------------
let sockets = [], retry = 0, want = null;

function open(level, view, onFrame) {
  const url = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}` +
              `/observe?session=${encodeURIComponent(want.session)}&level=${level}`;
  const ws = new WebSocket(url, ['kerf.v1', `token.${want.token}`]);
  ws.binaryType = 'arraybuffer';
  ws.onopen = () => { state.connected = true; state.error = ''; retry = 0; status(''); };
  ws.onmessage = (event) => {
    const frame = Frame.decode(new Uint8Array(event.data));
    if (!view.apply(frame)) { ws.close(); return; }  // out of step: a fresh keyframe
    onFrame(frame);
  };
  ws.onclose = (event) => {
    state.connected = false;
    if (sockets.includes(ws)) reconnect(event.reason || 'connection lost');
  };
  return ws;
}

function connect() {
  for (const ws of sockets) ws.close();
  sockets = [];
  if (!want?.session || !want?.token) return;
  const view = new FrameView();
  const forces = $('heat').checked ? new FrameView() : null;
  let count = 0, since = performance.now();
  sockets.push(open('SURFACE', view, (frame) => {
    draw(view, forces);
    drawBlade(frame);
    count += 1;
    const now = performance.now();
    if (now - since >= 1000) { state.fps = count * 1000 / (now - since); count = 0; since = now; }
    state.sequence = Number(frame.sequence);
    state.recent.push(state.sequence);  // the last few hundred frame numbers drawn
    if (state.recent.length > 300) state.recent.shift();
    state.gaps = view.gaps;
    state.frames = view.frames;
    state.tets = Number(frame.statistics?.tets ?? 0);
    state.latencyMs = Date.now() - Number(frame.sendTimeUnixNanos) / 1e6;
  }));
  if (forces) sockets.push(open('FORCES', forces, () => { state.forceFrames += 1; }));
}

function reconnect(why) {
  state.reconnects += 1;
  state.error = why;
  const delay = Math.min(5000, 200 * 2 ** retry++);
  status(`${why}; reconnecting in ${(delay / 1000).toFixed(1)} s`);
  setTimeout(connect, delay);
}

function status(text) { $('status').textContent = text; }

// --- the page -------------------------------------------------------------------------------
function fromLink() {
  const p = new URLSearchParams(location.hash.slice(1));
  return { session: p.get('session') ?? '', token: p.get('token') ?? '' };
}

async function listSessions(selected) {
  try {
    const list = await (await fetch('api/sessions')).json();
    const select = $('sessions');
    select.replaceChildren(...(list.sessions ?? []).map((s) => {
      const option = new Option(`${s.session_id.slice(0, 8)}… ${s.scene_name} (${s.tets} tets)`,
                                s.session_id);
      option.selected = s.session_id === selected;
      return option;
    }));
  } catch (e) {
    status(`cannot list sessions: ${e}`);
  }
}

function watch(session, token) {
  want = { session, token };
  framed = false;
  $('link').href = `#session=${encodeURIComponent(session)}&token=${encodeURIComponent(token)}`;
  connect();
}

$('watch').onclick = () => {
  const session = $('sessions').value, token = $('token').value;
  history.replaceState(null, '', `#session=${session}&token=${token}`);
  watch(session, token);
};
$('heat').onchange = () => connect();
window.addEventListener('hashchange', () => { const l = fromLink(); watch(l.session, l.token); });

const link = fromLink();
$('token').value = link.token;
listSessions(link.session);
setInterval(() => listSessions(want?.session ?? link.session), 5000);
if (link.session && link.token) watch(link.session, link.token);

(function loop() {
  controls.update();
  renderer.render(scene, camera);
  $('stats').textContent =
    `frames/s ${state.fps.toFixed(1)}   latency ${state.latencyMs.toFixed(1)} ms   ` +
    `tets ${state.tets}\ntriangles ${state.triangles} (${state.onCut} on the cut)   ` +
    `frame ${state.sequence}   gaps ${state.gaps}   ${state.connected ? 'live' : 'offline'}`;
  requestAnimationFrame(loop);
})();
