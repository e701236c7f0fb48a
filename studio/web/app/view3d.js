// The 3D view: the layout as our glTF export (GET /api/layout.glb) with orbit navigation
// (OrbitControls), walking (W A S D / arrows move the eye and the orbit centre together), the
// designed path and keyframes, keyframes added by a double click on the floor and dragged by
// their markers (level, at their own height; with Shift held, aimed), and playback of the path
// as its camera sees it.
//
// Frames: the glTF's root node turns our Z-up world into three.js's Y-up one; `world` below
// does the same, so the path and keyframes are given in our coordinates. A pose T_world_camera
// (OpenCV camera: x right, y down, z forward) becomes a three.js camera (y up, looking along -z)
// as  R_x(-90 deg) * T_world_camera * diag(1, -1, -1).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { mergeGeometries } from 'three/addons/utils/BufferGeometryUtils.js';
import { MeshoptSimplifier } from 'meshoptimizer';

const kOpenCvToGl = new THREE.Matrix4().makeScale(1, -1, -1);
const kZupToYup = new THREE.Matrix4().makeRotationX(-Math.PI / 2);
const kCoarseError = 0.05;  ///< metres: how far the coarse copy may stray (buildCoarse)
const kGrabPx = 12;  ///< CSS pixels: how close to a keyframe's marker a press grabs it

/// The visible meshes of `root` merged into one mesh per material, in world coordinates: a
/// 10-room apartment has some 850 meshes, and each draw call costs (most of all in software
/// GL). The view neither picks nor animates single objects, so nothing is lost.
function mergeByMaterial(root) {
  root.updateMatrixWorld(true);
  const groups = new Map();
  root.traverseVisible((o) => {
    if (!o.isMesh) return;
    const g = o.geometry.clone();  // indexed stays indexed: shared vertices are shaded once
    for (const name of Object.keys(g.attributes))
      if (!['position', 'normal', 'uv'].includes(name)) g.deleteAttribute(name);
    g.applyMatrix4(o.matrixWorld);
    const key = `${o.material.uuid}/${Object.keys(g.attributes).sort().join(',')}/${!!g.index}`;
    if (!groups.has(key)) groups.set(key, { material: o.material, geometries: [] });
    groups.get(key).geometries.push(g);
  });
  const merged = new THREE.Group();
  for (const { material, geometries } of groups.values()) {
    const g = mergeGeometries(geometries);
    for (const part of geometries) part.dispose();
    if (g) merged.add(new THREE.Mesh(g, material));
  }
  return merged;
}

export class View3D {
  /// onPick(x, y) is called with the world point a double click hits (our coordinates);
  /// onMove(index, position_xy or null, look_xy or null) when a keyframe's marker is dragged
  /// (moved; with Shift held, aimed at where the drag ends), as the plan's onMove.
  constructor(container, onPick = () => {}, onMove = () => {}) {
    this.onPick = onPick;
    this.onMove = onMove;
    this.markers = [];  // the keyframes' balls, in the order of the keyframes
    this.drag = null;
    this.container = container;
    // no MSAA: software GL (SwiftShader, headless Chromium) pays for every sample
    this.renderer = new THREE.WebGLRenderer({ antialias: false });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xcfd6de);
    this.camera = new THREE.PerspectiveCamera(60, 1, 0.05, 500);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.requestRender());
    // while the view moves it draws the coarse copy (buildCoarse), once it stops the full one
    this.controls.addEventListener('start', () => this.setMoving(true));
    this.controls.addEventListener('end', () => this.setMoving(false));
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.2);
    sun.position.set(3, 10, 4);
    this.scene.add(sun);
    this.world = new THREE.Group();  // our Z-up coordinates
    this.world.rotation.x = -Math.PI / 2;
    this.scene.add(this.world);
    this.overlay = new THREE.Group();
    this.world.add(this.overlay);
    this.pending = false;
    this.playing = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.installWalkKeys();
    this.renderer.domElement.addEventListener('dblclick', (e) => this.pick(e));
    this.installMarkerDrag();
  }

  /// Dragging a keyframe's marker: a press within kGrabPx of one (the nearest) takes the
  /// pointer before OrbitControls sees it (a capturing listener on the container), the marker
  /// follows the pointer on the level plane at the keyframe's height, and the release moves the
  /// keyframe there (onMove), or with Shift held aims it there.
  installMarkerDrag() {
    const el = this.renderer.domElement;
    const local = (e) => {
      const r = el.getBoundingClientRect();
      return [e.clientX - r.left, e.clientY - r.top];
    };
    this.container.addEventListener('pointerdown', (e) => {
      if (e.button !== 0 || this.playing) return;
      const i = this.markerAt(...local(e));
      if (i < 0) return;
      e.stopPropagation();
      e.preventDefault();
      el.setPointerCapture(e.pointerId);
      this.controls.enabled = false;
      const ball = this.markers[i];
      this.drag = { index: i, from: ball.position.clone(), to: null };
    }, { capture: true });
    el.addEventListener('pointermove', (e) => {
      if (!this.drag) {
        el.style.cursor = this.markerAt(...local(e)) >= 0 ? 'grab' : '';
        return;
      }
      const p = this.levelPoint(...local(e), this.drag.from.z);
      if (!p) return;
      this.drag.to = p;
      if (!e.shiftKey) this.markers[this.drag.index].position.set(p[0], p[1], this.drag.from.z);
      this.requestRender();
    });
    const end = (e) => {
      const d = this.drag;
      if (!d) return;
      this.drag = null;
      this.controls.enabled = true;
      if (el.hasPointerCapture(e.pointerId)) el.releasePointerCapture(e.pointerId);
      if (!d.to) return;
      if (e.shiftKey) this.onMove(d.index, null, d.to);
      else this.onMove(d.index, d.to, null);
    };
    el.addEventListener('pointerup', end);
    el.addEventListener('pointercancel', end);
  }

  /// The index of the keyframe marker nearest to view point (u, v) (CSS pixels) within
  /// kGrabPx and in front of the camera, else -1.
  markerAt(u, v) {
    let best = -1, best_d = kGrabPx;
    this.markers.forEach((ball, i) => {
      const p = ball.position;
      const v3 = new THREE.Vector3(p.x, p.z, -p.y).project(this.camera);
      if (v3.z > 1) return;  // behind the camera
      const [su, sv] = this.screenPoint([p.x, p.y, p.z]);
      const d = Math.hypot(su - u, sv - v);
      if (d < best_d) { best_d = d; best = i; }
    });
    return best;
  }

  /// Where the view ray through (u, v) (CSS pixels) meets the level plane at height z (our
  /// coordinates): [x, y], or null when it does not (looking away from it).
  levelPoint(u, v, z) {
    const r = this.renderer.domElement.getBoundingClientRect();
    const ray = new THREE.Raycaster();
    ray.setFromCamera(new THREE.Vector2(u / r.width * 2 - 1, -(v / r.height) * 2 + 1), this.camera);
    const hit = ray.ray.intersectPlane(new THREE.Plane(new THREE.Vector3(0, 1, 0), -z),
      new THREE.Vector3());
    return hit ? [hit.x, -hit.z] : null;
  }

  /// A double click: the first surface of the model under the pointer (floor, furniture top),
  /// in our coordinates, goes to onPick.
  pick(e) {
    if (!this.model || this.playing) return;
    const r = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1,
      -((e.clientY - r.top) / r.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    const hit = ray.intersectObject(this.model, true)[0];
    if (hit) this.onPick(hit.point.x, -hit.point.z, hit.point.y);
  }

  /// Where world point p (our coordinates) is in the view, in CSS pixels from its corner.
  screenPoint(p) {
    const v = new THREE.Vector3(p[0], p[2], -p[1]).project(this.camera);
    const r = this.renderer.domElement.getBoundingClientRect();
    return [(v.x + 1) / 2 * r.width, (1 - v.y) / 2 * r.height];
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
    });
  }

  /// Loads the layout's glTF and frames the box lo..hi (our coordinates); resolves with the
  /// load time (ms).
  async load(url, lo, hi) {
    const t0 = performance.now();
    const gltf = await new GLTFLoader().loadAsync(url);
    // our lights are photometric (KHR_lights_punctual in candela): the view lights itself
    const lights = [];
    gltf.scene.traverse((o) => { if (o.isLight) lights.push(o); });
    for (const l of lights) l.removeFromParent();
    // a doll's house: the ceilings are hidden so that the rooms are seen from above (the
    // export's node extras name each object's NYU40 class)
    gltf.scene.traverse((o) => { if (o.userData && o.userData.nyu40_name === 'ceiling') o.visible = false; });
    // Lambert rather than the export's metallic-roughness PBR: a design view needs colours and
    // shapes, and software GL (SwiftShader, headless Chromium) renders it about 3x faster
    const lambert = new Map();  // one per glTF material, so that merging can group by it
    gltf.scene.traverse((o) => {
      if (!o.isMesh) return;
      const m = o.material;
      if (!lambert.has(m.uuid)) {
        lambert.set(m.uuid, new THREE.MeshLambertMaterial({ color: m.color, map: m.map,
          emissive: m.emissive, emissiveMap: m.emissiveMap, transparent: m.transparent,
          opacity: m.opacity, side: m.side, name: m.name }));
      }
      o.material = lambert.get(m.uuid);
    });
    this.model = mergeByMaterial(gltf.scene);
    this.scene.add(this.model);
    this.coarseReady = this.buildCoarse();
    this.frameAll(lo, hi);
    await new Promise((resolve) => requestAnimationFrame(() => {
      this.renderer.render(this.scene, this.camera);
      resolve();
    }));
    return { ms: performance.now() - t0 };
  }

  /// A coarse copy of the model for moving views: each merged mesh of over 1,000 triangles
  /// simplified by meshoptimizer's sloppy simplifier (topology not kept) towards a tenth of its
  /// triangles, at most kCoarseError off (its vertices shared with the full mesh). Software GL (SwiftShader) is bound by triangles: a
  /// 10-room apartment has 475,000. Built after the first frame, one mesh per task.
  async buildCoarse() {
    await MeshoptSimplifier.ready;
    const coarse = new THREE.Group();
    for (const mesh of this.model.children) {
      const g = mesh.geometry;
      let c = g;
      if (g.index && g.index.count > 3000) {
        const indices = g.index.array instanceof Uint32Array ? g.index.array : Uint32Array.from(g.index.array);
        const target = Math.floor(indices.length / 30) * 3;
        const [simple] = MeshoptSimplifier.simplifySloppy(indices, g.attributes.position.array, 3,
          null, target, kCoarseError / MeshoptSimplifier.getScale(g.attributes.position.array, 3));
        c = new THREE.BufferGeometry();
        for (const [name, attr] of Object.entries(g.attributes)) c.setAttribute(name, attr);
        c.setIndex(new THREE.BufferAttribute(simple, 1));
        await new Promise((resolve) => setTimeout(resolve, 0));
      }
      coarse.add(new THREE.Mesh(c, mesh.material));
    }
    coarse.visible = false;
    this.scene.add(coarse);
    this.coarse = coarse;
    let triangles = 0;
    coarse.traverse((o) => { if (o.isMesh) triangles += o.geometry.index ? o.geometry.index.count / 3 : 0; });
    return { triangles };
  }

  /// Cuts away everything above height z (our coordinates; null: nothing), so that a storey
  /// is seen from above with the ones over it removed.
  setCutAbove(z) {
    this.renderer.clippingPlanes = z === null ? [] : [new THREE.Plane(new THREE.Vector3(0, -1, 0), z)];
    this.requestRender();
  }

  /// Draws the coarse copy (moving) or the full model.
  setMoving(moving) {
    if (!this.coarse || !this.model) return;
    this.coarse.visible = moving;
    this.model.visible = !moving;
    this.requestRender();
  }

  /// Puts the orbit centre in the middle of the box lo..hi (our coordinates; default: the whole
  /// model) and the eye above one corner.
  frameAll(lo, hi) {
    const box = lo ? new THREE.Box3(new THREE.Vector3(lo[0], lo[2], -hi[1]),
      new THREE.Vector3(hi[0], hi[2], -lo[1])) : new THREE.Box3().setFromObject(this.model);
    const centre = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3());
    const r = Math.max(size.x, size.z) * 0.75 + 1;
    this.controls.target.copy(centre);
    this.camera.position.set(centre.x + r * 0.4, centre.y + r, centre.z + r * 0.7);
    this.controls.update();
    this.requestRender();
  }

  /// The path (poses of /api/design/path; `bad[i]` marks poses outside the free space) and
  /// the keyframes ({position, look_at}, `free` per keyframe).
  setDesign(keyframes, free, poses, bad) {
    this.overlay.clear();
    if (poses && poses.length > 1) {
      const points = poses.map((p) => new THREE.Vector3(...p.position));
      const colors = [];
      for (let i = 0; i < poses.length; i++) colors.push(...(bad[i] ? [0.9, 0.1, 0.1] : [0.1, 0.3, 0.9]));
      const g = new THREE.BufferGeometry().setFromPoints(points);
      g.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
      this.overlay.add(new THREE.Line(g, new THREE.LineBasicMaterial({ vertexColors: true })));
    }
    this.markers = [];
    keyframes.forEach((k, i) => {
      const ok = free[i] !== false;
      // drawn over the model, so that a keyframe behind a wall can still be seen and dragged
      const ball = new THREE.Mesh(new THREE.SphereGeometry(0.08, 16, 8),
        new THREE.MeshBasicMaterial({ color: ok ? 0x2060e0 : 0xe02020, depthTest: false }));
      ball.renderOrder = 1;
      ball.position.set(...k.position);
      this.overlay.add(ball);
      this.markers.push(ball);
      const look = new THREE.BufferGeometry().setFromPoints(
        [new THREE.Vector3(...k.position), new THREE.Vector3(...k.look_at)]);
      this.overlay.add(new THREE.Line(look, new THREE.LineBasicMaterial({ color: 0x208040 })));
    });
    this.requestRender();
  }

  /// Shows the camera of pose p ({position, quaternion_xyzw}) with focal length fx for an
  /// image `height` pixels tall.
  showPose(p, fx, height) {
    const [x, y, z, w] = p.quaternion_xyzw;
    const T = new THREE.Matrix4().compose(new THREE.Vector3(...p.position),
      new THREE.Quaternion(x, y, z, w), new THREE.Vector3(1, 1, 1));
    const m = kZupToYup.clone().multiply(T).multiply(kOpenCvToGl);
    m.decompose(this.camera.position, this.camera.quaternion, new THREE.Vector3());
    this.camera.fov = 2 * Math.atan(height / 2 / fx) * 180 / Math.PI;
    this.camera.updateProjectionMatrix();
    this.renderer.render(this.scene, this.camera);
  }

  /// Plays the poses at their own times; resolves when done (or stopped by another play()).
  play(poses, fx, height) {
    this.stop();
    const saved = { position: this.camera.position.clone(), fov: this.camera.fov };
    this.controls.enabled = false;
    this.overlay.visible = false;
    return new Promise((resolve) => {
      const t0 = performance.now();
      const run = { resolve, saved };
      this.playing = run;
      const step = () => {
        if (this.playing !== run) return;
        const t_ns = (performance.now() - t0) * 1e6;
        let i = poses.findIndex((p) => p.t_ns > t_ns);
        if (i < 0) return this.stop();
        this.showPose(poses[Math.max(0, i - 1)], fx, height);
        requestAnimationFrame(step);
      };
      step();
    });
  }

  stop() {
    const run = this.playing;
    if (!run) return;
    this.playing = null;
    this.camera.position.copy(run.saved.position);
    this.camera.fov = run.saved.fov;
    this.camera.updateProjectionMatrix();
    this.controls.enabled = true;
    this.overlay.visible = true;
    this.controls.update();
    this.requestRender();
    run.resolve();
  }

  /// W A S D or the arrows walk: the eye and the orbit centre move together, level, along the
  /// view direction (0.1 m a press).
  installWalkKeys() {
    const el = this.renderer.domElement;
    el.tabIndex = 0;
    el.addEventListener('keydown', (e) => {
      const step = { KeyW: [0, 1], ArrowUp: [0, 1], KeyS: [0, -1], ArrowDown: [0, -1],
        KeyA: [-1, 0], ArrowLeft: [-1, 0], KeyD: [1, 0], ArrowRight: [1, 0] }[e.code];
      if (!step) return;
      e.preventDefault();
      const forward = new THREE.Vector3();
      this.camera.getWorldDirection(forward);
      forward.y = 0;
      if (forward.lengthSq() < 1e-9) return;
      forward.normalize();
      const right = new THREE.Vector3().crossVectors(forward, this.camera.up).normalize();
      const move = forward.multiplyScalar(step[1] * 0.1).add(right.multiplyScalar(step[0] * 0.1));
      this.camera.position.add(move);
      this.controls.target.add(move);
      this.controls.update();
    });
  }

  /// Orbits for `ms` milliseconds, rendering every animation frame, as a drag does (the coarse
  /// copy when `moving`, else the full model); resolves with the frames drawn and the frame rate
  /// (what the browser's own frame timing allowed).
  measureOrbit(ms, moving = true) {
    this.setMoving(moving);
    return new Promise((resolve) => {
      const t0 = performance.now();
      const gaps = [];
      let last = t0;
      const step = (now) => {
        gaps.push(now - last);
        last = now;
        this.controls.rotateLeft(0.02);
        this.controls.update();
        this.renderer.render(this.scene, this.camera);
        if (now - t0 < ms) return requestAnimationFrame(step);
        this.setMoving(false);
        gaps.shift();
        gaps.sort((a, b) => a - b);
        const total = now - t0;
        resolve({ frames: gaps.length, ms: total, fps: gaps.length / (total / 1000),
          median_frame_ms: gaps[Math.floor(gaps.length / 2)],
          p95_frame_ms: gaps[Math.floor(gaps.length * 0.95)] });
      };
      requestAnimationFrame(step);
    });
  }
}
