#!/usr/bin/env node
// Browser end-to-end test of the shatter web build.
//
//   node e2e.mjs [screenshot.png]
//
// Serves the static site (web/dist, or $SHATTER_WEB_DIST) on 127.0.0.1,
// opens it in headless Chromium (/usr/bin/chromium, software WebGL2 via
// SwiftShader) and checks the app's console contract:
//   0. every file has a .gz and a .br copy that decodes to it, served with
//      Content-Encoding when the browser accepts it (the summary's sizes and
//      served_encodings);
//   1. a `SHATTER_STATE {json}` line with frames > 0 (first frame rendered), then
//      one with fragments > 0 (the scene, opened after the first frame);
//   2. after Enter on the focused canvas: running == true;
//   3. after left clicks on the wall (~640,380): bonds_broken > 0 (screenshot
//      <screenshot>-wall.png);
//   4. "Add mesh…" takes a good OBJ and refuses a broken one;
//   5. index.html?scene=textured draws the textured example (textured_materials >= 2)
//      and its balls break it after Enter (screenshot <screenshot>-textured.png).
// Prints a summary JSON; exits 0 only if every step held, else 1.
//
// Environment (all optional):
//   SHATTER_WEB_DIST            site folder (default: <this folder>/dist)
//   SHATTER_E2E_SCREENSHOT      screenshot path (the first argument wins)
//   SHATTER_CHROMIUM            browser binary (default /usr/bin/chromium)
//   SHATTER_E2E_FIRST_FRAME_S   timeout for the first frame   (default 300)
//   SHATTER_E2E_RUNNING_S       timeout for running == true   (default 60)
//   SHATTER_E2E_BROKEN_S        timeout for bonds_broken > 0  (default 120)
//   SHATTER_E2E_TOTAL_S         hard limit for the whole run  (default 900)
//   SHATTER_E2E_CLICK_X/_Y      click point in canvas px      (default 640,380)
//   SHATTER_E2E_HEADFUL=1       show the browser window (debugging)

import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const DIST = path.resolve(process.env.SHATTER_WEB_DIST || path.join(HERE, 'dist'));
const SCREENSHOT = path.resolve(
  process.argv[2] || process.env.SHATTER_E2E_SCREENSHOT || path.join(HERE, 'e2e-screenshot.png'),
);
const CHROMIUM = process.env.SHATTER_CHROMIUM || '/usr/bin/chromium';
const num = (name, dflt) => {
  const v = Number(process.env[name]);
  return Number.isFinite(v) && v > 0 ? v : dflt;
};
const FIRST_FRAME_MS = num('SHATTER_E2E_FIRST_FRAME_S', 300) * 1000;
const RUNNING_MS = num('SHATTER_E2E_RUNNING_S', 60) * 1000;
const BROKEN_MS = num('SHATTER_E2E_BROKEN_S', 120) * 1000;
const TOTAL_MS = num('SHATTER_E2E_TOTAL_S', 900) * 1000;
const CLICK_X = num('SHATTER_E2E_CLICK_X', 640);
const CLICK_Y = num('SHATTER_E2E_CLICK_Y', 380);
const VIEWPORT = { width: 1280, height: 720 };

// Flags for headless Chromium in a container without a GPU. WebGL2 then runs
// on SwiftShader (CPU Vulkan) through ANGLE; --enable-unsafe-swiftshader keeps
// Chromium from refusing that software fallback for WebGL (newer versions
// deprecate the automatic fallback). See README.md.
const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--use-gl=angle',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  // Keep rAF/timers running at full speed even if the page is not "visible".
  '--disable-background-timer-throttling',
  '--disable-renderer-backgrounding',
  '--disable-backgrounding-occluded-windows',
];

const CONTROL_FLOW = 'Using exceptions for control flow';
const MARK = 'SHATTER_STATE ';

const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
  '.gif': 'image/gif',
  '.svg': 'image/svg+xml',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
  '.ktx2': 'image/ktx2',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.ttf': 'font/ttf',
  '.otf': 'font/otf',
  '.woff': 'font/woff',
  '.woff2': 'font/woff2',
  '.ogg': 'audio/ogg',
  '.wav': 'audio/wav',
  '.ron': 'text/plain; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
};

const t0 = Date.now();
const elapsed = () => Date.now() - t0;
const log = (...a) => console.error(`[e2e +${(elapsed() / 1000).toFixed(1)}s]`, ...a);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// ---------------------------------------------------------------- state ---
const consoleLines = []; // "[type] text"
const states = []; // parsed SHATTER_STATE objects, in order
const stateTimes = []; // elapsed() when each state arrived
const pageErrors = []; // uncaught errors other than Bevy's control-flow one
const ignoredErrors = [];
const httpErrors = [];
const served = {}; // url path -> bytes sent
const encodings = {}; // url path -> Content-Encoding served
const failures = [];
const timings = {};
// The first page's first frame and scene on its own clock (window.shatterFirstFrameMs
// and shatterSceneMs, ms from its navigation start).
const firstPage = { firstFrameMs: null, sceneMs: null };
let fatal = null; // set on an uncaught page error / crash: aborts the waits
let waiters = []; // { pred, resolve } woken on every new state or fatal

function parseState(text) {
  const at = text.indexOf(MARK);
  if (at < 0) return null;
  const s = text.slice(at + MARK.length);
  const start = s.indexOf('{');
  if (start < 0) return null;
  // Take the balanced {...} object (the line may carry trailing decorations).
  let depth = 0;
  let inStr = false;
  let esc = false;
  for (let i = start; i < s.length; i++) {
    const c = s[i];
    if (inStr) {
      if (esc) esc = false;
      else if (c === '\\') esc = true;
      else if (c === '"') inStr = false;
    } else if (c === '"') inStr = true;
    else if (c === '{') depth++;
    else if (c === '}' && --depth === 0) {
      try {
        return JSON.parse(s.slice(start, i + 1));
      } catch {
        return null;
      }
    }
  }
  return null;
}

function wake() {
  const still = [];
  for (const w of waiters) {
    if (fatal) w.resolve({ fatal });
    else {
      const i = states.findIndex((s, j) => j >= w.from && w.pred(s));
      if (i >= 0) w.resolve({ state: states[i], at: stateTimes[i] });
      else still.push(w);
    }
  }
  waiters = still;
}

// Resolves with the first state (arrived at index >= from) matching pred,
// as { state, at } (at: elapsed() when that state arrived);
// rejects on timeout or a fatal page error. onTick(ms) runs every second.
function waitForState(what, pred, timeoutMs, { from = 0, onTick } = {}) {
  return new Promise((resolve, reject) => {
    const started = Date.now();
    let tick = null;
    const done = (fn, v) => {
      clearTimeout(timer);
      if (tick) clearInterval(tick);
      waiters = waiters.filter((w) => w !== waiter);
      fn(v);
    };
    const waiter = {
      pred,
      from,
      resolve: (r) =>
        r.fatal
          ? done(reject, new Error(`${what}: aborted by page error: ${r.fatal}`))
          : done(resolve, r),
    };
    const timer = setTimeout(
      () => done(reject, new Error(`${what}: not seen within ${Math.round(timeoutMs / 1000)} s`)),
      timeoutMs,
    );
    if (onTick) {
      tick = setInterval(() => {
        Promise.resolve(onTick(Date.now() - started)).catch((e) => log('tick error:', e.message));
      }, 1000);
    }
    waiters.push(waiter);
    wake();
  });
}

// --------------------------------------------------------------- server ---
function startServer(root) {
  const server = http.createServer((req, res) => {
    let urlPath;
    try {
      urlPath = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    } catch {
      res.writeHead(400).end();
      return;
    }
    if (urlPath.endsWith('/')) urlPath += 'index.html';
    const file = path.resolve(root, '.' + urlPath);
    if (file !== root && !file.startsWith(root + path.sep)) {
      res.writeHead(403).end();
      return;
    }
    fs.stat(file, (err, st) => {
      if (err || !st.isFile()) {
        res.writeHead(404, { 'Content-Type': 'text/plain' }).end('not found');
        return;
      }
      const type = MIME[path.extname(file).toLowerCase()] || 'application/octet-stream';
      // Serve the build's precompressed copy when the browser takes it, as a static
      // server configured per web/README.md does: brotli first, then gzip.
      const accepts = String(req.headers['accept-encoding'] || '');
      let body = file;
      let size = st.size;
      const headers = { 'Content-Type': type, 'Cache-Control': 'no-store', Vary: 'Accept-Encoding' };
      for (const [enc, ext] of [['br', '.br'], ['gzip', '.gz']]) {
        if (!accepts.includes(enc)) continue;
        try {
          size = fs.statSync(file + ext).size;
          body = file + ext;
          headers['Content-Encoding'] = enc;
          break;
        } catch {
          /* no such copy */
        }
      }
      headers['Content-Length'] = size;
      res.writeHead(200, headers);
      if (req.method === 'HEAD') {
        res.end();
        return;
      }
      served[urlPath] = (served[urlPath] || 0) + size;
      if (headers['Content-Encoding']) encodings[urlPath] = headers['Content-Encoding'];
      fs.createReadStream(body).pipe(res);
    });
  });
  server.keepAliveTimeout = 1000;
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => resolve(server));
  });
}

// ---------------------------------------------------------------- sizes ---
function sizes() {
  const out = {};
  const size = (f) => {
    try {
      return fs.statSync(path.join(DIST, f)).size;
    } catch {
      return null;
    }
  };
  out.index_html_bytes = size('index.html');
  out.js_bytes = size('shatter_app.js');
  out.wasm_bytes = size('shatter_app_bg.wasm');
  // The build's precompressed copies: their sizes, and whether each one decodes to
  // exactly the file beside it (a stale or broken copy would be served to browsers).
  out.precompressed = {};
  for (const f of ['index.html', 'shatter_app.js', 'shatter_app_bg.wasm']) {
    let plain;
    try {
      plain = fs.readFileSync(path.join(DIST, f));
    } catch {
      continue;
    }
    const entry = {};
    for (const [ext, decode] of [['.gz', zlib.gunzipSync], ['.br', zlib.brotliDecompressSync]]) {
      try {
        const packed = fs.readFileSync(path.join(DIST, f + ext));
        entry[ext.slice(1) + '_bytes'] = packed.length;
        entry[ext.slice(1) + '_matches'] = Buffer.compare(decode(packed), plain) === 0;
      } catch (e) {
        entry[ext.slice(1) + '_bytes'] = null;
        entry[ext.slice(1) + '_matches'] = false;
      }
    }
    out.precompressed[f] = entry;
  }
  out.wasm_gzip_bytes = out.precompressed['shatter_app_bg.wasm']?.gz_bytes ?? null;
  out.wasm_br_bytes = out.precompressed['shatter_app_bg.wasm']?.br_bytes ?? null;
  return out;
}

// Count distinct colours in a PNG screenshot (coarse sample), to tell a
// blank page from a rendered one. Handles 8-bit RGB/RGBA, non-interlaced
// (what Chromium writes); returns null for anything else.
function pngDistinctColours(buf) {
  try {
    if (buf.readUInt32BE(0) !== 0x89504e47) return null;
    let off = 8;
    let w = 0, h = 0, ctype = 0, depth = 0, interlace = 0;
    const idat = [];
    while (off < buf.length) {
      const len = buf.readUInt32BE(off);
      const type = buf.toString('ascii', off + 4, off + 8);
      const data = buf.subarray(off + 8, off + 8 + len);
      if (type === 'IHDR') {
        w = data.readUInt32BE(0);
        h = data.readUInt32BE(4);
        depth = data[8];
        ctype = data[9];
        interlace = data[12];
      } else if (type === 'IDAT') idat.push(data);
      else if (type === 'IEND') break;
      off += 12 + len;
    }
    const bpp = ctype === 6 ? 4 : ctype === 2 ? 3 : 0;
    if (!bpp || depth !== 8 || interlace) return null;
    const raw = zlib.inflateSync(Buffer.concat(idat));
    const stride = w * bpp;
    const cur = Buffer.alloc(stride);
    const prev = Buffer.alloc(stride);
    const colours = new Set();
    for (let y = 0; y < h; y++) {
      const base = y * (stride + 1);
      const f = raw[base];
      for (let x = 0; x < stride; x++) {
        const v = raw[base + 1 + x];
        const a = x >= bpp ? cur[x - bpp] : 0;
        const b = prev[x];
        const c = x >= bpp ? prev[x - bpp] : 0;
        let p;
        switch (f) {
          case 0: p = 0; break;
          case 1: p = a; break;
          case 2: p = b; break;
          case 3: p = (a + b) >> 1; break;
          case 4: {
            const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
            p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            break;
          }
          default: return null;
        }
        cur[x] = (v + p) & 0xff;
      }
      if (y % 4 === 0) {
        for (let x = 0; x < w; x += 4) {
          const i = x * bpp;
          colours.add((cur[i] << 16) | (cur[i + 1] << 8) | cur[i + 2]);
        }
      }
      cur.copy(prev);
    }
    return colours.size;
  } catch {
    return null;
  }
}

// ----------------------------------------------------------------- main ---
let browser = null;
let server = null;
let page = null;
let finished = false;

async function shot(file = SCREENSHOT) {
  if (!page) return null;
  try {
    fs.mkdirSync(path.dirname(file), { recursive: true });
    const buf = await page.screenshot({ path: file, timeout: 30000 });
    return { path: file, distinct_colours: pngDistinctColours(buf) };
  } catch (e) {
    log('screenshot failed:', e.message);
    return { path: null, error: e.message };
  }
}

async function finish(ok, extra = {}) {
  if (finished) return;
  finished = true;
  if (ok && (pageErrors.length || fatal)) {
    ok = false;
    failures.push(`uncaught page error: ${fatal || pageErrors[0].split('\n')[0]}`);
  }
  const screenshot = await shot();
  if (screenshot && screenshot.distinct_colours !== null && screenshot.distinct_colours !== undefined &&
      screenshot.distinct_colours <= 1 && ok) {
    ok = false;
    failures.push('screenshot is a single flat colour (nothing rendered?)');
  }
  const sizeReport = sizes();
  for (const [f, e] of Object.entries(sizeReport.precompressed)) {
    if (!(e.gz_matches && e.br_matches)) {
      ok = false;
      failures.push(`${f}: its .gz or .br copy is missing or does not decode to it`);
    }
  }
  const summary = {
    ok,
    failures,
    dist: DIST,
    // The first page's own clock (from its navigation start), read when its scene
    // opened; the textured scene's page, opened later from the first, also counts the
    // first page's unloading (about 0.6 s).
    time_to_first_frame_ms: firstPage.firstFrameMs === null ? null : Math.round(firstPage.firstFrameMs),
    time_to_scene_ms: firstPage.sceneMs === null ? null : Math.round(firstPage.sceneMs),
    timings_ms: timings,
    final_state: states.length ? states[states.length - 1] : null,
    states_seen: states.length,
    sizes: sizeReport,
    served_bytes: served,
    served_encodings: encodings,
    page_errors: pageErrors,
    ignored_errors: ignoredErrors.length,
    http_errors: httpErrors,
    screenshot,
    total_ms: elapsed(),
    ...extra,
  };
  console.log(JSON.stringify(summary, null, 2));
  if (!ok) {
    console.log(`--- FAILED: ${failures.join('; ')}`);
    console.log('--- last 30 console lines:');
    for (const l of consoleLines.slice(-30)) console.log(l);
  }
  const closers = [];
  if (browser) closers.push(browser.close().catch(() => {}));
  if (server) closers.push(new Promise((r) => { server.closeAllConnections?.(); server.close(() => r()); }));
  await Promise.race([Promise.all(closers), sleep(10000)]);
  process.exit(ok ? 0 : 1);
}

const hardStop = setTimeout(() => {
  failures.push(`hard time limit of ${TOTAL_MS / 1000} s reached`);
  // finish() itself must not hang either.
  setTimeout(() => process.exit(1), 45000).unref();
  finish(false);
}, TOTAL_MS);
hardStop.unref();

process.on('SIGINT', () => { failures.push('interrupted'); finish(false); });
process.on('SIGTERM', () => { failures.push('terminated'); finish(false); });

async function clickWall(n) {
  // The page's main thread is busy with a software-rendered frame most of the time,
  // so ask for the canvas position with a generous bound (it is fixed at 0,0 anyway).
  const box = await Promise.race([
    page.evaluate(() => {
      const r = document.getElementById('shatter-canvas').getBoundingClientRect();
      return { x: r.left, y: r.top };
    }),
    sleep(60000).then(() => null),
  ]);
  const x = (box ? box.x : 0) + CLICK_X;
  const y = (box ? box.y : 0) + CLICK_Y;
  // Move first and let a frame or two pass so the app knows the cursor
  // position before the press.
  await page.mouse.move(x, y, { steps: 2 });
  await sleep(300);
  await page.mouse.down({ button: 'left' });
  await sleep(80);
  await page.mouse.up({ button: 'left' });
  log(`click ${n} at (${x}, ${y})`);
}

function checkFatal(step) {
  if (fatal) throw new Error(`${step}: aborted by page error: ${fatal}`);
}

async function main() {
  for (const f of ['index.html', 'shatter_app.js', 'shatter_app_bg.wasm']) {
    if (!fs.existsSync(path.join(DIST, f))) {
      failures.push(`missing ${path.join(DIST, f)} (run: bash build.sh)`);
    }
  }
  if (failures.length) return finish(false);
  if (!fs.existsSync(CHROMIUM)) {
    failures.push(`no browser at ${CHROMIUM} (apt-get install -y chromium)`);
    return finish(false);
  }

  server = await startServer(DIST);
  const url = `http://127.0.0.1:${server.address().port}/`;
  log('serving', DIST, 'at', url);

  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: process.env.SHATTER_E2E_HEADFUL !== '1',
    args: CHROMIUM_ARGS,
    timeout: 60000,
  });
  log('browser', browser.version());
  const context = await browser.newContext({ viewport: VIEWPORT, deviceScaleFactor: 1 });
  page = await context.newPage();
  page.setDefaultTimeout(30000);

  page.on('console', (msg) => {
    const text = msg.text();
    consoleLines.push(`[${msg.type()}] ${text}`);
    if (consoleLines.length > 2000) consoleLines.splice(0, 1000);
    if (text.includes(MARK)) {
      const st = parseState(text);
      if (st) {
        states.push(st);
        stateTimes.push(elapsed());
        wake();
      }
    }
  });
  page.on('pageerror', (err) => {
    const msg = `${err.name || 'Error'}: ${err.message}`;
    if (msg.includes(CONTROL_FLOW)) {
      ignoredErrors.push(msg);
      return;
    }
    pageErrors.push(msg + (err.stack ? `\n${err.stack}` : ''));
    consoleLines.push(`[pageerror] ${msg}`);
    if (!fatal) fatal = msg;
    wake();
  });
  page.on('crash', () => {
    fatal = fatal || 'page crashed';
    consoleLines.push('[crash] page crashed');
    wake();
  });
  page.on('response', (r) => {
    if (r.status() >= 400) httpErrors.push(`${r.status()} ${r.url()}`);
  });
  page.on('requestfailed', (r) => {
    httpErrors.push(`failed ${r.url()}: ${r.failure()?.errorText}`);
  });

  // 1. First frame.
  const navStart = elapsed();
  await page.goto(url, { waitUntil: 'load', timeout: 120000 });
  timings.page_load = elapsed() - navStart;
  let hit = await waitForState('a SHATTER_STATE with frames > 0', (s) => s.frames > 0, FIRST_FRAME_MS, {
    onTick: (ms) => { if (ms % 30000 < 1000) log(`waiting for the first frame… ${Math.round(ms / 1000)} s`); },
  });
  timings.first_frame_seen = hit.at - navStart;
  log('first frame:', JSON.stringify(hit.state));
  // 1b. The scene opens after the first frame: wait for its fragments, as a user
  //     waits to see it, before starting it.
  hit = await waitForState('a SHATTER_STATE with fragments > 0 (the scene)', (s) => s.fragments > 0, FIRST_FRAME_MS);
  timings.scene_seen = hit.at - navStart;
  log('scene:', JSON.stringify(hit.state));
  [firstPage.firstFrameMs, firstPage.sceneMs] = await page.evaluate(
    () => [window.shatterFirstFrameMs, window.shatterSceneMs], null, { timeout: 30000 });

  // 2. Start the simulation: focus the canvas (no click: a click fires) and
  //    press Enter. Press again (at most twice more) if frames advance but the
  //    app still reports running=false.
  const focusAndEnter = async () => {
    await page.evaluate(() => document.getElementById('shatter-canvas').focus());
    await page.keyboard.press('Enter');
  };
  checkFatal('before Enter');
  await focusAndEnter();
  const enterAt = states.length;
  let extraEnters = 0;
  let lastEnterMs = 0;
  const tStart = elapsed();
  hit = await waitForState('a SHATTER_STATE with running == true (after Enter)', (s) => s.running === true, RUNNING_MS, {
    from: enterAt,
    onTick: async (ms) => {
      if (extraEnters < 2 && ms - lastEnterMs >= 15000) {
        lastEnterMs = ms;
        const last = states[states.length - 1];
        if (states.length > enterAt + 2 && last && last.running === false) {
          extraEnters++;
          log('still not running; pressing Enter again');
          await focusAndEnter();
        }
      }
    },
  });
  timings.running_after_enter = hit.at - tStart;
  log('running:', JSON.stringify(hit.state));

  // 3. Fire at the wall.
  checkFatal('before clicks');
  const tFire = elapsed();
  const fireAt = states.length;
  let clicks = 0;
  for (let i = 0; i < 3; i++) {
    await clickWall(++clicks);
    if (i < 2) await sleep(1500);
  }
  let lastClickMs = 0;
  hit = await waitForState('a SHATTER_STATE with bonds_broken > 0 (after clicks)', (s) => s.bonds_broken > 0, BROKEN_MS, {
    from: fireAt,
    onTick: async (ms) => {
      // Keep firing now and then (slow software rendering may drop early shots).
      if (clicks < 8 && ms - lastClickMs >= 20000) {
        lastClickMs = ms;
        await clickWall(++clicks);
      }
    },
  });
  timings.bonds_broken_after_first_click = hit.at - tFire;
  log('broken:', JSON.stringify(hit.state));

  // 4. "Add mesh…": a picked OBJ reaches the app (its add_mesh export parses it), a
  //    broken one is refused with the parser's message.
  const meshStatus = async () =>
    page.evaluate(() => document.getElementById('shatter-mesh-status').textContent);
  const pick = async (name, text) => {
    await page.setInputFiles('#shatter-mesh-file', {
      name,
      mimeType: 'text/plain',
      buffer: Buffer.from(text),
    });
    const until = Date.now() + 60000;
    const before = await meshStatus();
    while (Date.now() < until) {
      const now = await meshStatus();
      if (now !== before) return now;
      await sleep(250);
    }
    return before;
  };
  const tet = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n';
  const good = await pick('tet.obj', tet);
  if (!good.includes('tet.obj added')) failures.push(`Add mesh: a good OBJ gave "${good}"`);
  const bad = await pick('bad.obj', 'v 0 0 0\nf 1 2 9\n');
  if (!bad.includes('bad.obj') || bad.includes('added')) {
    failures.push(`Add mesh: a broken OBJ gave "${bad}"`);
  }
  log('add mesh:', good, '|', bad);
  if (failures.length) return finish(false);

  // Let the debris fly for a moment, then keep the wall's screenshot.
  await sleep(2000);
  checkFatal('after bonds broke');
  const wallShot = await shot(SCREENSHOT.replace(/\.png$/, '') + '-wall.png');

  // 5. A user's textured models in the page: the `textured` example (the spider OBJ
  //    with its MTL and five JPEG textures, Khronos' textured box GLB; the app carries
  //    their files) opened from the address, drawn with their textures, and broken by
  //    the scene's balls once started.
  const texAt = states.length;
  await page.goto(`${url}?scene=textured`, { waitUntil: 'load', timeout: 120000 });
  hit = await waitForState(
    'a SHATTER_STATE of the textured scene with textured materials drawn',
    (s) => s.frames > 0 && s.textured_materials >= 2 && s.fragments >= 20,
    FIRST_FRAME_MS,
    { from: texAt },
  );
  log('textured scene:', JSON.stringify(hit.state));
  const texturedFirst = hit.state;
  await focusAndEnter();
  hit = await waitForState(
    'a SHATTER_STATE with bonds_broken > 0 in the textured scene',
    (s) => s.running === true && s.bonds_broken > 0,
    BROKEN_MS,
    { from: states.length },
  );
  await sleep(2000);
  checkFatal('after the textured scene broke');
  const texturedShot = await shot(SCREENSHOT.replace(/\.png$/, '') + '-textured.png');
  if (texturedShot && texturedShot.distinct_colours !== null && texturedShot.distinct_colours < 20) {
    failures.push(`textured scene screenshot has only ${texturedShot.distinct_colours} colours`);
    return finish(false);
  }
  return finish(true, {
    clicks,
    extra_enters: extraEnters,
    add_mesh: { good, bad },
    wall_screenshot: wallShot,
    textured: { first: texturedFirst, broken: hit.state, screenshot: texturedShot },
  });
}

main().catch((e) => {
  failures.push(e.message.split('\n')[0]);
  finish(false);
});
