// The floor plan (a 2D canvas): the free-space raster of GET /api/layout/plan, the rooms'
// outlines and names, the keyframes (numbered, with a line to where each looks) and the path
// (red where it leaves the free space). A click adds a keyframe; a drag adds one standing
// where the drag starts and looking where it ends. World x right, y up (our Z-up world seen
// from above).
const kColours = { o: [221, 221, 221], '#': [51, 51, 51], f: [201, 165, 122],
  b: [255, 224, 138], '.': [255, 255, 255] };

export class PlanView {
  /// onPlace(position_xy, look_xy or null) is called for each click or drag on free ground;
  /// onMove(index, position_xy or null, look_xy or null) when a keyframe's marker is dragged
  /// (moved; with Shift held, aimed at where the drag ends).
  constructor(canvas, onPlace, onMove = () => {}) {
    this.canvas = canvas;
    this.onPlace = onPlace;
    this.onMove = onMove;
    this.keyframes = [];
    this.free = [];
    this.poses = [];
    this.bad = [];
    this.drag = null;
    new ResizeObserver(() => this.draw()).observe(canvas);
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.move(e));
    canvas.addEventListener('pointerup', (e) => this.up(e));
  }

  setPlan(plan, rooms) {
    this.plan = plan;
    this.rooms = rooms || [];
    const img = document.createElement('canvas');
    img.width = plan.nx;
    img.height = plan.ny;
    const ctx = img.getContext('2d');
    const data = ctx.createImageData(plan.nx, plan.ny);
    for (let j = 0; j < plan.ny; j++) {
      const row = plan.rows[j], tops = plan.tops[j];
      const y = plan.ny - 1 - j;  // row 0 is the lowest y: the bottom of the image
      for (let i = 0; i < plan.nx; i++) {
        let c = kColours[row[i]] || kColours.o;
        if (row[i] === 'f') {  // furniture: the taller, the darker
          const k = tops.charCodeAt(i) - 97;
          c = c.map((v) => Math.round(v * (1.15 - 0.5 * Math.min(k, 22) / 22)));
        }
        data.data.set([...c, 255], 4 * (y * plan.nx + i));
      }
    }
    ctx.putImageData(data, 0, 0);
    this.image = img;
    this.draw();
  }

  setDesign(keyframes, free, poses, bad) {
    Object.assign(this, { keyframes, free, poses: poses || [], bad: bad || [] });
    this.draw();
  }

  /// Canvas pixels per metre and the offset, fitting the raster with a margin.
  transform() {
    const p = this.plan;
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    const span_x = p.nx * p.cell_m, span_y = p.ny * p.cell_m;
    const s = Math.min((w - 20) / span_x, (h - 20) / span_y);
    const x0 = p.origin[0] - p.cell_m / 2, y0 = p.origin[1] - p.cell_m / 2;
    const ox = (w - s * span_x) / 2, oy = (h - s * span_y) / 2;
    return {
      s,
      toCanvas: (x, y) => [ox + (x - x0) * s, h - oy - (y - y0) * s],
      toWorld: (u, v) => [x0 + (u - ox) / s, y0 + (h - oy - v) / s],
      rect: [ox, oy, s * span_x, s * span_y],
    };
  }

  /// The canvas position (CSS pixels) of world point (x, y): what a test clicks.
  canvasPoint(x, y) {
    return this.transform().toCanvas(x, y);
  }

  eventWorld(e) {
    const r = this.canvas.getBoundingClientRect();
    return this.transform().toWorld(e.clientX - r.left, e.clientY - r.top);
  }

  /// The keyframe whose marker is under canvas point (u, v), or -1.
  markerAt(u, v) {
    const t = this.transform();
    for (let i = this.keyframes.length - 1; i >= 0; i--) {
      const [ku, kv] = t.toCanvas(this.keyframes[i].position[0], this.keyframes[i].position[1]);
      if (Math.hypot(ku - u, kv - v) <= 8) return i;
    }
    return -1;
  }

  down(e) {
    if (!this.plan || e.button !== 0) return;
    this.canvas.setPointerCapture(e.pointerId);
    const r = this.canvas.getBoundingClientRect();
    this.drag = { from: this.eventWorld(e), to: null, px: [e.clientX, e.clientY],
      marker: this.markerAt(e.clientX - r.left, e.clientY - r.top), aim: e.shiftKey };
  }

  move(e) {
    if (!this.drag) return;
    if (Math.hypot(e.clientX - this.drag.px[0], e.clientY - this.drag.px[1]) > 6)
      this.drag.to = this.eventWorld(e);
    this.draw();
  }

  up(e) {
    if (!this.drag) return;
    const { from, to, marker, aim } = this.drag;
    this.drag = null;
    if (marker < 0) return this.onPlace(from, to);
    if (to) this.onMove(marker, aim ? null : to, aim ? to : null);
    else this.draw();  // a click on a marker changes nothing
  }

  draw() {
    const c = this.canvas, ctx = c.getContext('2d');
    const dpr = window.devicePixelRatio || 1;
    c.width = Math.round(c.clientWidth * dpr);
    c.height = Math.round(c.clientHeight * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, c.clientWidth, c.clientHeight);
    if (!this.plan) return;
    const t = this.transform();
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(this.image, ...t.rect);
    ctx.font = '11px system-ui, sans-serif';
    for (const room of this.rooms) {
      ctx.strokeStyle = '#4a6fa5';
      ctx.lineWidth = 1;
      ctx.beginPath();
      room.outline.forEach(([x, y], i) => ctx[i ? 'lineTo' : 'moveTo'](...t.toCanvas(x, y)));
      ctx.closePath();
      ctx.stroke();
      const cx = room.outline.reduce((a, p) => a + p[0], 0) / room.outline.length;
      const cy = room.outline.reduce((a, p) => a + p[1], 0) / room.outline.length;
      ctx.fillStyle = '#4a6fa5';
      ctx.fillText(room.type.replace(/_/g, ' '), ...t.toCanvas(cx, cy));
    }
    this.drawPath(ctx, t);
    this.keyframes.forEach((k, i) => this.drawKeyframe(ctx, t, k.position, k.look_at, i,
      this.free[i] !== false));
    const d = this.drag;
    if (d && d.to && d.marker < 0)
      this.drawKeyframe(ctx, t, d.from, d.to, this.keyframes.length, true);
    if (d && d.to && d.marker >= 0) {  // where the marker goes, or where it will look
      const k = this.keyframes[d.marker];
      if (d.aim) this.drawKeyframe(ctx, t, k.position, d.to, d.marker, true);
      else this.drawKeyframe(ctx, t, d.to, k.look_at, d.marker, true);
    }
  }

  drawPath(ctx, t) {
    ctx.lineWidth = 2;
    for (let i = 1; i < this.poses.length; i++) {
      ctx.strokeStyle = this.bad[i] || this.bad[i - 1] ? '#e02020' : '#2060e0';
      ctx.beginPath();
      ctx.moveTo(...t.toCanvas(...this.poses[i - 1].position));
      ctx.lineTo(...t.toCanvas(...this.poses[i].position));
      ctx.stroke();
    }
  }

  drawKeyframe(ctx, t, p, look, i, ok) {
    const [u, v] = t.toCanvas(p[0], p[1]);
    const [lu, lv] = t.toCanvas(look[0], look[1]);
    ctx.strokeStyle = '#208040';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(u, v);
    ctx.lineTo(lu, lv);
    ctx.stroke();
    ctx.fillStyle = ok ? '#2060e0' : '#e02020';
    ctx.beginPath();
    ctx.arc(u, v, 7, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = '#fff';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(String(i + 1), u, v);
    ctx.textAlign = 'start';
    ctx.textBaseline = 'alphabetic';
  }
}
