// The run's page in headless Chromium (spec/page.md PAGE-1..8): Debian's chromium driven by
// puppeteer-core, WebGL on SwiftShader, the page opened from file:// with the browser's default file
// security. Two pages: the fandisk's (the paper's §6 run) and a generated genus-1 surface with a
// boundary loop. Each check is one JUnit case (FHR_JUNIT_XML), counted by proofs_tests/run_suites.py.
//
//   node web/test/test_page.mjs                 every check; screenshots to out/page-tests/
//   node web/test/test_page.mjs --regenerate    rewrite the reviewed screenshots in reference_outputs/page/
// Environment: FHR (the built fhr), FHR_CGAL_MESHES (libcgal-demo's meshes), FHR_JUNIT_XML.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import pixelmatch from 'pixelmatch';
import { PNG } from 'pngjs';
import puppeteer from 'puppeteer-core';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const OUT = path.join(ROOT, 'out', 'page-tests');
const REFERENCE = path.join(ROOT, 'reference_outputs', 'page');
const REGENERATE = process.argv.includes('--regenerate');
const FHR = process.env.FHR || path.join(ROOT, 'build', 'src', 'fhr');
const MESHES = process.env.FHR_CGAL_MESHES || path.join(ROOT, 'out', 'cgal-data', 'data', 'meshes');

// WebGL on SwiftShader, headless; --no-sandbox because the tests run as root here (Chromium refuses
// to start as root with its sandbox). No flag touches file:// security.
const CHROMIUM_ARGS = ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox',
  '--font-render-hinting=none', '--hide-scrollbars'];
// Console warnings that the software GL driver prints on its own, not the page.
const KNOWN_WARNINGS = [/GPU stall due to ReadPixels/, /Automatic fallback to software WebGL/, /GL Driver Message/];
// Reviewed screenshots match when at most this share of pixels differ by more than pixelmatch's
// perceptual threshold (YIQ distance 0.1): antialiasing and rasterization may move a few edges.
const SCREENSHOT_THRESHOLD = 0.1, SCREENSHOT_SHARE = 0.005;
const VIEWPORT = { width: 1280, height: 800, deviceScaleFactor: 1, hasTouch: true };

const results = [];
async function check(name, body) {
  const start = Date.now();
  try {
    await body();
    results.push({ name, seconds: (Date.now() - start) / 1000 });
    console.log(`ok   ${name}`);
  } catch (e) {
    results.push({ name, seconds: (Date.now() - start) / 1000, failure: String(e && e.stack || e) });
    console.log(`FAIL ${name}\n${e && e.stack || e}`);
  }
}
function assert(condition, message) {
  if (!condition) throw new Error(message);
}

function fhr(...args) {
  return execFileSync(FHR, args, { stdio: ['ignore', 'pipe', 'pipe'] }).toString();
}

/** The patch of every face of T′, from param.fhrp (spec/param.md). */
function fhrpFaces(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n');
  const at = lines.findIndex((l) => l.startsWith('surface_vertices'));
  const vertices = lines.slice(at + 1, at + 1 + Number(lines[at].split(' ')[1])).map((l) => l.split(' ').map(Number));
  const start = at + 1 + vertices.length;
  const count = Number(lines[start].split(' ')[1]);
  return lines.slice(start + 1, start + 1 + count).map((l) => {
    const t = l.split(' ').map(Number);
    const [a, b, c] = [vertices[t[0]], vertices[t[1]], vertices[t[2]]];
    const u = a.map((x, i) => b[i] - x), v = a.map((x, i) => c[i] - x);
    const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    return { patch: t[3], area: Math.hypot(...n) / 2 };
  });
}

const decode = (png) => PNG.sync.read(png);
/** Pixels of two screenshots that differ perceptibly (pixelmatch, threshold as stated above). */
function differing(a, b) {
  const x = decode(a), y = decode(b);
  if (x.width !== y.width || x.height !== y.height) return x.width * x.height;
  return pixelmatch(x.data, y.data, null, x.width, x.height, { threshold: SCREENSHOT_THRESHOLD });
}

async function settled(page) {
  await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
}
async function canvasShot(page) {
  await settled(page);
  return (await page.$('canvas.three')).screenshot();
}

async function openPage(browser, html) {
  const page = await browser.newPage();
  const requests = [], console_ = [];
  page.on('request', (r) => requests.push(r.url()));
  page.on('console', (m) => console_.push({ type: m.type(), text: m.text() }));
  page.on('pageerror', (e) => console_.push({ type: 'error', text: String(e) }));
  await page.setViewport(VIEWPORT);
  await page.goto('file://' + html);
  await page.waitForFunction('window.fhrPage && window.fhrPage.firstFrame !== null', { timeout: 60000 });
  return { page, requests, console: console_ };
}

async function stage(page, id) {
  await page.click(`button[data-stage="${id}"]`);
  await settled(page);
}

/** Steps a range input through all its values from its minimum, returning a (shot, readout) per step. */
async function sweep(page, id) {
  const max = await page.$eval(`#${id}`, (e) => Number(e.max));
  const steps = [];
  for (let v = 0; v <= max; v++) {
    await page.$eval(`#${id}`, (e, value) => {
      e.value = String(value);
      e.dispatchEvent(new Event('input', { bubbles: true }));
    }, v);
    steps.push({ shot: await canvasShot(page), readout: await page.$eval('#readout', (e) => e.textContent) });
  }
  return steps;
}

async function checkPage(browser, name, dir) {
  const html = path.join(dir, 'index.html');
  const report = JSON.parse(fs.readFileSync(path.join(dir, 'report.json'), 'utf8'));
  const { page, requests, console: messages } = await openPage(browser, html);
  const shots = {};

  await check(`${name}: every request is file:, data: or blob: (PAGE-1)`, async () => {
    assert(requests.length > 0 && requests[0].startsWith('file://'), `first request ${requests[0]}`);
    const other = requests.filter((u) => !/^(file|data|blob):/.test(u));
    assert(other.length === 0, `requests elsewhere: ${other.join(', ')}`);
  });

  await check(`${name}: the canvas is not blank`, async () => {
    const png = decode(await canvasShot(page));
    const background = [png.data[0], png.data[1], png.data[2]];
    let drawn = 0;
    const colours = new Set();
    for (let i = 0; i < png.data.length; i += 4) {
      if (Math.abs(png.data[i] - background[0]) + Math.abs(png.data[i + 1] - background[1]) + Math.abs(png.data[i + 2] - background[2]) > 30) drawn++;
      colours.add((png.data[i] << 16) | (png.data[i + 1] << 8) | png.data[i + 2]);
    }
    assert(drawn > 0.05 * png.width * png.height, `only ${drawn} of ${png.width * png.height} pixels drawn`);
    assert(colours.size > 20, `only ${colours.size} colours`);
  });

  await check(`${name}: the page looks as reviewed (reference_outputs/page/, timings masked)`, async () => {
    await page.addStyleTag({ content: '.timing { visibility: hidden; }' });
    const failures = [];
    for (const id of ['s2', 's3', 's4', 's5', 'run']) {
      await stage(page, id);
      await page.click('#reset');
      await settled(page);
      const shot = await page.screenshot();
      const file = `${name}-${id}.png`;
      fs.writeFileSync(path.join(OUT, file), shot);
      const reference = path.join(REFERENCE, file);
      if (REGENERATE) {
        fs.mkdirSync(REFERENCE, { recursive: true });
        fs.writeFileSync(reference, shot);
        continue;
      }
      if (!fs.existsSync(reference)) { failures.push(`${file}: no reviewed screenshot (run with --regenerate and review)`); continue; }
      const bad = differing(fs.readFileSync(reference), shot);
      const share = bad / (VIEWPORT.width * VIEWPORT.height);
      if (share > SCREENSHOT_SHARE) failures.push(`${file}: ${(100 * share).toFixed(2)} % of pixels differ (at most ${100 * SCREENSHOT_SHARE} %); see ${path.join(OUT, file)}`);
    }
    assert(failures.length === 0, failures.join('\n'));
  });
  await check(`${name}: each stage and each of its toggles changes the pixels (PAGE-4)`, async () => {
    let previous = await canvasShot(page);
    for (const id of ['s2', 's3', 's4', 's5', 'run']) {
      await stage(page, id);
      const shot = await canvasShot(page);
      shots[id] = shot;
      if (id !== 's2') assert(differing(previous, shot) > 100, `stage ${id} draws the same pixels as the one before`);
      previous = shot;
      for (const toggle of await page.$$('#controls input[type=checkbox], #controls input[type=radio]')) {
        const label = await toggle.evaluate((e) => e.id);
        if (await toggle.evaluate((e) => e.checked && e.type === 'radio')) continue;
        await toggle.click();
        const after = await canvasShot(page);
        assert(differing(previous, after) > 100, `stage ${id}: toggle ${label} changes nothing`);
        previous = after;
      }
      await stage(page, id); // the next stage starts from this stage's first view
      previous = await canvasShot(page);
    }
  });

  await check(`${name}: a click on a face shows its patch from param.fhrp (PAGE-5)`, async () => {
    await stage(page, 's4');
    const faces = fhrpFaces(path.join(dir, 'param.fhrp'));
    const order = faces.map((f, i) => i).sort((i, j) => faces[j].area - faces[i].area);
    let target = null;
    for (const f of order.slice(0, 400)) {
      const at = await page.evaluate((face) => window.fhrPage.project(face), f);
      if (at) { target = { f, at }; break; }
    }
    assert(target, 'no face of the 400 largest is seen whole');
    await page.mouse.click(target.at.x, target.at.y);
    await settled(page);
    const shown = await page.$eval('#patch-panel', (e) => ({ hidden: e.hidden, patch: e.dataset.patch, face: e.dataset.face, title: e.querySelector('.panel-title').textContent }));
    assert(!shown.hidden, 'the 2D panel did not open');
    assert(Number(shown.face) === target.f, `clicked face ${target.f}, the panel names face ${shown.face}`);
    assert(Number(shown.patch) === faces[target.f].patch, `face ${target.f} is in patch ${faces[target.f].patch} (param.fhrp), the panel says ${shown.patch}`);
    assert(shown.title.includes(`Patch ${faces[target.f].patch}:`), `title "${shown.title}"`);
    // The face is highlighted in 3D, under the click, and in 2D.
    const png = decode(await canvasShot(page));
    const rect = await page.$eval('canvas.three', (c) => { const r = c.getBoundingClientRect(); return { x: r.left, y: r.top }; });
    const i = 4 * (Math.round(target.at.y - rect.y) * png.width + Math.round(target.at.x - rect.x));
    assert(png.data[i] > 200 && png.data[i + 1] > 80 && png.data[i + 1] < 170 && png.data[i + 2] < 90, `pixel under the click ${png.data.slice(i, i + 3)} is not the highlight`);
    const orange = await page.$eval('#patch-panel canvas', (c) => {
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let k = 0; k < d.length; k += 4) if (d[k] > 240 && d[k + 1] > 100 && d[k + 1] < 150 && d[k + 2] < 40) n++;
      return n;
    });
    assert(orange > 0, 'the 2D panel does not highlight the face');
  });

  await check(`${name}: each step of the level slider changes the mesh and its readout (PAGE-6)`, async () => {
    await stage(page, 's5');
    const steps = await sweep(page, 'level');
    assert(steps.length === report.remesh.level + 1, `${steps.length} steps for J = ${report.remesh.level}`);
    for (let k = 1; k < steps.length; k++) {
      assert(differing(steps[k - 1].shot, steps[k].shot) > 100, `level ${k} draws what level ${k - 1} drew`);
      assert(steps[k - 1].readout !== steps[k].readout, `level ${k}: the readout stays "${steps[k].readout}"`);
    }
  });

  await check(`${name}: each step of the coefficients slider changes the mesh and the errors shown (PAGE-6)`, async () => {
    await stage(page, 's5');
    const steps = await sweep(page, 'keep');
    const kept = report.wavelet.kept.map((k) => k.percent);
    assert(steps.length >= 7 + kept.filter((p) => ![1, 2, 5, 10, 20, 50, 100].includes(p)).length, `${steps.length} steps`);
    for (let k = 1; k < steps.length; k++) {
      assert(differing(steps[k - 1].shot, steps[k].shot) > 20, `step ${k} draws what step ${k - 1} drew`);
      assert(steps[k - 1].readout !== steps[k].readout, `step ${k}: the readout stays "${steps[k].readout}"`);
    }
    for (const k of report.wavelet.kept) {
      const shown = steps.find((s) => s.readout.startsWith(`${k.percent} %`));
      assert(shown && shown.readout.includes(`L2 error ${k.l2_error.toPrecision(3)}`), `${k.percent} %: report's L2 error ${k.l2_error} not shown`);
    }
  });

  await check(`${name}: mouse drag turns, the wheel zooms, reset returns`, async () => {
    await stage(page, 's2');
    const rect = await page.$eval('canvas.three', (c) => { const r = c.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
    const cx = rect.x + rect.w / 2, cy = rect.y + rect.h / 2;
    const before = await canvasShot(page);
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    await page.mouse.move(cx + 150, cy + 40, { steps: 8 });
    await page.mouse.up();
    const turned = await canvasShot(page);
    assert(differing(before, turned) > 1000, 'a drag does not turn the view');
    await page.mouse.wheel({ deltaY: -400 });
    const zoomed = await canvasShot(page);
    assert(differing(turned, zoomed) > 1000, 'the wheel does not zoom');
    await page.click('#reset');
    const back = await canvasShot(page);
    assert(differing(before, back) < 50, 'reset does not return to the first view');
  });

  await check(`${name}: a touch drag turns the view`, async () => {
    await stage(page, 's2');
    await page.click('#reset');
    const rect = await page.$eval('canvas.three', (c) => { const r = c.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
    const cx = rect.x + rect.w / 2, cy = rect.y + rect.h / 2;
    const before = await canvasShot(page);
    await page.touchscreen.touchStart(cx, cy);
    for (let k = 1; k <= 8; k++) await page.touchscreen.touchMove(cx + 20 * k, cy + 5 * k);
    await page.touchscreen.touchEnd();
    const after = await canvasShot(page);
    assert(differing(before, after) > 1000, 'a touch drag does not turn the view');
    await page.click('#reset');
  });

  await check(`${name}: the verdict shown is report.json's (PAGE-7)`, async () => {
    await stage(page, 'run');
    const oracle = report.parameterization.oracle;
    const shown = await page.$eval('#verdict', (t) => ({
      valid: t.dataset.valid,
      rows: [...t.querySelectorAll('tr[data-check]')].map((r) => [...r.cells].map((c) => c.textContent)),
    }));
    assert(shown.valid === String(oracle.valid), `valid ${shown.valid}, report ${oracle.valid}`);
    assert(JSON.stringify(shown.rows) === JSON.stringify(oracle.checks.map((c) => [c.id, c.status, c.checked.toLocaleString('en-US'), String(c.failures)])),
      `checks shown ${JSON.stringify(shown.rows)}`);
    const badge = await page.$eval('#verdict-badge', (e) => e.textContent);
    assert(badge.includes(oracle.valid ? 'oracle: valid' : 'oracle: INVALID'), `badge "${badge}"`);
  });

  await check(`${name}: no console error, no warning but the driver's (PAGE-1)`, async () => {
    const bad = messages.filter((m) => m.type === 'error' || (m.type === 'warn' && !KNOWN_WARNINGS.some((w) => w.test(m.text))));
    assert(bad.length === 0, bad.map((m) => `${m.type}: ${m.text}`).join('\n'));
  });

  await page.close();
}

// PAGE-9: beyond --page-faces N the page draws a display copy of T′ and says so; a click names the
// face of T′ the face clicked stands for, with its patch from param.fhrp.
async function checkDisplayCopy(browser, name, dir, budget) {
  const { page } = await openPage(browser, path.join(dir, 'index.html'));
  await check(`${name}: T′ drawn as a display copy of at most ${budget} faces, clicks resolve to T′ (PAGE-9)`, async () => {
    const faces = fhrpFaces(path.join(dir, 'param.fhrp'));
    const drawn = await page.evaluate(() => window.fhrPage.faces());
    assert(faces.length > budget && drawn <= budget && drawn > budget / 4, `T′ ${faces.length} faces, ${drawn} drawn`);
    const note = await page.$eval('#note', (e) => (e.hidden ? '' : e.textContent));
    assert(note.includes('display copy'), `the page does not say it draws a display copy: "${note}"`);
    await stage(page, 's4');
    let clicked = 0;
    for (let f = 0; f < drawn && clicked < 3; f += 97) {
      const at = await page.evaluate((face) => window.fhrPage.project(face), f);
      if (!at) continue;
      await page.mouse.click(at.x, at.y);
      await settled(page);
      const shown = await page.$eval('#patch-panel', (e) => ({ patch: Number(e.dataset.patch), face: Number(e.dataset.face) }));
      const original = await page.evaluate((face) => window.fhrPage.original(face), f);
      assert(shown.face === original, `display face ${f} stands for face ${original} of T′, the panel names ${shown.face}`);
      assert(faces[original] && shown.patch === faces[original].patch, `face ${original} of T′ is in patch ${faces[original]?.patch}, the panel says ${shown.patch}`);
      clicked++;
    }
    assert(clicked === 3, `only ${clicked} display faces could be clicked`);
  });
  await page.close();
}

function writeJunit(file) {
  const escape = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
  const failed = results.filter((r) => r.failure).length;
  const cases = results.map((r) => `  <testcase classname="page" name="${escape(r.name)}" time="${r.seconds}">` +
    (r.failure ? `<failure message="${escape(r.failure.split('\n')[0])}">${escape(r.failure)}</failure>` : '') + '</testcase>').join('\n');
  fs.writeFileSync(file, `<?xml version="1.0" encoding="utf-8"?>\n<testsuite name="page" tests="${results.length}" failures="${failed}" errors="0" skipped="0">\n${cases}\n</testsuite>\n`);
}

async function main() {
  fs.mkdirSync(OUT, { recursive: true });
  const runs = path.join(OUT, 'runs');
  fs.rmSync(runs, { recursive: true, force: true });
  const fandisk = path.join(MESHES, 'fandisk.off');
  const pages = [];
  await check('the pages are written (fhr run --html)', async () => {
    assert(fs.existsSync(fandisk), `${fandisk} is missing: libcgal-demo's meshes (./run extracts them; FHR_CGAL_MESHES)`);
    fhr('run', fandisk, '--faces', '114', '--levels', '3', '--keep', '5,20', '--map', 'paper', '--html', '--out', path.join(runs, 'fandisk'));
    fhr('run', fandisk, '--faces', '114', '--levels', '3', '--keep', '5,20', '--map', 'paper', '--html', '--out', path.join(runs, 'fandisk-again'));
    pages.push(['fandisk', path.join(runs, 'fandisk')]);
    fhr('run', fandisk, '--faces', '114', '--map', 'paper', '--html', '--page-faces', '8000', '--out', path.join(runs, 'fandisk-display'));
    // A genus-1 surface with one boundary loop: boundary arcs among the curves.
    const mesh = path.join(runs, 'genus1-hole.off');
    fhr('generate', '--genus', '1', '--holes', '1', '--faces', '2000', '--seed', '3', '--noise', '0.1', '--out', mesh);
    fhr('run', mesh, '--faces', '60', '--levels', '2', '--keep', '5,20', '--html', '--out', path.join(runs, 'genus1-hole'));
    pages.push(['genus1-hole', path.join(runs, 'genus1-hole')]);
    const report = JSON.parse(fs.readFileSync(path.join(runs, 'genus1-hole', 'report.json'), 'utf8'));
    assert(report.input.genus === 1 && report.input.boundary_loops === 1 && report.partition.boundary_edges > 0,
      `the generated surface is not of genus 1 with a boundary arc: ${JSON.stringify(report.input)}`);
  });
  await check('the page is the same bytes on every run but its timings (PAGE-2)', async () => {
    const [a, b] = ['fandisk', 'fandisk-again'].map((d) => fs.readFileSync(path.join(runs, d, 'index.html'), 'utf8'));
    const withoutTimings = (html) => html.replace(/"timings": \{[^}]*\}/, '"timings": {}');
    assert(withoutTimings(a) === withoutTimings(b), 'two runs wrote different pages (timings aside)');
    assert(/"timings": \{[^}]*"total"/.test(a), 'the page holds no timings');
  });
  const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: true, args: CHROMIUM_ARGS });
  try {
    for (const [name, dir] of pages) await checkPage(browser, name, dir);
    if (pages.length) await checkDisplayCopy(browser, 'fandisk-display', path.join(runs, 'fandisk-display'), 8000);
  } finally {
    await browser.close();
  }
  if (process.env.FHR_JUNIT_XML) writeJunit(process.env.FHR_JUNIT_XML);
  const failed = results.filter((r) => r.failure).length;
  console.log(`${results.length - failed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

await main();
