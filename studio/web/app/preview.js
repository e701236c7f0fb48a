// The frame preview: a slider over the path's poses and a pass; the server renders that frame
// (POST /api/preview/frame: ground truth at once, the colour at a few samples per pixel,
// through the sequence's lens and camera response) and the image appears beside the slider.
// At most 320 pixels wide (fx scaled with the image; a fisheye's stays square, a panorama's 2:1);
// a newer request wins over one still on its way. #frame-img's data-state says "ready" with
// data-version when the image shown is the latest.
import { post } from './api.js';

export class FramePreview {
  constructor({ slider, pass, img, info, camera }) {
    Object.assign(this, { slider, pass, img, info, camera });
    this.poses = [];
    this.version = 0;
    this.timer = null;
    slider.addEventListener('input', () => this.schedule());
    pass.addEventListener('change', () => this.schedule());
  }

  setPoses(poses) {
    this.poses = poses || [];
    this.slider.max = String(Math.max(0, this.poses.length - 1));
    if (Number(this.slider.value) > this.poses.length - 1) this.slider.value = '0';
    this.schedule();
  }

  schedule() {
    clearTimeout(this.timer);
    this.timer = setTimeout(() => this.update(), 120);
  }

  async update() {
    const version = ++this.version;
    const i = Number(this.slider.value);
    const pose = this.poses[i];
    if (!pose) {
      this.img.removeAttribute('src');
      this.info.textContent = '';
      return;
    }
    const c = this.camera();
    const s = Math.min(1, 320 / c.width);
    const width = Math.max(16, Math.round(c.width * s));
    // scaled, a fisheye's or panorama's image keeps its shape (the server checks it)
    const shape = { fisheye: 1, panorama: 2 }[c.keys.lens];
    const height = shape && c.width === shape * c.height ? Math.round(width / shape)
      : Math.max(16, Math.round(c.height * s));
    const request = { position: pose.position, quaternion_xyzw: pose.quaternion_xyzw,
      width, height, fx: c.fx * s, spp: Math.min(16, c.spp), pass: this.pass.value, ...c.keys };
    this.img.dataset.state = 'loading';
    const t0 = performance.now();
    try {
      const blob = await (await post('/api/preview/frame', request)).blob();
      if (version !== this.version) return;
      const old = this.img.src;
      this.img.src = URL.createObjectURL(blob);
      await this.img.decode();
      if (old) URL.revokeObjectURL(old);
      this.info.textContent = `frame ${i + 1} of ${this.poses.length}, t = ` +
        `${(pose.t_ns * 1e-9).toFixed(2)} s, ${request.pass} ${request.width} x ` +
        `${request.height}, ${request.lens} in ${(performance.now() - t0).toFixed(0)} ms`;
      this.img.dataset.state = 'ready';
    } catch (err) {
      if (version !== this.version) return;
      this.info.textContent = err.message;
      this.img.dataset.state = 'error';
    }
    this.img.dataset.version = String(version);
  }
}
