// The 3D view: one mesh per face (lit, shaded, coloured by deviation), the
// tool at its pose, the device path (engaged and free) and the contacts, with
// orbit, zoom and pan. Coordinates are the model's [mm], Z up.

import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const ENGAGED = new THREE.Color(0.95, 0.55, 0.1);
const FREE = new THREE.Color(0.55, 0.58, 0.62);

export class SceneView {
  constructor(container, data) {
    this.data = data;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0.93, 0.94, 0.95);
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1e7);
    this.camera.up.set(0, 0, 1);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8076, 1.5));
    const key = new THREE.DirectionalLight(0xffffff, 2.2);
    key.position.set(0.4, 0.6, 1);
    this.camera.add(key); // the key light follows the eye: relief reads from every side
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener("change", () => this.render());
    this.meshes = data.faces.map((face, index) => this.faceMesh(face, index));
    this.box = new THREE.Box3();
    for (const mesh of this.meshes) {
      mesh.geometry.computeBoundingBox();
      this.box.union(mesh.geometry.boundingBox);
    }
    this.size = this.box.getSize(new THREE.Vector3()).length() || 1;
    this.addRun();
    this.resize();
    this.fit();
    window.addEventListener("resize", () => {
      this.resize();
      this.render();
    });
  }

  faceMesh(face, index) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(face.positions.slice(), 3));
    geometry.setAttribute("normal", new THREE.BufferAttribute(face.normals.slice(), 3));
    const colours = new Float32Array(face.positions.length).fill(0.8);
    geometry.setAttribute("color", new THREE.BufferAttribute(colours, 3));
    geometry.setIndex(new THREE.BufferAttribute(face.indices, 1));
    const material = new THREE.MeshStandardMaterial({
      vertexColors: true,
      side: THREE.DoubleSide,
      roughness: 0.55,
      metalness: 0.05,
      polygonOffset: true, // the path and contacts stay visible on the surface
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.userData.face = index;
    this.scene.add(mesh);
    return mesh;
  }

  addRun() {
    const { run, tools } = this.data;
    if (!run) return;
    const n = run.time.length;
    // The device path, at most 20000 points (every k-th tick).
    const every = Math.max(1, Math.ceil(n / 20000));
    const points = [], colours = [];
    for (let k = 0; k < n; k += every) {
      points.push(run.device[3 * k], run.device[3 * k + 1], run.device[3 * k + 2]);
      const c = run.engaged[k] ? ENGAGED : FREE;
      colours.push(c.r, c.g, c.b);
    }
    const path = new THREE.BufferGeometry();
    path.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
    path.setAttribute("color", new THREE.Float32BufferAttribute(colours, 3));
    this.path = new THREE.Line(path, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.scene.add(this.path);
    // One object per tool the run held; showTick shows the one held then.
    this.tools = tools.map((tool) => this.toolObject(tool));
    this.tool = new THREE.Group();
    for (const object of this.tools) this.tool.add(object);
    this.scene.add(this.tool);
    this.contacts = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ color: 0x10a050, size: 6, sizeAttenuation: false })
    );
    this.scene.add(this.contacts);
  }

  toolObject(tool) {
    const material = new THREE.MeshStandardMaterial({
      color: 0x8899aa,
      transparent: true,
      opacity: 0.45,
      depthWrite: false,
      roughness: 0.3,
    });
    if (tool && tool.type === "sphere") {
      return new THREE.Mesh(new THREE.SphereGeometry(tool.radius, 40, 20), material);
    }
    if (tool && tool.mesh) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.BufferAttribute(tool.mesh.positions, 3));
      geometry.setAttribute("normal", new THREE.BufferAttribute(tool.mesh.normals, 3));
      geometry.setIndex(new THREE.BufferAttribute(tool.mesh.indices, 1));
      material.side = THREE.DoubleSide;
      return new THREE.Mesh(geometry, material);
    }
    // A point tool: a marker a hundredth of the scene across.
    material.opacity = 0.9;
    return new THREE.Mesh(new THREE.SphereGeometry(this.size / 200, 16, 8), material);
  }

  /// Puts the tool at tick k's proxy with the device's orientation, and the
  /// contacts of that tick.
  showTick(k, contacts) {
    const run = this.data.run;
    if (!run || k < 0) return;
    this.tools.forEach((object, i) => (object.visible = i === run.tool[k]));
    this.tool.position.set(run.proxy[3 * k], run.proxy[3 * k + 1], run.proxy[3 * k + 2]);
    const q = run.orientation;
    this.tool.quaternion.set(q[4 * k + 1], q[4 * k + 2], q[4 * k + 3], q[4 * k]);
    this.contacts.geometry.setAttribute("position", new THREE.BufferAttribute(contacts, 3));
  }

  setVisible(what, visible) {
    if (this[what]) this[what].visible = visible;
  }

  resize() {
    const el = this.renderer.domElement.parentElement;
    const w = el.clientWidth || 800, h = el.clientHeight || 600;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  /// A three-quarter view of the models from above, or of `box` (a
  /// THREE.Box3) from where the eye is now.
  fit(box = null) {
    const target = box || this.box;
    const centre = target.getCenter(new THREE.Vector3());
    const size = Math.max(target.getSize(new THREE.Vector3()).length(), this.size * 1e-4);
    const dir = box
      ? this.camera.position.clone().sub(this.controls.target).normalize()
      : new THREE.Vector3(0.55, -0.75, 0.65).normalize();
    const distance = (0.55 * size) / Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.camera.position.copy(centre).addScaledVector(dir, distance);
    this.camera.near = distance / 1000;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
  }

  /// The eye on the outward side of `point`, along `normal`, a third of the
  /// models' size away, looking at it.
  lookAt(point, normal) {
    const target = new THREE.Vector3(...point);
    const n = new THREE.Vector3(...normal).normalize();
    this.camera.position.copy(target).addScaledVector(n, this.size / 3);
    this.controls.target.copy(target);
    this.controls.update();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }

  /// Pixel (CSS, from the canvas's top left) of a world point.
  project(p) {
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(this.camera);
    const rect = this.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  /// The first surface under the pixel (client coordinates): its face, the
  /// triangle's vertices and barycentric weights, the point, or null.
  hit(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1
    );
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    const hits = ray.intersectObjects(this.meshes.filter((m) => m.visible), false);
    if (!hits.length) return null;
    const h = hits[0];
    const pos = h.object.geometry.getAttribute("position");
    const corner = (i) => new THREE.Vector3().fromBufferAttribute(pos, i);
    const { a, b, c } = h.face;
    const weights = new THREE.Vector3();
    new THREE.Triangle(corner(a), corner(b), corner(c)).getBarycoord(h.point, weights);
    return { face: h.object.userData.face, triangle: h.faceIndex, vertices: [a, b, c], weights, point: h.point };
  }
}
