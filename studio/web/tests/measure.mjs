// The figures of docs/studio.md for a layout (default: procedural:11, a 10-room apartment):
// the studio's start (layout, free space, plan), the page's load until the 3D view has drawn
// the layout, the glTF's size, and the orbit frame rate in headless chromium (requestAnimation-
// Frame timing while the view orbits and redraws every frame), with the coarse copy a moving
// view draws and with the full model.
//   node measure.mjs --binary build/apps/interiornet [--layout procedural:11] [--orbit-ms 5000]
//     [--screenshot FILE] [--viewport 1400x900]
import { launch, options, skipUnlessBrowser, startStudio } from './lib.mjs';

skipUnlessBrowser();
const opt = options({ binary: '', layout: 'procedural:11', 'orbit-ms': '5000', screenshot: '',
  viewport: '1400x900' });
const [vw, vh] = opt.viewport.split('x').map(Number);
const studio = await startStudio(opt.binary, ['--layout', opt.layout]);
const browser = await launch();
try {
  const health = await (await fetch(`${studio.url}api/layout`,
    { headers: { Authorization: `Bearer ${studio.token}` } })).json();
  const page = await browser.newPage({ viewport: { width: vw, height: vh } });
  const t0 = Date.now();
  await page.goto(studio.open_url);
  await page.waitForSelector('#status[data-state=ready], #status[data-state=error]', { timeout: 120000 });
  const load_ms = Date.now() - t0;
  const inPage = await page.evaluate(() => ({ load_ms: window.studio.load_ms, glb_ms: window.studio.glb_ms }));
  const glb = await page.evaluate(() => fetch('/api/layout.glb').then((r) => r.arrayBuffer()).then((b) => b.byteLength));
  const stats = await page.evaluate(() => {
    let meshes = 0, triangles = 0;
    window.studio.view.model.traverse((o) => {
      if (o.isMesh) { meshes++; triangles += (o.geometry.index ? o.geometry.index.count : o.geometry.attributes.position.count) / 3; }
    });
    const c = window.studio.view.renderer.domElement;
    return { meshes, triangles, canvas: [c.width, c.height] };
  });
  const coarse = await page.evaluate(() => window.studio.view.coarseReady);
  const coarse_ms = Date.now() - t0 - load_ms;
  const orbit = await page.evaluate((ms) => window.studio.measureOrbit(ms, true), Number(opt['orbit-ms']));
  const orbit_full = await page.evaluate((ms) => window.studio.measureOrbit(ms, false), Number(opt['orbit-ms']));
  if (opt.screenshot) await page.screenshot({ path: opt.screenshot });
  console.log(JSON.stringify({ layout: opt.layout, rooms: health.rooms.length,
    layout_load_s: health.load_s, studio_start_ms: studio.started_ms, page_load_ms: load_ms,
    page: inPage, glb_bytes: glb, ...stats, coarse: { ...coarse, ready_after_ms: coarse_ms },
    orbit_moving: orbit, orbit_full }, null, 1));
} finally {
  await browser.close();
  await studio.stop();
}
