// Shared by the studio's browser tests: skipping when the browser or the npm packages are
// missing (exit 77, ctest's SKIP_RETURN_CODE), starting `interiornet studio` on a free port,
// launching Debian's chromium headless through playwright-core, and reading trajectories.
import { spawn } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const kSkip = 77;
const here = dirname(fileURLToPath(import.meta.url));
export const chromiumPath = process.env.INET_CHROMIUM || '/usr/bin/chromium';

/// Exits 77 with a message when chromium or playwright-core is absent.
export function skipUnlessBrowser() {
  if (!existsSync(chromiumPath)) {
    console.log(`SKIP: no chromium at ${chromiumPath} (scripts/setup.sh installs Debian's ` +
                'chromium; INET_CHROMIUM names another)');
    process.exit(kSkip);
  }
  if (!existsSync(join(here, '..', 'node_modules', 'playwright-core'))) {
    console.log('SKIP: studio/web/node_modules is missing (scripts/setup.sh runs npm ci there)');
    process.exit(kSkip);
  }
}

/// --name value pairs of the command line.
export function options(defaults) {
  const out = { ...defaults };
  const argv = process.argv.slice(2);
  for (let i = 0; i < argv.length; i += 2) {
    if (!argv[i].startsWith('--') || argv[i + 1] === undefined) throw new Error(`bad argument ${argv[i]}`);
    out[argv[i].slice(2)] = argv[i + 1];
  }
  return out;
}

/// Starts the studio; resolves with {url (the base), open_url (with ?token=), token, proc,
/// stop(), started_ms (until the URL was printed)}.
export function startStudio(binary, args) {
  return new Promise((resolve, reject) => {
    const t0 = Date.now();
    const proc = spawn(binary, ['studio', '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '', err = '';
    const timer = setTimeout(() => { proc.kill('SIGTERM'); reject(new Error(`no URL after 120 s:\n${out}\n${err}`)); }, 120000);
    proc.stderr.on('data', (d) => { err += d; });
    proc.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/serving (https?:\/\/127\.0\.0\.1:\d+\/)(\?token=([\w-]+))? /);
      if (!m) return;
      clearTimeout(timer);
      resolve({ url: m[1], open_url: m[1] + (m[2] || ''), token: m[3] || '', proc, started_ms: Date.now() - t0, stderr: () => err,
        stop: () => new Promise((done) => { proc.once('exit', (code) => done(code)); proc.kill('SIGTERM'); }) });
    });
    proc.on('exit', (code) => { clearTimeout(timer); reject(new Error(`studio exited ${code}:\n${out}\n${err}`)); });
  });
}

export async function launch() {
  const { chromium } = await import('playwright-core');
  // SwiftShader is Chromium's software WebGL: the machine has no GPU
  return chromium.launch({ executablePath: chromiumPath, headless: true,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
}

/// Poses of a TUM or EuRoC file as [{t_ns, p: [x, y, z], q: [x, y, z, w]}], w >= 0.
export function readPoses(path) {
  const poses = [];
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    if (!line.trim() || line.startsWith('#')) continue;
    const euroc = line.includes(',');
    const f = line.split(euroc ? ',' : /\s+/).map(Number);
    const t_ns = euroc ? f[0] : Math.round(f[0] * 1e9);
    let q = euroc ? [f[5], f[6], f[7], f[4]] : [f[4], f[5], f[6], f[7]];
    if (q[3] < 0) q = q.map((v) => -v);
    poses.push({ t_ns, p: f.slice(1, 4), q });
  }
  return poses;
}

/// The largest difference between two pose lists' positions and quaternions (and whether the
/// times agree to 1 us); the first `n` poses.
export function poseDifference(a, b, n) {
  let d = 0, times = true;
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) d = Math.max(d, Math.abs(a[i].p[k] - b[i].p[k]));
    for (let k = 0; k < 4; k++) d = Math.max(d, Math.abs(a[i].q[k] - b[i].q[k]));
    if (Math.abs(a[i].t_ns - b[i].t_ns) > 1000) times = false;
  }
  return { max: d, times };
}

/// Runs a command; resolves with its exit code and output.
export function run(cmd, args) {
  return new Promise((resolve) => {
    const p = spawn(cmd, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    p.stdout.on('data', (d) => { out += d; });
    p.stderr.on('data', (d) => { out += d; });
    p.on('exit', (code) => resolve({ code, out }));
  });
}
