// The 3D surface view: the Utah teapot, the NURBS torus and a bicubic patch
// whose heights you edit, meshed by SurfaceService.Tessellate within the
// tolerance you choose and drawn by three.js as the server sent them:
// its vertices, triangles and unit normals go into the buffers unchanged.

import {
  AmbientLight, BufferAttribute, BufferGeometry, Color, DirectionalLight, DoubleSide,
  LineBasicMaterial, LineSegments, Mesh, MeshStandardMaterial, PerspectiveCamera, Scene,
  WebGLRenderer, WireframeGeometry,
} from 'three';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';
import {VertexNormalsHelper} from 'three/addons/helpers/VertexNormalsHelper.js';

import {call} from './rpc.js';
import {Refresher} from './refresher.js';

// Where the camera looks from and at, and the length of the drawn normals,
// for each model (z is up in all three).
const VIEWS = {
  teapot: {eye: [4.9, -5.4, 4.0], target: [0.2, 0, 1.2], normalLength: 0.15},
  torus: {eye: [9, -10, 8], target: [0, 0, 0], normalLength: 0.6},
  patch: {eye: [6, -4, 5], target: [1.5, 1.5, 0.5], normalLength: 0.2},
};
// The edited patch: a bicubic Bezier net on the grid {0, 1, 2, 3}^2 whose
// sixteen heights are the sliders' values.
const PATCH_GRID = [0, 1, 2, 3];
const FIRST_HEIGHTS = [0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 2, 0, 0, 0, 0, 0];

async function fetchJson(path) {
  const answer = await fetch(path);
  if (!answer.ok) throw new Error(`${path}: HTTP ${answer.status}`);
  return answer.json();
}

// The teapot's 32 bicubic patches (examples/teapot.json) as Surfaces.
async function teapotSurfaces() {
  const teapot = await fetchJson('/examples/teapot.json');
  return teapot.patches.map((patch) => ({
    bezier: {controlNet: {dimension: 3, countU: 4, countV: 4, coordinates: patch.control_points.flat()}},
  }));
}

// The NURBS torus of examples/torus_mesh.json.
async function torusSurfaces() {
  return (await fetchJson('/examples/torus_mesh.json')).surfaces;
}

export class SurfaceView {
  constructor(root, report) {
    this.root = root;
    this.controls = Object.fromEntries(
        [...root.querySelectorAll('[data-control]')].map((node) => [node.dataset.control, node]));
    this.heights = [...FIRST_HEIGHTS];
    this.sources = {teapot: teapotSurfaces(), torus: torusSurfaces()};
    this.sources.teapot.catch(() => {});
    this.sources.torus.catch(() => {});
    // What the last redraw drew: the request and the server's vertex count.
    this.drawn = {request: null, vertexCount: 0, triangleCount: 0};
    this.setUpScene(root.querySelector('canvas'));
    this.buildHeightSliders();
    this.refresher = new Refresher(() => this.redraw(), report);
    for (const name of ['model', 'tolerance', 'normals', 'wireframe']) {
      this.controls[name].addEventListener('change', () => this.refresh());
    }
  }

  setUpScene(canvas) {
    this.renderer = new WebGLRenderer({canvas, antialias: true, preserveDrawingBuffer: true});
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.scene = new Scene();
    this.scene.background = new Color(0xf4f6f8);
    this.camera = new PerspectiveCamera(40, 1, 0.05, 200);
    this.camera.up.set(0, 0, 1);
    this.scene.add(new AmbientLight(0xffffff, 0.9));
    const light = new DirectionalLight(0xffffff, 2.2);
    light.position.set(4, -6, 10);
    this.scene.add(light);
    this.orbit = new OrbitControls(this.camera, canvas);
    this.orbit.addEventListener('change', () => this.render());
    this.material = new MeshStandardMaterial({color: 0x4f7cac, roughness: 0.45, metalness: 0.1, side: DoubleSide});
    this.lineMaterial = new LineBasicMaterial({color: 0x1d2b3a, transparent: true, opacity: 0.55});
    new ResizeObserver(() => this.resize()).observe(canvas);
  }

  resize() {
    const canvas = this.renderer.domElement;
    this.renderer.setSize(canvas.clientWidth, canvas.clientHeight, false);
    this.camera.aspect = canvas.clientWidth / Math.max(1, canvas.clientHeight);
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  buildHeightSliders() {
    const grid = this.controls.heights;
    this.heights.forEach((height, index) => {
      const slider = document.createElement('input');
      Object.assign(slider, {type: 'range', min: '-2', max: '3', step: '0.25', value: String(height)});
      slider.title = `height of P[${index >> 2}][${index & 3}]`;
      slider.addEventListener('input', () => {
        this.heights[index] = Number(slider.value);
        this.refresh();
      });
      grid.appendChild(slider);
    });
  }

  // patchSurfaces returns the edited patch as a Surface.
  patchSurfaces() {
    const coordinates = [];
    PATCH_GRID.forEach((x, i) => PATCH_GRID.forEach((y, j) => coordinates.push(x, y, this.heights[i * 4 + j])));
    return [{bezier: {controlNet: {dimension: 3, countU: 4, countV: 4, coordinates}}}];
  }

  async surfaces(model) {
    return model === 'patch' ? this.patchSurfaces() : this.sources[model];
  }

  refresh() {
    this.root.dataset.model = this.controls.model.value;
    this.refresher.request();
  }

  settled() {
    return this.refresher.settled();
  }

  async redraw() {
    const model = this.controls.model.value;
    const request = {
      surfaces: await this.surfaces(model),
      tolerance: Number(this.controls.tolerance.value),
      normals: true,
    };
    const mesh = await call('SurfaceService', 'Tessellate', request);
    if (this.refresher.superseded) return;
    this.show(model, mesh);
    this.drawn = {
      request,
      vertexCount: this.geometry.getAttribute('position').count,
      triangleCount: this.renderer.info.render.triangles,
    };
    this.controls.vertexCount.textContent = String(this.drawn.vertexCount);
    this.controls.triangleCount.textContent = String(this.drawn.triangleCount);
  }

  // show replaces the scene's mesh by the server's, and draws it.
  show(model, mesh) {
    for (const object of [this.mesh, this.wireframe, this.normals]) {
      if (object) {
        this.scene.remove(object);
        object.geometry.dispose();
      }
    }
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(new Float32Array(mesh.vertices.coordinates), 3));
    geometry.setAttribute('normal', new BufferAttribute(new Float32Array(mesh.normals.coordinates), 3));
    geometry.setIndex(new BufferAttribute(new Uint32Array(mesh.triangles), 1));
    this.geometry = geometry;
    this.mesh = new Mesh(geometry, this.material);
    this.scene.add(this.mesh);
    this.wireframe = this.controls.wireframe.checked ?
      new LineSegments(new WireframeGeometry(geometry), this.lineMaterial) : null;
    if (this.wireframe) this.scene.add(this.wireframe);
    const view = VIEWS[model];
    this.normals = this.controls.normals.checked ?
      new VertexNormalsHelper(this.mesh, view.normalLength, 0xc0392b) : null;
    if (this.normals) this.scene.add(this.normals);
    if (this.shownModel !== model) {
      this.camera.position.set(...view.eye);
      this.orbit.target.set(...view.target);
      this.orbit.update();
      this.shownModel = model;
    }
    this.resize();
  }
}
