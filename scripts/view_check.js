// Checks and measures `mocapsolve view` pages in headless Chromium (scripts/view_check.sh
// sets CHROMIUM and NODE_PATH). Usage: node view_check.js SPEC.json, where SPEC is
//   {"width": 960, "height": 600,                 viewport (CSS pixels)
//    "pages": [{
//      "path": "/abs/page.html",                  opened from file://
//      "min_share": 0.01,                         canvas pixels that are not background
//      "moving": [0, 20],                         these two frames must render differently,
//                                                 and a frame drawn twice identically
//      "repaired": {"label": "LKNE", "frame": 12, "state": "gap"},
//                                                 that marker drawn in that state's colour
//      "screenshot": {"path": "/abs/shot.png", "frame": 10},
//      "bench": {"seconds": 3}                    open time, and frames drawn per second
//                                                 while playing (requestAnimationFrame)
//    }]}
// Prints one JSON line per page with its figures and failures; exit 1 if any check
// failed, 77 if the browser cannot be started.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');

let puppeteer;
try {
  puppeteer = require('puppeteer-core');
} catch (e) {
  console.error('view_check: puppeteer-core is not installed (scripts/viewer_tools.sh)');
  process.exit(77);
}

const BACKGROUND = [0x1d, 0x21, 0x27];

async function canvasFigures(page) {
  return page.evaluate((background) => {
    const canvas = document.getElementById('mv-canvas');
    const w = canvas.width, h = canvas.height;
    const copy = document.createElement('canvas');
    copy.width = w;
    copy.height = h;
    const g = copy.getContext('2d');
    g.drawImage(canvas, 0, 0);
    const data = g.getImageData(0, 0, w, h).data;
    let drawn = 0, hash = 2166136261;
    for (let i = 0; i < data.length; i += 4) {
      const d = Math.abs(data[i] - background[0]) + Math.abs(data[i + 1] - background[1]) +
                Math.abs(data[i + 2] - background[2]);
      if (d > 24) drawn++;
      hash = Math.imul(hash ^ data[i], 16777619) ^ Math.imul(data[i + 1] + 256 * data[i + 2], 2246822519);
    }
    return { width: w, height: h, share: drawn / (w * h), hash: hash >>> 0 };
  }, BACKGROUND);
}

async function pixelAt(page, x, y) {
  return page.evaluate((x, y) => {
    const canvas = document.getElementById('mv-canvas');
    const ratio = canvas.width / canvas.clientWidth;
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const g = copy.getContext('2d');
    g.drawImage(canvas, 0, 0);
    const p = g.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data;
    return [p[0], p[1], p[2]];
  }, x, y);
}

function hexColor(hex) {
  return [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
}

async function checkPage(browser, spec, viewport) {
  const result = { page: spec.path, failures: [] };
  const fail = (text) => result.failures.push(text);
  const page = await browser.newPage();
  await page.setViewport(viewport);
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('requestfailed', (r) => errors.push('request failed: ' + r.url().slice(0, 80)));
  const started = Date.now();
  await page.goto('file://' + path.resolve(spec.path), { waitUntil: 'load', timeout: 60000 });
  try {
    await page.waitForFunction('window.mocapsolveView && (window.mocapsolveView.ready || window.mocapsolveView.error)',
                               { timeout: 60000, polling: 20 });
  } catch (e) {
    fail('not ready within 60 s');
  }
  result.open_seconds = (Date.now() - started) / 1000;
  const state = await page.evaluate(() => ({ ready: window.mocapsolveView.ready, frames: window.mocapsolveView.frames,
                                             error: window.mocapsolveView.error }));
  result.frames = state.frames;
  if (state.error) fail('page error: ' + state.error.split('\n')[0]);
  if (!state.ready) {
    result.console_errors = errors;
    await page.close();
    return result;
  }
  result.bytes = fs.statSync(spec.path).size;
  const first = await canvasFigures(page);
  result.canvas = [first.width, first.height];
  result.share = first.share;
  if (first.share < (spec.min_share || 0.01)) fail('canvas nearly blank: ' + (100 * first.share).toFixed(2) + '% drawn');

  if (spec.moving) {
    const [a, b] = spec.moving;
    await page.evaluate((i) => window.mocapsolveView.setFrame(i), a);
    const ha = (await canvasFigures(page)).hash;
    await page.evaluate((i) => window.mocapsolveView.setFrame(i), b);
    const hb = (await canvasFigures(page)).hash;
    await page.evaluate((i) => window.mocapsolveView.setFrame(i), a);
    const ha2 = (await canvasFigures(page)).hash;
    result.moving = { a: ha, b: hb, a_again: ha2 };
    if (ha === hb) fail('frames ' + a + ' and ' + b + ' render identically');
    if (ha !== ha2) fail('frame ' + a + ' renders differently the second time');
  }
  if (spec.repaired) {
    const r = spec.repaired;
    await page.evaluate((i) => window.mocapsolveView.setFrame(i), r.frame);
    const at = await page.evaluate((label) => window.mocapsolveView.markerScreen(label), r.label);
    if (!at) {
      fail('marker ' + r.label + ' not drawn at frame ' + r.frame);
    } else {
      const names = await page.evaluate(() => window.mocapsolveView.stateNames);
      const colors = await page.evaluate(() => window.mocapsolveView.stateColors);
      const expected = hexColor(colors[names.indexOf(r.state)] || '#000000');
      const got = await pixelAt(page, at.x, at.y);
      result.repaired = { label: r.label, frame: r.frame, state: at.state, expected: expected, pixel: got };
      if (at.state !== r.state) fail(r.label + ' at frame ' + r.frame + ' is "' + at.state + '", expected "' + r.state + '"');
      if (expected.some((c, k) => Math.abs(c - got[k]) > 12)) {
        fail(r.label + ' drawn as rgb(' + got + '), expected the ' + r.state + ' colour rgb(' + expected + ')');
      }
    }
  }
  if (spec.screenshot) {
    await page.evaluate((i) => window.mocapsolveView.setFrame(i), spec.screenshot.frame || 0);
    await page.screenshot({ path: spec.screenshot.path, type: 'png' });
  }
  if (spec.bench) {
    const seconds = spec.bench.seconds || 3;
    result.play = await page.evaluate((seconds) => new Promise((resolve) => {
      const view = window.mocapsolveView;
      const before = view.renders;
      const times = [];
      view.play();
      const start = performance.now();
      function tick(now) {
        times.push(now);
        if (now - start < seconds * 1000) { requestAnimationFrame(tick); return; }
        view.pause();
        const intervals = [];
        for (let i = 1; i < times.length; ++i) intervals.push(times[i] - times[i - 1]);
        intervals.sort((x, y) => x - y);
        resolve({ renders: view.renders - before, seconds: (now - start) / 1000,
                  fps: (view.renders - before) / ((now - start) / 1000),
                  median_ms: intervals[Math.floor(intervals.length / 2)] || 0,
                  p95_ms: intervals[Math.floor(intervals.length * 0.95)] || 0 });
      }
      requestAnimationFrame(tick);
    }), seconds);
  }
  result.console_errors = errors;
  if (errors.length) fail('console errors: ' + errors.slice(0, 3).join(' | '));
  await page.close();
  return result;
}

(async () => {
  const spec = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
  const viewport = { width: spec.width || 960, height: spec.height || 600, deviceScaleFactor: 1 };
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'mocapsolve-chromium-'));
  let browser;
  try {
    browser = await puppeteer.launch({
      executablePath: process.env.CHROMIUM,
      headless: true,
      userDataDir: profile,
      timeout: 60000,
      args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
             '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update',
             '--disable-sync', '--disable-dev-shm-usage', '--allow-file-access-from-files'],
    });
  } catch (e) {
    console.error('view_check: cannot start chromium: ' + String(e).split('\n')[0]);
    fs.rmSync(profile, { recursive: true, force: true });
    process.exit(77);
  }
  let failed = false;
  try {
    for (const page of spec.pages) {
      const result = await checkPage(browser, page, viewport);
      if (result.failures.length) failed = true;
      console.log(JSON.stringify(result));
    }
  } catch (e) {
    console.error('view_check: ' + String(e));
    failed = true;
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  process.exit(failed ? 1 : 0);
})();
