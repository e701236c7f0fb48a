// The path's speed (m/s) and turn rate (deg/s) over time, drawn under the keyframe table from
// the poses of /api/design/path (differences of consecutive poses), with the server's limits
// (1.5 m/s, 120 deg/s) as dashed lines. Each curve has its own scale, written at its axis.
const kSpeedLimit = 1.5, kTurnLimit = 120;

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
  const dpr = window.devicePixelRatio || 1;
  const w = canvas.clientWidth, h = canvas.clientHeight;
  canvas.width = Math.round(w * dpr);
  canvas.height = Math.round(h * dpr);
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, w, h);
  const m = poses && poses.length > 1 ? motion(poses) : [];
  if (m.length === 0) return;
  const t_max = m[m.length - 1].t_s || 1;
  const pad = 4, x = (t) => 40 + (w - 80) * t / t_max;
  const series = [
    { key: 'speed', limit: kSpeedLimit, colour: '#2060e0', unit: 'm/s', side: 'left' },
    { key: 'turn', limit: kTurnLimit, colour: '#208040', unit: '°/s', side: 'right' },
  ];
  ctx.font = '10px system-ui, sans-serif';
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
