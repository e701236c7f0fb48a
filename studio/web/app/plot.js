// The path's speed (m/s) and turn rate (deg/s) over time, drawn under the keyframe table from
// the poses of /api/design/path (differences of consecutive poses), with the server's limits
// (1.5 m/s, 120 deg/s) as dashed lines. Each curve has its own scale, written at its axis.
const kSpeedLimit = 1.5, kTurnLimit = 120;

/// Sizes the canvas for the device's pixels and clears it; the 2D context in CSS pixels.
function prepare(canvas) {
  const dpr = window.devicePixelRatio || 1;
  canvas.width = Math.round(canvas.clientWidth * dpr);
  canvas.height = Math.round(canvas.clientHeight * dpr);
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, canvas.clientWidth, canvas.clientHeight);
  ctx.font = '10px system-ui, sans-serif';
  return ctx;
}

/// [{t_s, speed, turn}] between consecutive poses.
export function motion(poses) {
  const out = [];
  for (let i = 1; i < poses.length; i++) {
    const a = poses[i - 1], b = poses[i];
    const dt = (b.t_ns - a.t_ns) * 1e-9;
    const d = Math.hypot(...b.position.map((v, k) => v - a.position[k]));
    const dot = Math.abs(a.quaternion_xyzw.reduce((s, v, k) => s + v * b.quaternion_xyzw[k], 0));
    const angle = 2 * Math.acos(Math.min(1, dot)) * 180 / Math.PI;
    out.push({ t_s: b.t_ns * 1e-9, speed: d / dt, turn: angle / dt });
  }
  return out;
}

export function drawMotion(canvas, poses) {
  const ctx = prepare(canvas);
  const w = canvas.clientWidth, h = canvas.clientHeight;
  const m = poses && poses.length > 1 ? motion(poses) : [];
  if (m.length === 0) return;
  const t_max = m[m.length - 1].t_s || 1;
  const pad = 4, x = (t) => 40 + (w - 80) * t / t_max;
  const series = [
    { key: 'speed', limit: kSpeedLimit, colour: '#2060e0', unit: 'm/s', side: 'left' },
    { key: 'turn', limit: kTurnLimit, colour: '#208040', unit: '°/s', side: 'right' },
  ];
  for (const s of series) {
    const top = Math.max(s.limit * 1.2, ...m.map((p) => p[s.key]));
    const y = (v) => h - pad - (h - 2 * pad) * v / top;
    ctx.strokeStyle = s.colour;
    ctx.setLineDash([4, 3]);
    ctx.beginPath();
    ctx.moveTo(x(0), y(s.limit));
    ctx.lineTo(x(t_max), y(s.limit));
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    m.forEach((p, i) => ctx[i ? 'lineTo' : 'moveTo'](x(p.t_s), y(p[s.key])));
    ctx.stroke();
    ctx.fillStyle = s.colour;
    ctx.textAlign = s.side === 'left' ? 'left' : 'right';
    ctx.fillText(`${top.toFixed(top < 10 ? 1 : 0)} ${s.unit}`, s.side === 'left' ? 2 : w - 2, 12);
  }
  ctx.fillStyle = '#666';
  ctx.textAlign = 'right';
  ctx.fillText(`${t_max.toFixed(1)} s`, w - 2, h - 2);
}

/// The IMU along the path (POST /api/design/imu: camera frame, gravity included): the
/// accelerometer's x, y, z (m/s^2) above, the gyroscope's (rad/s) below, red, green, blue.
export function drawImu(canvas, imu) {
  const ctx = prepare(canvas);
  const w = canvas.clientWidth, h = canvas.clientHeight;
  const s = imu ? imu.samples : [];
  if (s.length < 2) return;
  const t_max = s[s.length - 1].t_ns * 1e-9 || 1;
  const x = (t) => 40 + (w - 50) * t / t_max;
  const colours = ['#d03030', '#20a040', '#3050d0'];
  [['accel', 'm/s²'], ['gyro', 'rad/s']].forEach(([key, unit], pane) => {
    const top = pane * h / 2 + 3, height = h / 2 - 6;
    const span = Math.max(1e-6, ...s.map((m) => Math.max(...m[key].map(Math.abs))));
    const y = (v) => top + height / 2 - (height / 2) * v / span;
    ctx.strokeStyle = '#ccc';
    ctx.beginPath();
    ctx.moveTo(x(0), y(0));
    ctx.lineTo(x(t_max), y(0));
    ctx.stroke();
    for (let a = 0; a < 3; a++) {
      ctx.strokeStyle = colours[a];
      ctx.beginPath();
      s.forEach((m, i) => ctx[i ? 'lineTo' : 'moveTo'](x(m.t_ns * 1e-9), y(m[key][a])));
      ctx.stroke();
    }
    ctx.fillStyle = '#444';
    ctx.textAlign = 'left';
    ctx.fillText(`${key} ±${span.toFixed(span < 10 ? 1 : 0)} ${unit}`, 2, top + 10);
  });
}
