// A humanoid walk's replay.html in a real browser (Debian's chromium, headless): it loads with no
// console error and no network request; moving the time slider changes the drawn picture; the
// pelvis the page shows at a frame is log.csv's at that time, and the COM marker is the log's COM
// moved by one fixed offset (the plan's frame in the world), as is the pelvis; the walk's markers
// are layers;
// each panel of plots (ZMP, COM and capture point, pelvis, gears, feet) draws its cursor at the
// slider's time and shows log.csv's and joints.csv's values there.
// Run: node web/test/humanoid_replay.test.mjs (env FLEXGAIT = the flexgait executable).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { runAndOpen, canvasSnapshot, moveSlider, parseCsv, checkPanels } from './browser.mjs';

// One step (4.5 s simulated): the page's data are the log's samples, 25 frames per second.
const { out, html, log, page, errors, requests, close } = await runAndOpen(['humanoid', 'walk', '--set', 'walk.steps=1'],
  'flexgait-humanoid-replay-');
const joints = parseCsv(readFileSync(join(out, 'joints.csv'), 'utf8'));  // (a row per log row, the same times)

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
    // The pelvis's x and y (the log's in the plan's frame) by the same offset: the float32 of the
    // pelvis (< 1 m: 6e-8 m) and of the COM marker, and the offset's, within 2e-6 m.
    const p = [pos[0] - offset[0], pos[1] - offset[1]];
    const want = [Number(row.pelvis_x), Number(row.pelvis_y)];
    for (let i = 0; i < 2; ++i) assert.ok(Math.abs(p[i] - want[i]) <= 2e-6, `pelvis ${p} vs log ${want}`);
  }
});

test('every panel of plots follows the slider and shows the log\'s values', async () => {
  const rowAt = (t) => {
    const i = log.findIndex((r) => Number(r.t) === t);
    return i < 0 ? undefined : { ...joints[i], ...log[i] };
  };
  // A signal is a column of log.csv or joints.csv, or "a - b" of two (the page rounds the double
  // difference to float32, as it does a column); the capture point is the page's marker.
  const expected = (row, name) => {
    const [a, b] = name.split(' - ');
    if (!(a in row) || (b !== undefined && !(b in row))) return undefined;
    return b === undefined ? Number(row[a]) : Number(row[a]) - Number(row[b]);
  };
  const checked = await checkPanels(page, assert, rowAt, expected);
  assert.deepEqual(Object.keys(checked), ['ZMP', 'COM, capture point', 'pelvis', 'gears', 'feet']);
  for (const name of ['zmp_ref_y', 'zmp_ft_y', 'zmp_true_y', 'zmp_true_x - zmp_ref_x'])
    assert.ok(checked.ZMP.has(name), name);
  for (const name of ['com_y', 'com_ref_y', 'com_x - com_ref_x']) assert.ok(checked['COM, capture point'].has(name), name);
  for (const name of ['roll_true', 'pitch_true', 'pelvis_z']) assert.ok(checked.pelvis.has(name), name);
  for (const name of ['l_hip_roll_torque_true', 'r_ankle_roll_torque_true', 'l_hip_roll_encoder - l_hip_roll_link'])
    assert.ok(checked.gears.has(name), name);
  for (const name of ['l_ft_fz', 'r_ft_fz']) assert.ok(checked.feet.has(name), name);
  // The capture point plotted is the capture point marker in the plan's frame: the marker less the
  // offset that takes the log's COM to the COM marker (the same float32 values, subtracted in double).
  await page.click('#panels button[data-panel="COM, capture point"]');
  const frames = await page.evaluate(() => window.flexgaitReplay.frames);
  for (const f of [0, Math.floor(frames * 0.6)]) {
    await moveSlider(page, f);
    const [t, com, xi, shown] = await page.evaluate((f) => {
      const r = window.flexgaitReplay;
      return [r.time(f), r.layerItem('COM ground projection', 0, f), r.layerItem('capture point', 0, f), r.plotted()];
    }, f);
    const row = rowAt(t);
    const value = (name) => shown.find((s) => s.name === name).value;
    // 2e-6 m: the float32 rounding of the markers (< 1 m: 6e-8 m) and of the log's COM, as above.
    assert.ok(Math.abs(value('capture_point_x') - (xi[0] - (com[0] - Number(row.com_x)))) <= 2e-6);
    assert.ok(Math.abs(value('capture_point_y') - (xi[1] - (com[1] - Number(row.com_y)))) <= 2e-6);
  }
  assert.deepEqual(errors, []);
});

test.after(close);
