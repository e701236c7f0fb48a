// The studio's page (issue 18): the layout in 3D (three.js) and as a floor plan, keyframed
// camera paths checked against the free space, export, sequence jobs and random trajectories.
// Everything it knows comes from the JSON API (docs/studio.md). window.studio exposes the
// pieces to the browser tests (studio/web/tests/).
import { getJson, post, postJson } from './api.js';
import { Design } from './design.js';
import { PlanView } from './plan.js';
import { drawImu, drawMotion } from './plot.js';
import { FramePreview } from './preview.js';
import { View3D } from './view3d.js';

const $ = (id) => document.getElementById(id);
const num = (id) => Number($(id).value);
const t0 = performance.now();

function setStatus(text, state) {
  $('status').textContent = text;
  $('status').dataset.state = state;
}

// a double click in 3D adds a keyframe above the point hit, as a click on the plan does, and
// dragging a keyframe's marker moves or aims it, as on the plan
const view = new View3D($('view3d'), (x, y) => design.add([x, y], null),
  (i, xy, look) => design.move(i, xy, look));
let plan = null;
const design = new Design({
  table: $('keyframes'), info: $('path-info'), warnings: $('warnings'),
  settings: () => ({ fps: num('fps'), height: num('kf-height'), speed: num('speed'),
    floor_z: plan ? plan.floor_z : 0 }),
  onPath: (r) => {
    const free = r ? r.keyframes.map((k) => k.free) : [];
    const bad = r ? badPoses(r) : [];
    planView.setDesign(design.keyframes, free, r ? r.poses : [], bad);
    view.setDesign(design.keyframes, free, r ? r.poses : [], bad);
    drawMotion($('plot'), r ? r.poses : []);
    frame.setPoses(r ? r.poses : []);
    updateImu(r);
  },
});
// the frame preview renders through the sequence's lens and camera response
const frame = new FramePreview({ slider: $('frame-slider'), pass: $('frame-pass'),
  img: $('frame-img'), info: $('frame-info'),
  camera: () => ({ fx: num('fx'), width: num('width'), height: num('height'), spp: num('spp'),
    keys: { ...lensRequest(), ...responseRequest() } }) });
const planView = new PlanView($('plan'), (xy, look) => design.add(xy, look),
  (i, xy, look) => design.move(i, xy, look));

let imuVersion = 0;
/// The IMU plot for path result r (a newer path wins over an older request).
async function updateImu(r) {
  const version = ++imuVersion;
  const el = $('imu-plot');
  el.dataset.state = 'loading';
  let imu = null;
  if (r && r.frames >= 2) {
    try {
      imu = await postJson('/api/design/imu', { ...design.request(), imu_rate: 100,
        noise: $('imu-noise').value });
    } catch (err) {
      imu = null;
    }
  }
  if (version !== imuVersion) return;
  drawImu(el, imu);
  el.dataset.state = imu ? 'ready' : 'empty';
}

/// Poses inside a warned stretch of the path.
function badPoses(r) {
  const bad = new Array(r.poses.length).fill(false);
  for (const w of r.warnings) {
    if (w.kind !== 'path') continue;
    r.poses.forEach((p, i) => {
      const t = p.t_ns * 1e-9;
      if (t >= w.from_s - 1e-9 && t <= w.to_s + 1e-9) bad[i] = true;
    });
  }
  return bad;
}

async function download(format) {
  if (design.keyframes.length === 0) return showJob('place keyframes first', 'failed');
  try {
    const res = await post('/api/design/export', { ...design.request(), format });
    const name = (res.headers.get('Content-Disposition') || '').match(/filename="([^"]+)"/);
    const a = document.createElement('a');
    a.href = URL.createObjectURL(await res.blob());
    a.download = name ? name[1] : `trajectory_${format}.txt`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  } catch (err) {
    showJob(err.message, 'failed');
  }
}

function showJob(text, state) {
  $('job').textContent = text;
  $('job').dataset.state = state;
}

const finished = (s) => s.state !== 'pending' && s.state !== 'running';

/// Follows a job until it has finished: its progress streamed (GET .../events, server-sent
/// events), or polled when the stream is refused or breaks. Resolves with the final status.
function follow(job, onStatus) {
  return new Promise((resolve, reject) => {
    const poll = async () => {
      try {
        for (;;) {
          const s = await getJson(job.status_url);
          if (finished(s)) return resolve(s);
          onStatus(s);
          await new Promise((r) => setTimeout(r, 300));
        }
      } catch (err) {
        reject(err);
      }
    };
    if (!window.EventSource) return poll();
    const events = new EventSource(`${job.status_url}/events`);
    events.onmessage = (e) => {
      const s = JSON.parse(e.data);
      if (!finished(s)) return onStatus(s);
      events.close();
      resolve(s);
    };
    events.onerror = () => {
      events.close();
      poll();
    };
  });
}

/// The lens keys of the camera panel (studio/camera_keys.h): a lens's own settings only for
/// the lens that uses them; the distortion when a coefficient is not 0 (k3 only when it is
/// not), for any lens, so that the server's one-line error says which lenses take it.
function lensRequest() {
  const lens = $('lens').value;
  const request = { lens };
  if (lens === 'thin_lens') Object.assign(request, { aperture_m: num('aperture'),
    focus_m: num('focus') });
  if (lens === 'fisheye') request.fisheye_fov_deg = num('fisheye-fov');
  const d = ['k1', 'k2', 'p1', 'p2', 'k3'].map(num);
  if (d.some((v) => v !== 0)) request.distortion = d[4] !== 0 ? d : d.slice(0, 4);
  return request;
}

/// The camera response keys of the camera panel (studio/camera_keys.h).
function responseRequest() {
  return { exposure: $('auto-exposure').value, exposure_ev: num('exposure-ev'),
    tone: $('tone').value, sensor_noise: $('sensor-noise').checked };
}

/// The sensors of the camera panel: the IMU's noise, and the event camera with its pass and
/// settings when it is on (generate's flags as keys; the server refuses them without it).
function sensorsRequest() {
  const request = { imu_noise: $('imu-noise').value };
  if (!$('events-on').checked) return request;
  return { ...request, passes: 'default,events', event_width: num('event-width'),
    event_height: num('event-height'), event_spp: num('event-spp'),
    contrast_pos: num('contrast-pos'), contrast_neg: num('contrast-neg'),
    contrast_sigma: num('contrast-sigma'), threshold_spread: num('threshold-spread'),
    refractory_ms: num('refractory'), leak_rate_hz: num('leak-rate'),
    shot_noise_rate_hz: num('shot-noise-rate') };
}

async function generate() {
  if (design.keyframes.length === 0) return showJob('place keyframes first', 'failed');
  const request = { ...design.request(), fx: num('fx'), width: num('width'),
    height: num('height'), spp: num('spp'), ...lensRequest(), ...responseRequest(),
    stereo: num('stereo'),
    exposure_ms: num('exposure'), readout_ms: num('readout'), imu_rate: num('imu-rate'),
    ...sensorsRequest(), config: $('config').value, formats: $('formats').value };
  showJob('starting…', 'pending');
  try {
    const job = await postJson('/api/jobs/sequence', request);
    showJob(`job ${job.id}: pending`, 'pending');
    $('cancel').disabled = false;
    $('job-sheet').hidden = true;
    $('cancel').onclick = () => fetch(job.status_url, { method: 'DELETE' });
    const s = await follow(job, (st) => {
      $('job-progress').value = st.progress;
      showJob(`job ${job.id}: ${st.state}, ${st.message}`, st.state);
    });
    $('job-progress').value = s.progress;
    $('cancel').disabled = true;
    if (s.state === 'cancelled') return showJob(`job ${job.id}: ${s.message}`, 'cancelled');
    if (s.state === 'failed') return showJob(`failed: ${s.error.error}`, 'failed');
    const r = s.result;
    const dirs = r.sequences.map((q) => q.dir).join(', ');
    // the contact sheet the job wrote below --out, which the studio serves as "out"
    if (r.contact_sheet) {  // made from the asl format's frames
      $('job-sheet').hidden = false;
      $('job-sheet').src = `/api/files/out/${r.contact_sheet}`;
    }
    showJob(`done: ${r.frames} frames in ${dirs} (${r.files} files, ` +
      `${(r.setup_s + r.render_s).toFixed(1)} s)`, 'done');
  } catch (err) {
    showJob(err.message, 'failed');
  }
}

let lastRandom = null;  // the random trajectory last previewed

async function randomPreview() {
  const out = $('random-info');
  out.textContent = 'computing…';
  try {
    const t = await postJson('/api/trajectory/preview', {
      type: $('random-type').value, frames: 250, fps: num('fps'), seed: num('random-seed'),
      v_mult: num('random-v'), w_mult: num('random-w'), style: $('random-style').value });
    lastRandom = t;
    $('random-keys').disabled = false;
    out.textContent = `${t.poses.length} poses (${t.type}, v_mult ${t.v_mult.toFixed(2)}, ` +
      `w_mult ${t.w_mult.toFixed(2)}) in ${t.compute_ms} ms: playing`;
    await view.play(t.poses, num('fx'), num('height'));
    out.textContent += ', done';
  } catch (err) {
    out.textContent = err.message;
  }
}

function wire() {
  $('export-tum').addEventListener('click', () => download('tum'));
  $('export-euroc').addEventListener('click', () => download('euroc'));
  $('export-other').addEventListener('click', () => download($('export-format').value));
  $('generate').addEventListener('click', generate);
  $('random').addEventListener('click', randomPreview);
  $('clear').addEventListener('click', () => design.clear());
  $('random-keys').addEventListener('click', () => {
    if (lastRandom) design.fromPoses(lastRandom.poses);
  });
  $('play').addEventListener('click', () => {
    if (design.result) view.play(design.result.poses, num('fx'), num('height'));
  });
  $('fps').addEventListener('change', () => design.update());
  $('imu-noise').addEventListener('change', () => updateImu(design.result));
  // the event camera's settings show when it is on
  $('events-on').addEventListener('change', () => {
    $('event-settings').hidden = !$('events-on').checked;
  });
  // any camera setting changes the frame preview
  for (const type of ['input', 'change']) $('camera').addEventListener(type, () => frame.schedule());
}

let layoutInfo = null;  // GET /api/layout

/// Where the 3D view cuts a storey of plan p: 2.4 m over its floor (a mesh scene's ceilings and
/// roofs are not labelled, so they are not hidden), or 0.3 m under the next level's floor.
function storeyCut(p) {
  const above = p.levels[p.level + 1];
  return Math.min(p.floor_z + 2.4, above === undefined ? Infinity : above - 0.3);
}

/// Shows floor level `level` (GET /api/layout/plan?level=N): its plan and its rooms, new
/// keyframes on its floor, and the 3D view cut above it (storeyCut).
async function showLevel(level) {
  const p = await getJson(`/api/layout/plan?level=${level}`);
  plan = p;
  planView.setPlan(p, layoutInfo.rooms.filter((r) => p.rooms.includes(r.id)));
  view.setCutAbove(storeyCut(p));
  design.update();  // the plan's markers and path again
}

async function start() {
  wire();
  try {
    const [layout, p] = await Promise.all([getJson('/api/layout'), getJson('/api/layout/plan')]);
    layoutInfo = layout;
    plan = p;
    $('layout-name').textContent = `${layout.name} (${layout.source}, ${layout.rooms.length} rooms)`;
    planView.setPlan(p, layout.rooms.filter((r) => p.rooms.includes(r.id)));
    if (p.levels.length > 1) {  // a storey at a time
      const metres = (z) => (Math.abs(z) < 0.005 ? 0 : z).toFixed(2);  // no "-0.00"
      $('level').replaceChildren(...p.levels.map((z, i) => new Option(`${i} (${metres(z)} m)`, i)));
      $('level-box').hidden = false;
      $('level').addEventListener('change', () => showLevel(Number($('level').value)));
    }
    setStatus('loading the 3D view…', 'loading');
    // the 3D view frames what the plan shows (the rooms, not the ground around them)
    const lo = [p.origin[0] - p.cell_m / 2, p.origin[1] - p.cell_m / 2, p.floor_z];
    const hi = [lo[0] + p.nx * p.cell_m, lo[1] + p.ny * p.cell_m, p.floor_z + 2.5];
    const glb = await view.load('/api/layout.glb', lo, hi);
    if (p.levels.length > 1) view.setCutAbove(storeyCut(p));
    window.studio.load_ms = performance.now() - t0;
    window.studio.glb_ms = glb.ms;
    setStatus(`ready (${(window.studio.load_ms / 1000).toFixed(2)} s)`, 'ready');
  } catch (err) {
    setStatus(err.message, 'error');
  }
}

window.studio = { view, planView, design, measureOrbit: (ms, moving) => view.measureOrbit(ms, moving) };
start();
