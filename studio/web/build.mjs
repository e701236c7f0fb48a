// Bundles the studio's page (app/) into one folder the server serves: index.html, studio.css
// and studio.js (app/main.js with three.js, bundled by esbuild). Run by the CMake build
// (src/studio/CMakeLists.txt) as `node build.mjs --out DIR`. Without node_modules (npm ci not
// run) it says so, removes DIR's index.html and exits 0: the server then serves unbuilt/.
import { copyFileSync, existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const at = process.argv.indexOf('--out');
if (at < 0 || !process.argv[at + 1]) {
  console.error('usage: node build.mjs --out DIR');
  process.exit(2);
}
const out = process.argv[at + 1];
mkdirSync(out, { recursive: true });

if (!existsSync(join(here, 'node_modules', 'esbuild')) ||
    !existsSync(join(here, 'node_modules', 'three'))) {
  rmSync(join(out, 'index.html'), { force: true });
  console.log('studio: studio/web/node_modules is missing (run scripts/setup.sh, or npm ci in ' +
              'studio/web): the page is not bundled and the studio serves a page saying so');
  process.exit(0);
}

const esbuild = await import('esbuild');
const result = await esbuild.build({
  entryPoints: [join(here, 'app', 'main.js')],
  bundle: true,
  format: 'esm',
  target: 'es2020',
  minify: true,
  sourcemap: false,
  legalComments: 'linked',
  outfile: join(out, 'studio.js'),
  logLevel: 'warning',
  metafile: true,
});
// copy only what changed, so the build stays quiet when nothing did
for (const name of ['index.html', 'studio.css']) {
  const src = join(here, 'app', name);
  const dst = join(out, name);
  if (!existsSync(dst) || !readFileSync(src).equals(readFileSync(dst))) copyFileSync(src, dst);
}
const bytes = Object.values(result.metafile.outputs).reduce((n, o) => n + o.bytes, 0);
writeFileSync(join(out, 'bundle.json'), JSON.stringify({ bytes, three: JSON.parse(
  readFileSync(join(here, 'node_modules', 'three', 'package.json'))).version }) + '\n');
console.log(`studio: bundled the page into ${out} (${(bytes / 1024).toFixed(0)} KiB)`);
