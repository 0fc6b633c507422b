// The rimless wheel's replay.html in a real browser (Debian's chromium, headless): it loads with
// no console error and no network request; moving the time slider changes the drawn picture and
// the plots' cursor; the hub position the page shows at a frame is the log's at that time; each
// panel of plots (body, energy, contacts) draws its cursor at the slider's time and shows
// log.csv's values there.
// Run: node web/test/rimless_replay.test.mjs (env FLEXGAIT = the flexgait executable).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { runAndOpen, canvasSnapshot, moveSlider, checkPanels } from './browser.mjs';

const { out, html, log, page, errors, requests, close } = await runAndOpen(['rimless', 'simulate', '--steps', '6'],
  'flexgait-rimless-replay-');
const slope = Number(/^\s+slope: ([0-9.e+-]+)/m.exec(readFileSync(join(out, 'config.yaml'), 'utf8'))[1]);

test('the page loads offline with no console error', async () => {
  assert.deepEqual(errors, []);
  assert.deepEqual(requests, []);  // everything it needs is inside the file
  assert.ok(statSync(html).size < 5e6);
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  assert.ok(frames > 30, `${frames} frames`);
});

test('moving the slider changes the picture and the plotted cursor', async () => {
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  await moveSlider(page, 0);
  const cursor0 = await page.evaluate(() => window.flexgaitReplay.cursorX());
  await canvasSnapshot(page, 'first');
  const f = Math.floor(frames * 0.6);
  await moveSlider(page, f);
  assert.equal(await page.evaluate(() => window.flexgaitReplay.frame()), f);
  const differing = await canvasSnapshot(page, 'later', 'first');
  // The wheel has rolled ~1.5 m and turned by several legs: far more than a few hundred pixels of
  // a 900 × 330 view change (a redraw of the same frame changes none: checked below).
  assert.ok(differing > 500, `${differing} pixels changed`);
  const cursor = await page.evaluate(() => window.flexgaitReplay.cursorX());
  assert.ok(cursor > cursor0 + 100, `cursor ${cursor0} -> ${cursor}`);
  await moveSlider(page, f);
  assert.equal(await canvasSnapshot(page, 'again', 'later'), 0);
  assert.deepEqual(errors, []);
});

test('the hub position shown at a frame is the log\'s at that time', async () => {
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  for (const f of [0, Math.floor(frames / 3), frames - 1]) {
    await moveSlider(page, f);
    const [t, pos, x, y] = await page.evaluate((f) => {
      const r = window.flexgaitReplay;
      return [r.time(f), r.bodyPosition('hub'), r.signal('x', f), r.signal('y', f)];
    }, f);
    // Frames are logged samples: the frame's time (float64) is a row's time exactly.
    const row = log.find((r) => Number(r.t) === t);
    assert.ok(row, `no log row at t = ${t}`);
    const lx = Number(row.x), ly = Number(row.y);
    // The page keeps float32 (24-bit mantissa, relative rounding 6e-8): 1e-6 m holds for
    // coordinates below 16 m, and a wrong row (1 ms away at ~1 m/s) is off by ~1e-3 m.
    assert.ok(Math.abs(x - lx) <= 1e-6 && Math.abs(y - ly) <= 1e-6, `signals (${x}, ${y}) vs log (${lx}, ${ly})`);
    // The hub in the world: the slope frame turned by φ about +y (docs/theory/rimless.md).
    const world = [lx * Math.cos(slope) + ly * Math.sin(slope), 0, -lx * Math.sin(slope) + ly * Math.cos(slope)];
    for (let i = 0; i < 3; ++i) assert.ok(Math.abs(pos[i] - world[i]) <= 1e-6, `hub ${pos} vs log ${world}`);
  }
});

test('every panel of plots follows the slider and shows the log\'s values', async () => {
  const rowAt = (t) => log.find((r) => Number(r.t) === t);
  // A signal is log.csv's column of its name; phaseK as a number (slip+ 1, stick 0, slip- -1,
  // none: not drawn).
  const phases = { 'slip+': 1, stick: 0, 'slip-': -1, none: NaN };
  const expected = (row, name) => {
    if (!(name in row)) return undefined;
    return name.startsWith('phase') ? phases[row[name]] : Number(row[name]);
  };
  const checked = await checkPanels(page, assert, rowAt, expected);
  assert.deepEqual(Object.keys(checked), ['body', 'energy', 'contacts']);
  for (const name of ['x', 'y', 'theta', 'thetad']) assert.ok(checked.body.has(name), name);
  for (const name of ['E_kinetic', 'E_total', 'W_damp', 'W_fric', 'balance']) assert.ok(checked.energy.has(name), name);
  for (const name of ['N1', 'T1', 'phase1', 'leg1', 'N3', 'phase3']) assert.ok(checked.contacts.has(name), name);
  assert.deepEqual(errors, []);
});

test.after(close);
