// Trajectory design: the keyframes ({t, position, look_at}, world Z up, metres), their table,
// and the path the server makes through them (POST /api/design/path: the spline, the free-space
// check and the speed limits). Every change asks for the path again; an answer to an older
// request is dropped. #path-info's data-state says "ready" (with data-version) when the path
// shown is the latest.
import { postJson } from './api.js';

const round = (v, d = 2) => Math.round(v * 10 ** d) / 10 ** d;

export class Design {
  constructor({ table, info, warnings, settings, onPath }) {
    Object.assign(this, { table, info, warnings, settings, onPath });
    this.keyframes = [];
    this.result = null;
    this.version = 0;
  }

  /// A keyframe standing at (x, y) (the keyframe height above the floor), looking at (lx, ly)
  /// at the same height, or along the way from the keyframe before (+x for the first).
  add(xy, look_xy) {
    const s = this.settings();
    const z = s.floor_z + s.height;
    const prev = this.keyframes[this.keyframes.length - 1];
    let look = look_xy;
    if (!look) {
      let dx = 1, dy = 0;
      if (prev) {
        dx = xy[0] - prev.position[0];
        dy = xy[1] - prev.position[1];
      }
      const n = Math.hypot(dx, dy) || 1;
      look = [xy[0] + dx / n, xy[1] + dy / n];
    }
    let t = 0;
    if (prev) {
      const d = Math.hypot(xy[0] - prev.position[0], xy[1] - prev.position[1]);
      t = round(prev.t + Math.max(0.5, d / s.speed), 1);
    }
    this.keyframes.push({ t, position: [round(xy[0]), round(xy[1]), round(z)],
      look_at: [round(look[0]), round(look[1]), round(z)] });
    this.changed();
  }

  /// Keyframes from a trajectory's poses (t_ns, position, quaternion_xyzw): one every
  /// `every_s` seconds and the last, each looking 1 m along its camera's z axis.
  fromPoses(poses, every_s = 1) {
    const slot = (p) => Math.floor(p.t_ns * 1e-9 / every_s);
    const picked = poses.filter((p, i) => i === 0 || i === poses.length - 1 ||
      slot(p) > slot(poses[i - 1]));
    this.keyframes = picked.map((p) => {
      const [x, y, z, w] = p.quaternion_xyzw;
      // the third column of the rotation matrix: the camera's z axis in the world
      const f = [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)];
      return { t: round(p.t_ns * 1e-9, 3), position: p.position.map((v) => round(v)),
        look_at: p.position.map((v, k) => round(v + f[k])) };
    }).filter((k, i, all) => i === 0 || k.t > all[i - 1].t);
    this.changed();
  }

  /// Moves keyframe i to (x, y) (its height kept; it keeps looking the same way) and/or aims it
  /// at (lx, ly) (at its own height).
  move(i, xy, look_xy) {
    const k = this.keyframes[i];
    if (xy) {
      const dx = round(xy[0]) - k.position[0], dy = round(xy[1]) - k.position[1];
      k.position = [k.position[0] + dx, k.position[1] + dy, k.position[2]].map((v) => round(v));
      k.look_at = [k.look_at[0] + dx, k.look_at[1] + dy, k.look_at[2]].map((v) => round(v));
    }
    if (look_xy) k.look_at = [round(look_xy[0]), round(look_xy[1]), k.position[2]];
    this.changed();
  }

  remove(i) {
    this.keyframes.splice(i, 1);
    this.changed();
  }

  clear() {
    this.keyframes = [];
    this.changed();
  }

  /// The request the design routes take.
  request() {
    return { keyframes: this.keyframes, fps: this.settings().fps };
  }

  changed() {
    this.renderTable();
    this.update();
  }

  async update() {
    const version = ++this.version;
    this.info.dataset.state = 'computing';
    if (this.keyframes.length === 0) {
      this.result = null;
      this.info.textContent = 'no path yet';
      this.info.dataset.state = 'empty';
      this.showWarnings([]);
      this.onPath(null);
      return;
    }
    try {
      const r = await postJson('/api/design/path', this.request());
      if (version !== this.version) return;
      this.result = r;
      this.info.textContent = `${r.frames} poses at ${r.fps} fps over ${r.duration_s.toFixed(2)} s; ` +
        `up to ${r.max_speed_mps.toFixed(2)} m/s and ${r.max_turn_rate_dps.toFixed(0)} deg/s ` +
        `(${r.compute_ms} ms)`;
      this.showWarnings(r.warnings);
      this.onPath(r);
      this.info.dataset.state = 'ready';
    } catch (err) {
      if (version !== this.version) return;
      this.result = null;
      this.info.textContent = err.message;
      this.info.dataset.state = 'error';
      this.showWarnings([]);
      this.onPath(null);
    }
    this.info.dataset.version = String(version);
    this.renderTable();
  }

  showWarnings(list) {
    this.warnings.replaceChildren(...list.map((w) => {
      const li = document.createElement('li');
      li.textContent = w.message;
      li.dataset.kind = w.kind;
      if (w.index !== undefined) li.dataset.index = String(w.index);
      return li;
    }));
  }

  /// One row per keyframe: editable time, position and look-at; a row whose keyframe is not
  /// in the free space is marked.
  renderTable() {
    const body = this.table.tBodies[0];
    const free = this.result ? this.result.keyframes.map((k) => k.free) : [];
    body.replaceChildren(...this.keyframes.map((k, i) => {
      const tr = document.createElement('tr');
      if (free[i] === false) tr.className = 'warn';
      tr.insertCell().textContent = String(i + 1);
      const field = (get, set) => {
        const input = document.createElement('input');
        input.type = 'number';
        input.step = 'any';
        input.value = String(get());
        input.addEventListener('change', () => {
          const v = Number(input.value);
          if (!Number.isFinite(v)) return;
          set(v);
          this.changed();
        });
        tr.insertCell().appendChild(input);
      };
      field(() => k.t, (v) => { k.t = v; });
      for (const key of ['position', 'look_at'])
        for (let a = 0; a < 3; a++) field(() => k[key][a], (v) => { k[key][a] = v; });
      const del = document.createElement('button');
      del.type = 'button';
      del.textContent = '×';
      del.title = 'remove this keyframe';
      del.addEventListener('click', () => this.remove(i));
      tr.insertCell().appendChild(del);
      return tr;
    }));
  }
}
