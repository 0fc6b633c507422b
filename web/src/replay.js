// flexgait's interactive replay: one scene of rigid bodies (poses per frame), marker layers
// (segments, springs, arrows, points per frame) and signals, read from the JSON block
// <script id="flexgait-replay-data"> that the C++ writer (src/flexgait/replay/) fills in.
// Conventions are MuJoCo's: z up, quaternions (w, x, y, z), geom sizes as half-lengths.
// The format is described in docs/guide/replay.md.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// ---- data -------------------------------------------------------------------------------------

function decodeBytes(text) {
  const bin = atob(text);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return bytes;
}
// Little-endian float32 / uint32 arrays (the writer's byte order, checked on its side).
const f32 = (text) => new Float32Array(decodeBytes(text).buffer);
const f64 = (text) => new Float64Array(decodeBytes(text).buffer);
const u32 = (text) => new Uint32Array(decodeBytes(text).buffer);
const u8 = (text) => decodeBytes(text);

function readData() {
  const raw = JSON.parse(document.getElementById('flexgait-replay-data').textContent);
  if (raw.format !== 'flexgait-replay' || raw.version !== 1)
    throw new Error(`not a flexgait replay (format ${raw.format}, version ${raw.version})`);
  const d = { ...raw };
  d.time = f64(raw.time);
  d.frames = d.time.length;
  d.bodies = raw.bodies ?? [];
  d.poses = raw.poses ? f32(raw.poses) : new Float32Array(0);
  d.layers = (raw.layers ?? []).map((l) => ({ ...l, data: f32(l.data), color: l.color ? u8(l.color) : null }));
  d.signals = (raw.signals ?? []).map((s) => ({ ...s, data: f32(s.data) }));
  d.statics = raw.statics ?? [];
  return d;
}

// ---- scene ------------------------------------------------------------------------------------

function checkerTexture(rgba1, rgba2, cells) {
  // One texture tile: cells × cells squares with a thin line at the tile's border (the 1 m grid).
  const px = 32 * cells;
  const c = document.createElement('canvas');
  c.width = c.height = px;
  const g = c.getContext('2d');
  const css = (v) => `rgb(${Math.round(255 * v[0])},${Math.round(255 * v[1])},${Math.round(255 * v[2])})`;
  for (let i = 0; i < cells; ++i)
    for (let j = 0; j < cells; ++j) {
      g.fillStyle = css((i + j) % 2 ? rgba1 : rgba2);
      g.fillRect(32 * i, 32 * j, 32, 32);
    }
  g.strokeStyle = 'rgba(40,40,40,0.8)';
  g.lineWidth = 2;
  g.strokeRect(0, 0, px, px);
  const t = new THREE.CanvasTexture(c);
  t.wrapS = t.wrapT = THREE.RepeatWrapping;
  t.colorSpace = THREE.SRGBColorSpace;
  t.anisotropy = 4;
  return t;
}

function geomMesh(geom) {
  const s = geom.size ?? [0.05, 0.05, 0.05];
  let geometry;
  switch (geom.type) {
    case 'box': geometry = new THREE.BoxGeometry(2 * s[0], 2 * s[1], 2 * s[2]); break;
    case 'sphere': geometry = new THREE.SphereGeometry(s[0], 24, 16); break;
    case 'ellipsoid':
      geometry = new THREE.SphereGeometry(1, 24, 16);
      geometry.scale(s[0], s[1], s[2]);
      break;
    case 'capsule':  // MuJoCo: radius, half-length along local z
      geometry = new THREE.CapsuleGeometry(s[0], 2 * s[1], 8, 16);
      geometry.rotateX(Math.PI / 2);
      break;
    case 'cylinder':
      geometry = new THREE.CylinderGeometry(s[0], s[0], 2 * s[1], 32);
      geometry.rotateX(Math.PI / 2);
      break;
    case 'plane': {  // half-sizes in x and y; 0 = unbounded (drawn 30 m)
      const hx = s[0] > 0 ? s[0] : 30, hy = s[1] > 0 ? s[1] : 30;
      geometry = new THREE.PlaneGeometry(2 * hx, 2 * hy);
      break;
    }
    case 'mesh': {
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(f32(geom.vertices), 3));
      geometry.setIndex(new THREE.BufferAttribute(u32(geom.faces), 1));
      geometry.computeVertexNormals();
      break;
    }
    default:
      geometry = new THREE.SphereGeometry(0.02);
  }
  const rgba = geom.rgba ?? [0.7, 0.7, 0.7, 1];
  const material = new THREE.MeshStandardMaterial({
    color: new THREE.Color(rgba[0], rgba[1], rgba[2]), roughness: 0.75, metalness: 0.05,
    transparent: rgba[3] < 1, opacity: rgba[3],
  });
  if (geom.type === 'plane' && geom.checker) {
    const hx = s[0] > 0 ? s[0] : 30, hy = s[1] > 0 ? s[1] : 30;
    material.map = checkerTexture(rgba, rgba.map((v, i) => (i < 3 ? 0.8 * v : v)), 2);
    material.map.repeat.set(hx, hy);  // a tile of 2 × 2 squares per 2 m: 1 m squares, a line every 2 m
    material.color.set(0xffffff);
  }
  const mesh = new THREE.Mesh(geometry, material);
  mesh.castShadow = geom.type !== 'plane';
  mesh.receiveShadow = true;
  if (geom.pos) mesh.position.set(geom.pos[0], geom.pos[1], geom.pos[2]);
  if (geom.quat) mesh.quaternion.set(geom.quat[1], geom.quat[2], geom.quat[3], geom.quat[0]);
  return mesh;
}

const UP = new THREE.Vector3(0, 1, 0);

// A spring: a helix of unit length along +y (drawn as a line), scaled to the item's length.
function springGeometry(radius, turns) {
  const pts = [];
  const n = turns * 16;
  for (let i = 0; i <= n; ++i) {
    const a = (2 * Math.PI * turns * i) / n;
    const y = i < 8 ? 0 : i > n - 8 ? 1 : i / n;
    const r = i < 8 || i > n - 8 ? 0 : radius;
    pts.push(new THREE.Vector3(r * Math.cos(a), y, r * Math.sin(a)));
  }
  return new THREE.BufferGeometry().setFromPoints(pts);
}

class Layer {
  constructor(spec, group) {
    this.spec = spec;
    this.group = new THREE.Group();
    this.group.name = spec.name;
    this.dim = spec.kind === 'points' ? 3 : 6;
    this.palette = (spec.palette ?? [[1, 0.5, 0, 1]]).map((c) => new THREE.Color(c[0], c[1], c[2]));
    this.items = [];
    const width = spec.width ?? 0.02;
    for (let k = 0; k < spec.count; ++k) {
      let obj;
      if (spec.kind === 'arrows') {
        obj = new THREE.ArrowHelper(UP, new THREE.Vector3(), 1, this.palette[0], 0.1, 0.05);
        obj.line.material.linewidth = 2;
      } else if (spec.kind === 'points') {
        obj = new THREE.Mesh(new THREE.SphereGeometry(width, 20, 12),
                             new THREE.MeshStandardMaterial({ color: this.palette[0], roughness: 0.5 }));
        obj.castShadow = true;
      } else if (spec.kind === 'springs') {
        obj = new THREE.Line(springGeometry(width, spec.turns ?? 10), new THREE.LineBasicMaterial({ color: this.palette[0] }));
      } else {  // segments: thin cylinders
        const g = new THREE.CylinderGeometry(width, width, 1, 12);
        g.translate(0, 0.5, 0);
        obj = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: this.palette[0], roughness: 0.6 }));
        obj.castShadow = true;
      }
      this.items.push(obj);
      this.group.add(obj);
    }
    group.add(this.group);
    this.a = new THREE.Vector3();
    this.b = new THREE.Vector3();
  }

  show(frame) {
    const { data, color, count, kind } = this.spec;
    for (let k = 0; k < count; ++k) {
      const obj = this.items[k];
      const at = (frame * count + k) * this.dim;
      const x0 = data[at];
      if (Number.isNaN(x0)) { obj.visible = false; continue; }
      obj.visible = true;
      const c = this.palette[color ? color[frame * count + k] : 0] ?? this.palette[0];
      this.a.set(data[at], data[at + 1], data[at + 2]);
      if (kind === 'points') {
        obj.position.copy(this.a);
        obj.material.color.copy(c);
        continue;
      }
      this.b.set(data[at + 3], data[at + 4], data[at + 5]);
      const dir = this.b.clone().sub(this.a);
      const length = dir.length();
      if (!(length > 1e-9)) { obj.visible = false; continue; }
      dir.divideScalar(length);
      if (kind === 'arrows') {
        obj.position.copy(this.a);
        obj.setDirection(dir);
        const head = Math.min(0.3 * length, 0.12);
        obj.setLength(length, head, 0.5 * head);
        obj.setColor(c);
      } else {
        obj.position.copy(this.a);
        obj.quaternion.setFromUnitVectors(UP, dir);
        obj.scale.set(1, length, 1);
        obj.material.color.copy(c);
      }
    }
  }
}

// ---- plots ------------------------------------------------------------------------------------

// The signals in panels (tabs), each panel a column of plots, each plot the lines of its signals
// on shared axes (one unit), in the order the signals come. A signal without a panel goes to
// "signals", without a plot to a plot of its own.
function groupSignals(signals) {
  const panels = [];
  signals.forEach((s, index) => {
    const name = s.panel || 'signals';
    let panel = panels.find((p) => p.name === name);
    if (!panel) panels.push((panel = { name, plots: [] }));
    const title = s.plot || s.name;
    let plot = s.plot ? panel.plots.find((p) => p.title === title) : undefined;
    if (!plot) panel.plots.push((plot = { title, unit: s.unit ?? '', lines: [] }));
    plot.lines.push({ index, name: s.name, label: s.label || s.name });
  });
  return panels;
}

const LINE_COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#17becf'];
const LEFT = 62, RIGHT = 10;  // the plots' margins [CSS pixels]

class Plots {
  constructor(canvas, tabs, data, onChange) {
    this.canvas = canvas;
    this.data = data;
    this.cursorX = 0;
    this.shown = [];
    const t = data.time;
    this.t0 = t[0];
    this.t1 = t[t.length - 1] > t[0] ? t[t.length - 1] : t[0] + 1;
    this.panels = groupSignals(data.signals);
    for (const panel of this.panels)
      for (const plot of panel.plots) {
        let lo = Infinity, hi = -Infinity;
        for (const line of plot.lines)
          for (const v of data.signals[line.index].data) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
        if (!(hi > lo)) { lo = Number.isFinite(lo) ? lo - 1 : -1; hi = Number.isFinite(hi) ? hi + 1 : 1; }
        const pad = 0.08 * (hi - lo);
        plot.range = [lo - pad, hi + pad];
      }
    this.panel = this.panels[0] ?? null;
    this.buttons = this.panels.map((panel) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = panel.name;
      b.dataset.panel = panel.name;
      b.addEventListener('click', () => { this.select(panel.name); onChange(); });
      tabs.append(b);
      return b;
    });
    if (this.panels.length < 2) tabs.style.display = 'none';
    this.select(this.panel?.name);
  }

  select(name) {
    this.panel = this.panels.find((p) => p.name === name) ?? this.panel;
    this.buttons.forEach((b) => b.classList.toggle('active', b.dataset.panel === this.panel?.name));
  }

  xOf(t, width) { return LEFT + ((t - this.t0) / (this.t1 - this.t0)) * (width - LEFT - RIGHT); }

  draw(frame) {
    const c = this.canvas;
    const dpr = window.devicePixelRatio || 1;
    const width = c.clientWidth, height = c.clientHeight;
    if (c.width !== Math.round(width * dpr) || c.height !== Math.round(height * dpr)) {
      c.width = Math.round(width * dpr);
      c.height = Math.round(height * dpr);
    }
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, width, height);
    this.shown = [];
    if (!this.panel) return;
    const plots = this.panel.plots;
    const strip = height / plots.length;
    const t = this.data.time;
    const step = Math.max(1, Math.floor(t.length / (4 * width)));
    g.font = '11px sans-serif';
    g.textBaseline = 'alphabetic';
    plots.forEach((plot, i) => {
      const [lo, hi] = plot.range;
      const y0 = i * strip + 16, h = strip - 22;
      const yOf = (v) => y0 + h - ((v - lo) / (hi - lo)) * h;
      g.strokeStyle = '#ddd';
      g.lineWidth = 1;
      g.strokeRect(LEFT, y0, width - LEFT - RIGHT, h);
      if (lo < 0 && hi > 0) {  // the zero line
        g.beginPath();
        g.moveTo(LEFT, yOf(0));
        g.lineTo(width - RIGHT, yOf(0));
        g.stroke();
      }
      g.fillStyle = '#333';
      g.textAlign = 'left';
      const title = `${plot.title}${plot.unit ? ` [${plot.unit}]` : ''}`;
      g.fillText(title, LEFT, y0 - 4);
      g.textAlign = 'right';
      g.fillText(hi.toPrecision(3), LEFT - 4, y0 + 9);
      g.fillText(lo.toPrecision(3), LEFT - 4, y0 + h);
      // The legend, right-aligned above the plot: each line's name and its value at the cursor
      // (the values alone where the names would run into the title).
      const shown = plot.lines.map((line) => {
        const v = this.data.signals[line.index].data[frame];
        const value = !Number.isFinite(v) ? '–' : Number.isInteger(v) ? String(v) : v.toPrecision(4);
        return { plot: plot.title, name: line.name, label: line.label, value: v, text: `${line.label} ${value}`, short: value };
      });
      const legendWidth = shown.reduce((w, x) => w + g.measureText(x.text).width + 24, 0);
      const short = LEFT + g.measureText(title).width + 12 > width - RIGHT - legendWidth;
      let x = width - RIGHT;
      for (let k = plot.lines.length - 1; k >= 0; --k) {
        const text = short ? shown[k].short : shown[k].text;
        g.fillStyle = '#333';
        g.fillText(text, x, y0 - 4);
        x -= g.measureText(text).width + 4;
        g.fillStyle = LINE_COLORS[k % LINE_COLORS.length];
        g.fillRect(x - 10, y0 - 11, 10, 6);
        x -= 20;
      }
      this.shown.push(...shown.map(({ short: _, ...x }) => x));
      plot.lines.forEach((line, k) => {
        const data = this.data.signals[line.index].data;
        g.strokeStyle = LINE_COLORS[k % LINE_COLORS.length];
        g.lineWidth = 1.2;
        g.beginPath();
        let pen = false;
        for (let f = 0; f < t.length; f += step) {
          const v = data[f];
          if (!Number.isFinite(v)) { pen = false; continue; }
          const px = this.xOf(t[f], width), py = yOf(v);
          if (pen) g.lineTo(px, py); else g.moveTo(px, py);
          pen = true;
        }
        g.stroke();
      });
    });
    // The cursor: a one-pixel black line at the frame's time, on a pixel's centre.
    this.cursorX = (Math.round(this.xOf(t[frame], width) * dpr) + 0.5) / dpr;
    g.strokeStyle = '#000';
    g.lineWidth = 1 / dpr;
    g.beginPath();
    g.moveTo(this.cursorX, 0);
    g.lineTo(this.cursorX, height);
    g.stroke();
  }
}

// ---- the page ---------------------------------------------------------------------------------

function main() {
  const data = readData();
  document.title = data.title ? `${data.title} — flexgait replay` : 'flexgait replay';
  document.getElementById('title').textContent = data.title ?? '';

  const view = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = THREE.PCFShadowMap;
  view.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  // Sky: a vertical gradient behind everything.
  const sky = document.createElement('canvas');
  sky.width = 2; sky.height = 256;
  const sg = sky.getContext('2d');
  const grad = sg.createLinearGradient(0, 0, 0, 256);
  grad.addColorStop(0, '#6f9fd8');
  grad.addColorStop(1, '#e8eef5');
  sg.fillStyle = grad;
  sg.fillRect(0, 0, 2, 256);
  scene.background = new THREE.CanvasTexture(sky);
  scene.background.colorSpace = THREE.SRGBColorSpace;

  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.4));
  const sun = new THREE.DirectionalLight(0xffffff, 2.2);
  sun.castShadow = true;
  sun.shadow.mapSize.set(2048, 2048);
  const sc = data.shadow_extent ?? 6;
  Object.assign(sun.shadow.camera, { left: -sc, right: sc, top: sc, bottom: -sc, near: 0.1, far: 60 });
  scene.add(sun, sun.target);

  for (const g of data.statics) scene.add(geomMesh(g));
  const bodies = data.bodies.map((b) => {
    const group = new THREE.Group();
    group.name = b.name;
    for (const g of b.geoms ?? []) group.add(geomMesh(g));
    scene.add(group);
    return group;
  });
  const markerRoot = new THREE.Group();
  scene.add(markerRoot);
  const layers = data.layers.map((l) => new Layer(l, markerRoot));

  const camera = new THREE.PerspectiveCamera(40, 16 / 9, 0.02, 200);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, renderer.domElement);
  const cam = data.camera ?? {};
  const target = new THREE.Vector3(...(cam.target ?? [0, 0, 0.5]));
  const az = ((cam.azimuth ?? -90) * Math.PI) / 180, el = ((cam.elevation ?? 10) * Math.PI) / 180;
  const dist = cam.distance ?? 4;
  camera.position.set(target.x + dist * Math.cos(el) * Math.cos(az), target.y + dist * Math.cos(el) * Math.sin(az),
                      target.z + dist * Math.sin(el));
  controls.target.copy(target);
  controls.update();
  const followIndex = data.bodies.findIndex((b) => b.name === (cam.follow ?? ''));

  // Controls.
  const slider = document.getElementById('slider');
  const playButton = document.getElementById('play');
  const speedSelect = document.getElementById('speed');
  const clock = document.getElementById('clock');
  const followBox = document.getElementById('follow');
  slider.max = String(Math.max(0, data.frames - 1));
  const toggles = document.getElementById('toggles');
  layers.forEach((layer) => {
    const label = document.createElement('label');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = layer.spec.visible !== false;
    layer.group.visible = box.checked;
    box.dataset.layer = layer.spec.name;
    box.addEventListener('change', () => { layer.group.visible = box.checked; draw(); });
    label.append(box, ` ${layer.spec.name}`);
    if (layer.spec.legend) {
      const legend = document.createElement('span');
      legend.className = 'legend';
      layer.spec.legend.forEach((name, i) => {
        const sw = document.createElement('i');
        sw.style.background = `#${layer.palette[i].getHexString()}`;
        legend.append(sw, `${name} `);
      });
      label.append(legend);
    }
    toggles.append(label);
  });
  if (followIndex < 0) followBox.parentElement.style.display = 'none';

  // (a panel's tab redraws the plots alone: the scene has not changed)
  const plots = new Plots(document.getElementById('plots'), document.getElementById('panels'), data, () => plots.draw(frame));
  let frame = 0;
  let playing = false;
  let playTime = data.time[0];
  let last = null;
  const followPrev = new THREE.Vector3();

  function pose(b, f) {
    const at = (f * data.bodies.length + b) * 7;
    return data.poses.subarray(at, at + 7);
  }

  function setFrame(f) {
    frame = Math.max(0, Math.min(data.frames - 1, f | 0));
    bodies.forEach((group, b) => {
      const p = pose(b, frame);
      group.position.set(p[0], p[1], p[2]);
      group.quaternion.set(p[4], p[5], p[6], p[3]);
    });
    layers.forEach((l) => l.show(frame));
    if (followIndex >= 0 && followBox.checked) {
      const p = bodies[followIndex].position;
      const delta = new THREE.Vector3(p.x, p.y, 0).sub(followPrev);
      camera.position.add(delta);
      controls.target.add(delta);
      followPrev.set(p.x, p.y, 0);
    }
    slider.value = String(frame);
    clock.textContent = `t = ${data.time[frame].toFixed(3)} s   frame ${frame + 1}/${data.frames}`;
    draw();
  }
  if (followIndex >= 0) {
    const p = pose(followIndex, 0);
    followPrev.set(p[0], p[1], 0);
  }

  function draw() {
    const w = view.clientWidth, h = view.clientHeight;
    if (renderer.domElement.width !== Math.round(w * renderer.getPixelRatio())) {
      renderer.setSize(w, h);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
    }
    sun.position.set(controls.target.x - 3, controls.target.y - 4, controls.target.z + 8);
    sun.target.position.copy(controls.target);
    renderer.render(scene, camera);
    plots.draw(frame);
  }

  slider.addEventListener('input', () => { playing = false; playButton.textContent = 'Play'; setFrame(Number(slider.value)); });
  playButton.addEventListener('click', () => {
    playing = !playing;
    playButton.textContent = playing ? 'Pause' : 'Play';
    if (playing && frame >= data.frames - 1) setFrame(0);
    playTime = data.time[frame];
    last = null;
  });
  followBox.addEventListener('change', () => {
    const p = bodies[followIndex].position;
    followPrev.set(p.x, p.y, 0);
  });
  controls.addEventListener('change', draw);
  window.addEventListener('resize', draw);
  document.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement && e.target.type !== 'range') return;
    if (e.key === ' ') { playButton.click(); e.preventDefault(); }
    if (e.key === 'ArrowRight') setFrame(frame + 1);
    if (e.key === 'ArrowLeft') setFrame(frame - 1);
  });

  function tick(now) {
    if (playing) {
      if (last !== null) playTime += ((now - last) / 1000) * Number(speedSelect.value);
      last = now;
      let f = frame;
      while (f + 1 < data.frames && data.time[f + 1] <= playTime) ++f;
      if (f !== frame) setFrame(f);
      if (frame >= data.frames - 1) { playing = false; playButton.textContent = 'Play'; }
    }
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);
  setFrame(0);

  // For tests and scripts: read what the page shows.
  window.flexgaitReplay = {
    frames: data.frames,
    frame: () => frame,
    setFrame,
    time: (f) => data.time[f],
    bodyNames: () => data.bodies.map((b) => b.name),
    bodyPosition: (name) => {
      const b = data.bodies.findIndex((x) => x.name === name);
      return b < 0 ? null : Array.from(bodies[b].position.toArray());
    },
    signal: (name, f) => {
      const s = data.signals.find((x) => x.name === name);
      return s ? s.data[f] : null;
    },
    layerItem: (name, k, f) => {
      const l = data.layers.find((x) => x.name === name);
      if (!l) return null;
      const dim = l.kind === 'points' ? 3 : 6;
      return Array.from(l.data.subarray((f * l.count + k) * dim, (f * l.count + k + 1) * dim));
    },
    cursorX: () => plots.cursorX,
    // The plots: the panels' names, the one shown, and what its legends show at the cursor
    // ({plot, name, label, value, text} per line).
    panels: () => plots.panels.map((p) => p.name),
    panel: () => plots.panel?.name ?? null,
    plotted: () => plots.shown.map((x) => ({ ...x })),
    ready: true,
  };
}

try {
  main();
} catch (e) {
  document.getElementById('title').textContent = `cannot show this replay: ${e.message}`;
  throw e;
}
