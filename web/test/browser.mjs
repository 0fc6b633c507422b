// Shared by the browser tests: Debian's chromium (headless, software WebGL), driven by
// puppeteer-core through the DevTools protocol; every network request is refused and recorded,
// every console error and page error collected.
import puppeteer from 'puppeteer-core';
import { execFile } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';

export const chromiumPath = process.env.FLEXGAIT_CHROMIUM || '/usr/bin/chromium';

/// Exits 77 (ctest's SKIP_RETURN_CODE) with one line saying why when there is no chromium.
export function requireChromium() {
  if (!existsSync(chromiumPath)) {
    console.log(`SKIPPED: no chromium at ${chromiumPath} (scripts/install-deps installs Debian's chromium)`);
    process.exit(77);
  }
}

/// A run of `$FLEXGAIT args... --no-plot --out DIR/run` in a fresh temporary directory, and its
/// replay.html opened (openPage; chromium required, started while the run goes): { dir, out,
/// html: the page's file, log: log.csv's rows, page, errors, requests, close }. close() also
/// removes dir.
export async function runAndOpen(args, prefix, size) {
  requireChromium();
  const exe = process.env.FLEXGAIT;
  if (!exe) throw new Error('set FLEXGAIT to the flexgait executable');
  const dir = mkdtempSync(join(tmpdir(), prefix));
  const out = join(dir, 'run');
  const browser = launch(size);
  browser.catch(() => {});  // (awaited below, after the run)
  try {
    await promisify(execFile)(exe, [...args, '--no-plot', '--out', out]);  // (the figures are not the page's)
  } catch (e) {
    await browser.then(({ browser: b }) => b.close(), () => {});
    throw e;
  }
  const html = join(out, 'replay.html');
  const opened = await openPage(html, { ...size, browser: await browser });
  const close = async () => {
    await opened.close();
    rmSync(dir, { recursive: true, force: true });
  };
  return { dir, out, html, log: parseCsv(readFileSync(join(out, 'log.csv'), 'utf8')), ...opened, close };
}

/// Every panel of the plots, shown as a person would (its tab clicked), at the first, a middle and
/// the last frame (the slider moved): the black cursor is drawn across the plots at the frame's
/// time (its x linear in time), and each value the legends show is `expected(row, name)` exactly
/// (Math.fround of it: the page keeps float32), where row is the log's row at the frame's time
/// (rowAt(t)); `expected` returns undefined for a signal the log does not hold. Returns the names
/// of the signals checked against the log, by panel.
export async function checkPanels(page, assert, rowAt, expected) {
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  const panels = await page.evaluate(() => window.flexgaitReplay.panels());
  const checked = {};
  for (const panel of panels) {
    await page.click(`#panels button[data-panel="${panel}"]`);
    assert.equal(await page.evaluate(() => window.flexgaitReplay.panel()), panel);
    checked[panel] = new Set();
    const cursor = [];
    const times = [];
    for (const f of [0, Math.floor(frames / 2), frames - 1]) {
      // (one round trip: the slider moved as moveSlider moves it, then what the plots show read)
      const [shownFrame, t, x, shown, dark] = await page.evaluate((f) => {
        const slider = document.getElementById('slider');
        slider.value = String(f);
        slider.dispatchEvent(new Event('input', { bubbles: true }));
        const r = window.flexgaitReplay;
        // The cursor's darkness: the share of the plots canvas's pixel column at cursorX that is
        // near black (the cursor is a one-pixel black line over the canvas's height).
        const c = document.getElementById('plots');
        const px = c.getContext('2d').getImageData(Math.floor(r.cursorX() * (window.devicePixelRatio || 1)), 0, 1,
          c.height).data;
        let black = 0;
        for (let i = 0; i < px.length; i += 4) black += px[i] < 60 && px[i + 1] < 60 && px[i + 2] < 60;
        return [r.frame(), r.time(r.frame()), r.cursorX(), r.plotted(), black / c.height];
      }, f);
      assert.equal(shownFrame, f);
      times.push(t);
      cursor.push(x);
      assert.ok(dark > 0.9, `${panel}, frame ${f}: the cursor's column is ${dark} dark`);
      assert.ok(shown.length > 0, `${panel}: nothing plotted`);
      const row = rowAt(t);
      assert.ok(row, `no log row at t = ${t}`);
      for (const s of shown) {
        const want = expected(row, s.name);
        if (want === undefined) continue;
        const value = s.value ?? NaN;  // (NaN is null once out of the page)
        assert.ok(value === Math.fround(want) || (Number.isNaN(value) && Number.isNaN(want)),
          `${panel}: ${s.name} at t = ${t} shows ${value}, the log ${want}`);
        checked[panel].add(s.name);
      }
    }
    // The cursor follows the slider: its x is linear in the frame's time (1 pixel of rounding).
    const expect = cursor[0] + ((cursor[2] - cursor[0]) * (times[1] - times[0])) / (times[2] - times[0]);
    assert.ok(cursor[2] > cursor[0] + 200, `${panel}: cursor ${cursor}`);
    assert.ok(Math.abs(cursor[1] - expect) <= 1, `${panel}: cursor ${cursor[1]} vs ${expect}`);
  }
  return checked;
}

function launch({ width = 900, height = 640 } = {}) {
  const profile = mkdtempSync(join(tmpdir(), 'flexgait-chromium-'));
  return puppeteer
    .launch({
      executablePath: chromiumPath,
      headless: true,
      userDataDir: profile,
      args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic',
             '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync',
             `--window-size=${width},${height}`],
    })
    .then((browser) => ({ browser, profile }));
}

/// `file` in chromium (`browser`: one launch() made, else a new one), in its first tab.
export async function openPage(file, { width = 900, height = 640, browser: launched } = {}) {
  const { browser, profile } = launched ?? (await launch({ width, height }));
  // (the tab chromium opens with: a new one costs a second or more under software rendering)
  const page = (await browser.pages())[0] ?? (await browser.newPage());
  await page.setViewport({ width, height });
  const errors = [];
  const requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.setRequestInterception(true);
  const url = `file://${file}`;
  page.on('request', (r) => {
    if (r.url() === url) return r.continue();
    requests.push(r.url());
    return r.abort();
  });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.flexgaitReplay?.ready === true || document.getElementById('title')?.textContent.startsWith('cannot'), { timeout: 20000 });
  const close = async () => {
    await browser.close();
    rmSync(profile, { recursive: true, force: true });
  };
  return { browser, page, errors, requests, close };
}

/// Pixels of the page's WebGL canvas (drawn into a 2D canvas), kept in the page under `key`;
/// with `against`, the count of pixels that differ from that earlier snapshot.
export async function canvasSnapshot(page, key, against) {
  return page.evaluate((key, against) => {
    const gl = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = gl.width;
    c.height = gl.height;
    const g = c.getContext('2d');
    g.drawImage(gl, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    window.__snapshots = window.__snapshots || {};
    window.__snapshots[key] = px;
    if (!against) return px.length / 4;
    const old = window.__snapshots[against];
    let differing = 0;
    for (let i = 0; i < px.length; i += 4)
      if (Math.abs(px[i] - old[i]) + Math.abs(px[i + 1] - old[i + 1]) + Math.abs(px[i + 2] - old[i + 2]) > 24) ++differing;
    return differing;
  }, key, against);
}

/// Moves the time slider as a person would (the input event), to frame f.
export async function moveSlider(page, f) {
  await page.evaluate((f) => {
    const s = document.getElementById('slider');
    s.value = String(f);
    s.dispatchEvent(new Event('input', { bubbles: true }));
  }, f);
}

/// Rows of a CSV file with a header line, as objects of strings.
export function parseCsv(text) {
  const [head, ...rows] = text.trim().split('\n');
  const cols = head.split(',');
  return rows.map((r) => Object.fromEntries(r.split(',').map((v, i) => [cols[i], v])));
}
