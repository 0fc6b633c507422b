// A humanoid walk's replay.html in a real browser (Debian's chromium, headless): it loads with no
// console error and no network request; moving the time slider changes the drawn picture; the
// pelvis height the page shows at a frame is log.csv's at that time, and the COM marker is the
// log's COM moved by one fixed offset (the plan's frame in the world); the walk's markers are layers.
// Run: node web/test/humanoid_replay.test.mjs (env FLEXGAIT = the flexgait executable).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { rmSync, statSync } from 'node:fs';
import { runWithReplay, openPage, canvasSnapshot, moveSlider } from './browser.mjs';

// One step (4.5 s simulated): the page's data are the log's samples, 25 frames per second.
const { dir, html, log } = runWithReplay(['humanoid', 'walk', '--set', 'walk.steps=1'], 'flexgait-humanoid-replay-');
const { page, errors, requests, close } = await openPage(html);

test('the page loads offline with no console error, with the walk\'s layers', async () => {
  assert.deepEqual(errors, []);
  assert.deepEqual(requests, []);  // everything it needs is inside the file
  assert.ok(statSync(html).size < 5e6);
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  assert.ok(frames > 100, `${frames} frames`);
  const names = await page.evaluate(() => window.flexgaitReplay.bodyNames());
  assert.ok(names.includes('pelvis'), names.join(' '));
  for (const layer of ['ZMP', 'reference ZMP', 'COM ground projection', 'capture point', 'actual footprints'])
    assert.ok(await page.evaluate((l) => window.flexgaitReplay.layerItem(l, 0, 0) !== null, layer), layer);
});

test('moving the slider changes the picture', async () => {
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  await moveSlider(page, 0);
  await canvasSnapshot(page, 'first');
  const f = Math.floor(frames * 0.6);  // in the step's single support: a leg lifted
  await moveSlider(page, f);
  assert.equal(await page.evaluate(() => window.flexgaitReplay.frame()), f);
  const differing = await canvasSnapshot(page, 'later', 'first');
  assert.ok(differing > 300, `${differing} pixels changed`);
  await moveSlider(page, f);
  assert.equal(await canvasSnapshot(page, 'again', 'later'), 0);
  assert.deepEqual(errors, []);
});

test('the pelvis shown at a frame is the log\'s at that time', async () => {
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  let offset = null;
  for (const f of [0, Math.floor(frames / 2), frames - 1]) {
    await moveSlider(page, f);
    const [t, pos, z, com] = await page.evaluate((f) => {
      const r = window.flexgaitReplay;
      return [r.time(f), r.bodyPosition('pelvis'), r.signal('pelvis_z', f), r.layerItem('COM ground projection', 0, f)];
    }, f);
    // Frames are logged samples: the frame's time (float64) is a row's time exactly.
    const row = log.find((r) => Number(r.t) === t);
    assert.ok(row, `no log row at t = ${t}`);
    // The page keeps float32 (relative rounding 6e-8 at < 1 m: 6e-8 m); log.csv's digits are
    // finer. A wrong row (20 ms away) moves the pelvis by ~1e-4 m or more while walking.
    assert.ok(Math.abs(pos[2] - Number(row.pelvis_z)) <= 1e-6, `pelvis z ${pos[2]} vs log ${row.pelvis_z}`);
    assert.ok(Math.abs(z - Number(row.pelvis_z)) <= 1e-6, `signal ${z} vs log ${row.pelvis_z}`);
    // The COM marker (world) against the log's COM (the plan's frame): one offset for every frame
    // (the twin's initial sole centres against the plan's footprints: 3.7 cm along x for the builtin).
    const d = [com[0] - Number(row.com_x), com[1] - Number(row.com_y)];
    if (offset === null) offset = d;
    for (let i = 0; i < 2; ++i) assert.ok(Math.abs(d[i] - offset[i]) <= 2e-6, `COM offset ${d} vs ${offset}`);
    assert.ok(Math.hypot(...offset) < 0.05, `offset ${offset}`);
  }
});

test.after(async () => {
  await close();
  rmSync(dir, { recursive: true, force: true });
});
