// Shared by the browser tests: Debian's chromium (headless, software WebGL), driven by
// puppeteer-core through the DevTools protocol; every network request is refused and recorded,
// every console error and page error collected.
import puppeteer from 'puppeteer-core';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const chromiumPath = process.env.FLEXGAIT_CHROMIUM || '/usr/bin/chromium';

/// Exits 77 (ctest's SKIP_RETURN_CODE) with one line saying why when there is no chromium.
export function requireChromium() {
  if (!existsSync(chromiumPath)) {
    console.log(`SKIPPED: no chromium at ${chromiumPath} (scripts/install-deps installs Debian's chromium)`);
    process.exit(77);
  }
}

/// A run of `$FLEXGAIT args... --out DIR/run` in a fresh temporary directory (chromium required
/// first): { dir, out, html: its replay.html, log: its log.csv's rows }. The caller removes dir.
export function runWithReplay(args, prefix) {
  requireChromium();
  const exe = process.env.FLEXGAIT;
  if (!exe) throw new Error('set FLEXGAIT to the flexgait executable');
  const dir = mkdtempSync(join(tmpdir(), prefix));
  const out = join(dir, 'run');
  execFileSync(exe, [...args, '--out', out], { stdio: 'ignore' });
  return { dir, out, html: join(out, 'replay.html'), log: parseCsv(readFileSync(join(out, 'log.csv'), 'utf8')) };
}

export async function openPage(file, { width = 900, height = 640 } = {}) {
  const profile = mkdtempSync(join(tmpdir(), 'flexgait-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: chromiumPath,
    headless: true,
    userDataDir: profile,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-quic',
           '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync',
           `--window-size=${width},${height}`],
  });
  const page = await browser.newPage();
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
