// sylva-three's tests and measures in headless Chromium (Debian's, driven by playwright-core).
//
//   node test/run.mjs --glb FOREST.glb [--out DIR] [--modes runtime,babylon-sylva,babylon,full,im2,batched]
//                     [--eyes edge,above] [--loads 10] [--budget 3000000] [--timeout 400]
//                     [--roles [--foliage-tolerance 2]]
//
// For every mode and eye it opens a page in a fresh headless Chromium (software GL), waits
// for its first frame and ten more, and prints one JSON line: triangles and draw calls a
// frame (three.js's renderer.info, Babylon's counters), time to first frame, frame time, and
// the browser's peak memory (the resident memory of all its processes, sampled every 250
// ms); a screenshot of each goes to DIR. `runtime` is three.js with SylvaForest,
// `babylon-sylva` Babylon.js with sylva-three/babylon, `babylon` Babylon.js with its own glTF
// loader and default settings, `full` three.js's GLTFLoader alone (every tree at full
// detail), `im2` and `batched` the designs sylva-three was weighed against
// (test/alternatives.js). With --roles the pictures are flat by role and the foliage seen
// with levels is held within --foliage-tolerance points of full detail's. Then it loads the
// runtime page `--loads` times in a row. It fails when a page errs, crashes or times out,
// and when either engine with sylva-three draws more than `--budget` triangles a frame from
// any eye (Babylon.js's loader alone reads MSFT_lod only to load the levels one after
// another, ending at full detail, so its rows are measured, not held to the budget). A
// crash is a failure: no page is asked twice.
import { createServer } from 'node:http';
import { createReadStream, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { eyes as eyesOf, readGlb } from './glb.js';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '..');

function option(name, fallback) {
  const k = process.argv.indexOf(`--${name}`);
  return k > 0 && process.argv[k + 1] !== undefined ? process.argv[k + 1] : fallback;
}
const glbPath = resolve(option('glb', join(root, '..', 'target', 'ci', 'forest.glb')));
const out = resolve(option('out', join(root, '..', 'target', 'ci', 'web')));
const modes = option('modes', 'runtime,babylon').split(',');
const eyeNames = option('eyes', 'edge,above').split(',');
const loads = Number(option('loads', '10'));
const budget = Number(option('budget', '3000000'));
const timeout = 1000 * Number(option('timeout', '400'));
// With --roles, pictures are drawn flat by role and full detail and levels compared: the
// foliage seen (leaves over the ground in the picture) may differ by at most this, in points.
const roles = process.argv.includes('--roles');
const foliageTolerance = Number(option('foliage-tolerance', '2'));
mkdirSync(out, { recursive: true });

// A static server on loopback: the package's folder, and the forest at /forest.glb.
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json', '.glb': 'model/gltf-binary', '.png': 'image/png', '.wasm': 'application/wasm' };
const server = createServer((req, res) => {
  const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  const file = path === '/forest.glb' ? glbPath : join(root, path);
  if (!file.startsWith(root) && file !== glbPath) { res.writeHead(403).end(); return; }
  if (!existsSync(file) || !statSync(file).isFile()) { res.writeHead(404).end(); return; }
  res.writeHead(200, { 'content-type': types[extname(file)] || 'application/octet-stream', 'content-length': statSync(file).size });
  createReadStream(file).pipe(res);
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const base = `http://127.0.0.1:${server.address().port}`;

// The browser process: the one whose command line names `profile`, and whose parent does not.
function browserPid(profile) {
  const named = new Map();
  for (const entry of readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    try {
      if (!readFileSync(`/proc/${entry}/cmdline`, 'utf8').includes(profile)) continue;
      const stat = readFileSync(`/proc/${entry}/stat`, 'utf8');
      named.set(Number(entry), Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]));
    } catch { /* gone */ }
  }
  for (const [pid, ppid] of named) if (!named.has(ppid)) return pid;
  return null;
}

// The resident memory of a process and all its descendants, in MB.
function treeRssMb(pid) {
  if (pid === null) return 0;
  const children = new Map();
  const rss = new Map();
  for (const entry of readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    try {
      const stat = readFileSync(`/proc/${entry}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      const ppid = Number(fields[1]);
      if (!children.has(ppid)) children.set(ppid, []);
      children.get(ppid).push(Number(entry));
      rss.set(Number(entry), Number(fields[21]) * 4096);
    } catch { /* gone */ }
  }
  let total = 0;
  const stack = [pid];
  while (stack.length) {
    const p = stack.pop();
    total += rss.get(p) || 0;
    stack.push(...(children.get(p) || []));
  }
  return total / 1e6;
}

// Kills a process and all its descendants.
function killTree(pid) {
  if (pid === null) return;
  const children = new Map();
  for (const entry of readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    try {
      const stat = readFileSync(`/proc/${entry}/stat`, 'utf8');
      const ppid = Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]);
      if (!children.has(ppid)) children.set(ppid, []);
      children.get(ppid).push(Number(entry));
    } catch { /* gone */ }
  }
  const stack = [pid];
  while (stack.length) {
    const p = stack.pop();
    try { process.kill(p, 'SIGKILL'); } catch { /* gone */ }
    stack.push(...(children.get(p) || []));
  }
}

const launchArgs = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
  '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update',
  '--disable-sync', '--no-sandbox'];

async function measure(mode, eyeName, eye, shot, frames = 5) {
  const profile = mkdtempSync(join(tmpdir(), 'sylva-three-'));
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: launchArgs,
    headless: true,
    viewport: { width: 1920, height: 1080 },
  });
  const pid = browserPid(profile);
  let peak = 0;
  const sampler = setInterval(() => { peak = Math.max(peak, treeRssMb(pid)); }, 250);
  const page = browser.pages()[0] || await browser.newPage();
  let crashed = null;
  page.on('crash', () => { crashed = 'the page crashed'; });
  page.on('pageerror', (e) => { crashed = crashed || `page error: ${e.message}`; });
  if (process.env.SYLVA_WEB_VERBOSE) page.on('console', (m) => console.error(`  [${mode} ${eyeName}] ${m.text()}`));
  const path = mode.startsWith('babylon') ? 'test/babylon.html' : 'example/index.html';
  const url = `${base}/${path}?file=/forest.glb&mode=${mode}${mode === 'babylon-sylva' ? '&sylva=1' : ''}&check=1&frames=${frames}&eye=${eye}${roles ? '&roles=1' : ''}${process.env.SYLVA_WEB_QUERY || ''}`;
  const started = Date.now();
  let result;
  try {
    await page.goto(url);
    await page.waitForFunction(() => window.sylvaResult !== undefined, null, { timeout, polling: 500 });
    result = await page.evaluate(() => window.sylvaResult);
    if (shot) await page.screenshot({ path: shot });
  } catch (e) {
    result = { error: crashed || String(e.message || e).split('\n')[0] };
  }
  clearInterval(sampler);
  peak = Math.max(peak, treeRssMb(pid));
  // A browser stuck in a frame it cannot finish does not close when asked: it is killed.
  const closed = await Promise.race([browser.close().then(() => true), new Promise((ok) => setTimeout(() => ok(false), 15000))]);
  if (!closed) killTree(pid);
  rmSync(profile, { recursive: true, force: true });
  // The page's own `eye` (where it stood) is kept as `at`; `eye` names the eye.
  const { eye: at, ...rest } = result;
  return { mode, eye: eyeName, at, ...rest, wall_s: (Date.now() - started) / 1000, peak_mb: Math.round(peak) };
}

const eyes = eyesOf(readGlb(glbPath));
let failures = 0;
const rows = [];
for (const mode of modes) {
  for (const name of eyeNames) {
    const row = await measure(mode, name, eyes[name], join(out, `${mode}_${name}${roles ? '_roles' : ''}.png`));
    rows.push(row);
    console.log(JSON.stringify(row));
    if (row.error) {
      console.error(`${mode} from ${name}: ${row.error}`);
      failures++;
    } else if ((mode === 'runtime' || mode === 'babylon-sylva') && row.triangles > budget) {
      console.error(`${mode} from ${name}: ${row.triangles} triangles a frame, over the budget of ${budget}`);
      failures++;
    }
  }
}
// Levels against full detail: the foliage each sees from the same eye.
for (const name of eyeNames) {
  if (!roles || !modes.includes('runtime') || !modes.includes('full')) break;
  const [levels, full] = ['runtime', 'full'].map((m) => rows.find((r) => r.mode === m && r.eye === name && r.coverage));
  if (!levels || !full) {
    console.error(`foliage from ${name}: no picture of ${levels ? 'full detail' : 'the levels'} to compare`);
    failures++;
    continue;
  }
  const difference = levels.coverage.foliage - full.coverage.foliage;
  console.log(`foliage from ${name}: ${levels.coverage.foliage.toFixed(1)}% with levels, ${full.coverage.foliage.toFixed(1)}% at full detail (${difference >= 0 ? '+' : ''}${difference.toFixed(1)} points)`);
  if (Math.abs(difference) > foliageTolerance) {
    console.error(`foliage from ${name} differs by more than ${foliageTolerance} points`);
    failures++;
  }
}
// Loads in a row, each in a fresh browser to its first frame, none retried.
let failedLoads = 0;
for (let k = 0; k < loads; k++) {
  const row = await measure('runtime', 'edge', eyes.edge, null, 0);
  if (row.error || !(row.triangles > 0)) {
    console.error(`load ${k + 1} of ${loads}: ${row.error || 'nothing drawn'}`);
    failedLoads++;
  }
}
failures += failedLoads;
if (loads > 0) console.log(`${loads} loads in a row of the runtime page: ${loads - failedLoads} drew their first frame`);
server.close();
if (failures) {
  console.error(`${failures} failures`);
  process.exit(1);
}
