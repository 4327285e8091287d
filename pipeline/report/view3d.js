// The report's 3D view (docs/report.md): the wireframe, the trajectories and the camera frusta of
// the scene JSON that report.cc writes into the script element #view3d-scene, drawn with three.js
// (inlined through the page's import map) and turned with OrbitControls: left drag orbits, the
// wheel zooms, right drag (or shift + left drag) pans. After the first frame the container gets
// data-view3d="drawn", data-drawn-pixels (the pixels that differ from the white background) and
// data-canvas-pixels, which tests/report/report_browser_test.sh reads.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const container = document.getElementById('view3d');
const scene3d = JSON.parse(document.getElementById('view3d-scene').textContent);
const vector = (xyz) => new THREE.Vector3(xyz[0], xyz[1], xyz[2]);

function geometryOf(flat) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(flat, 3));
  return geometry;
}

// Coordinates relative to the centre, so that float32 keeps millimetres on maps far from the origin.
function centred(flat) {
  const out = new Float32Array(flat.length);
  for (let i = 0; i < flat.length; ++i) out[i] = flat[i] - scene3d.centre[i % 3];
  return out;
}

const scene = new THREE.Scene();
scene.background = new THREE.Color('#ffffff');
scene.add(new THREE.LineSegments(geometryOf(centred(scene3d.edges)),
                                 new THREE.LineBasicMaterial({ color: scene3d.colours.edges })));
scene.add(new THREE.Points(geometryOf(centred(scene3d.points)),
                           new THREE.PointsMaterial({ color: scene3d.colours.points, size: 4,
                                                      sizeAttenuation: false })));
for (const path of scene3d.paths) {
  const material = new THREE.LineBasicMaterial({ color: path.colour });
  scene.add(new THREE.Line(geometryOf(centred(path.xyz)), material));
}
scene.add(new THREE.LineSegments(geometryOf(centred(scene3d.frusta.xyz)),
                                 new THREE.LineBasicMaterial({ color: scene3d.frusta.colour })));

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
container.textContent = '';  // the note shown where modules or WebGL are missing
container.appendChild(renderer.domElement);

// Looking at the bulk of the map from behind the start of the camera path, 35 degrees from above,
// with gravity up (the floor down, as in the static views).
const radius = scene3d.radius;
const camera = new THREE.PerspectiveCamera(45, 2, radius / 1000, radius * 100);
camera.up.copy(vector(scene3d.up));
const eye = vector(scene3d.along).multiplyScalar(-0.75)
                .add(vector(scene3d.across).multiplyScalar(-0.35))
                .add(vector(scene3d.up).multiplyScalar(0.55));
camera.position.copy(eye.normalize().multiplyScalar(2.2 * radius));
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(0, 0, 0);
controls.update();
controls.saveState();

function render() {
  renderer.render(scene, camera);
}

function resize() {
  const width = container.clientWidth, height = Math.round(Math.min(640, Math.max(320, width / 2)));
  renderer.setSize(width, height);
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
  render();
}

controls.addEventListener('change', render);
new ResizeObserver(resize).observe(container);
document.getElementById('view3d-reset').addEventListener('click', () => controls.reset());
resize();

// What the first frame drew, for the browser test: pixels that differ from the white background.
const gl = renderer.getContext();
const pixels = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
let drawn = 0;
for (let i = 0; i < pixels.length; i += 4) {
  if (pixels[i] < 250 || pixels[i + 1] < 250 || pixels[i + 2] < 250) ++drawn;
}
container.dataset.drawnPixels = String(drawn);
container.dataset.canvasPixels = String(pixels.length / 4);
container.dataset.view3d = 'drawn';
