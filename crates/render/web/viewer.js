// vsrlab replay viewer: reads replay files (docs/viewer.md) and draws them on canvases, in sync.
// Plain JavaScript, no library, no network access beyond the server that sent this page.
"use strict";

const PANE_COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"];
const RED = [255, 0, 0], YELLOW = [255, 255, 0], GREEN = [0, 255, 0];

const state = {
  panes: [],
  time: 0,
  duration: 0,
  playing: false,
  speed: 1,
  follow: true,
  zoom: 1,
  overlays: { colours: true, touch: true, lidar: true, trail: true, footprints: true, ticks: true },
  orbit: { azimuth: -60, elevation: 25 }, // the 3D camera's direction from its target (degrees), shared by all 3D panes
  selected: null, // { pane, unit }
  unitChannel: "", // the per-unit channel the unit chart plots ("": actuation and area ratio)
  chartsDirty: true,
};

// Timing of the drawing, read by the browser test (docs/viewer.md).
const stats = { playedFrames: 0, playStart: 0, playEnd: 0, drawMs: 0, drawn: 0, maxDrawMs: 0 };

class ReplayError extends Error {}

// ---------------------------------------------------------------- reading a replay

function fail(name, message) {
  throw new ReplayError(`${name}: ${message}`);
}

function need(cond, name, message) {
  if (!cond) fail(name, message);
}

function isNumber(v) {
  return typeof v === "number" && Number.isFinite(v);
}

// Decodes one delta-coded channel into a Float64Array (frame-major).
function decodeChannel(name, key, channel, frames) {
  need(channel && typeof channel === "object", name, `channel '${key}' is not an object`);
  const { per_frame: per, scale, data } = channel;
  need(Number.isInteger(per) && per > 0, name, `channel '${key}': per_frame must be a positive integer, got ${JSON.stringify(per)}`);
  need(isNumber(scale) && scale > 0, name, `channel '${key}': scale must be a positive number, got ${JSON.stringify(scale)}`);
  need(Array.isArray(data), name, `channel '${key}': data must be an array`);
  need(data.length === per * frames, name,
    `channel '${key}': data holds ${data.length} numbers, expected ${per * frames} (frames ${frames} × per_frame ${per})`);
  const out = new Float64Array(data.length);
  const sums = new Float64Array(per);
  for (let j = 0; j < data.length; j++) {
    const d = data[j];
    if (!Number.isInteger(d)) fail(name, `channel '${key}': data[${j}] is not an integer (${JSON.stringify(d)})`);
    const i = j % per;
    sums[i] += d;
    out[j] = sums[i] * scale;
  }
  return { per, values: out };
}

// Checks a parsed replay file and decodes it; throws ReplayError naming the field.
function readReplay(json, name) {
  need(json && typeof json === "object" && !Array.isArray(json), name, "not a replay: the file is not a JSON object");
  need(json.format === "vsrlab-replay", name, `not a vsrlab replay: field 'format' is ${JSON.stringify(json.format)}, expected "vsrlab-replay"`);
  need(json.version === 1, name, `field 'version' is ${JSON.stringify(json.version)}; this viewer reads version 1`);
  const frames = json.frames;
  need(Number.isInteger(frames) && frames > 0, name, `field 'frames' must be a positive integer, got ${JSON.stringify(frames)}`);
  for (const f of ["t0", "frame_dt", "side", "quantum"]) need(isNumber(json[f]), name, `field '${f}' must be a number, got ${JSON.stringify(json[f])}`);
  need(json.frame_dt > 0, name, "field 'frame_dt' must be positive");
  need(json.side > 0, name, "field 'side' must be positive");
  if (json.channels && typeof json.channels === "object" && json.channels.voxel_xyz) return readSolidReplay(json, name);
  const world = json.world, body = json.body;
  need(world && Array.isArray(world.terrain) && world.terrain.length !== 1, name, "field 'world.terrain' must be a list of at least 2 points, or empty (no ground)");
  world.terrain.forEach((p, i) => need(Array.isArray(p) && isNumber(p[0]) && isNumber(p[1]), name, `field 'world.terrain[${i}]' is not an [x, y] point`));
  const obstacles = world.obstacles || [];
  need(Array.isArray(obstacles), name, "field 'world.obstacles' must be a list of polygons");
  const balls = world.balls || [];
  need(body && Array.isArray(body.corners) && body.corners.length > 0, name, "field 'body.corners' must be a non-empty list");
  body.corners.forEach((n, i) => need(Number.isInteger(n) && n >= 3, name, `field 'body.corners[${i}]' must be an integer ≥ 3`));
  const cells = body.cells || [];
  need(Array.isArray(cells), name, "field 'body.cells' must be a list");
  const rays = body.rays || [];
  const unitFill = body.unit_fill || [];
  need(Array.isArray(unitFill) && unitFill.every((c) => Number.isInteger(c) && c >= 0 && c <= 0xffffff), name, "field 'body.unit_fill' must be a list of 0xRRGGBB colours");
  need(json.channels && typeof json.channels === "object", name, "field 'channels' is missing");
  const ch = {};
  for (const [key, channel] of Object.entries(json.channels)) ch[key] = decodeChannel(name, key, channel, frames);
  const corners = body.corners.reduce((a, b) => a + b, 0);
  need(ch.outline, name, "channel 'outline' is missing");
  need(ch.outline.per === 2 * corners, name, `channel 'outline' has ${ch.outline.per} values per frame, expected ${2 * corners} (2 × the corners in 'body.corners')`);
  need(ch.center && ch.center.per === 2, name, "channel 'center' is missing or does not hold 2 values per frame");
  const units = cells.length;
  for (const key of ["area_ratio", "actuation", "touch", "angle"]) {
    if (ch[key]) need(ch[key].per === units, name, `channel '${key}' has ${ch[key].per} values per frame, expected ${units} (one per body cell)`);
  }
  if (ch.lidar) need(ch.lidar.per === rays.length, name, `channel 'lidar' has ${ch.lidar.per} values per frame, expected ${rays.length} (one per ray in 'body.rays')`);
  rays.forEach((r, i) => need(r && Number.isInteger(r.unit) && r.unit < body.corners.length && isNumber(r.angle) && isNumber(r.range), name, `field 'body.rays[${i}]' is not a {unit, angle, range} ray of a listed polygon`));
  if (ch.ball_xy) need(ch.ball_xy.per === 2 * balls.length, name, "channel 'ball_xy' does not match 'world.balls'");
  const polygonStart = [];
  let s = 0;
  for (const n of body.corners) { polygonStart.push(s); s += n; }
  const r = {
    name, title: json.title || name, frames, t0: json.t0, dt: json.frame_dt, side: json.side,
    terrain: world.terrain, obstacles, balls, cells, rays, corners: body.corners, polygonStart, ch, unitFill,
    damage: json.damage || null, graph: json.graph || null,
  };
  derive(r);
  return r;
}

// Quantities the page computes once: velocity over the last second, footprints, extents.
function derive(r) {
  const cx = (k) => r.ch.center.values[2 * k];
  const w = Math.max(1, Math.round(1 / r.dt));
  r.velocity = new Float64Array(r.frames);
  for (let k = 0; k < r.frames; k++) {
    const j = Math.max(0, k - w);
    r.velocity[k] = k === 0 ? 0 : (cx(k) - cx(j)) / ((k - j) * r.dt);
  }
  r.duration = (r.frames - 1) * r.dt;
  const o = r.ch.outline.values;
  let minX = Infinity, maxX = -Infinity, minY = Infinity, maxY = -Infinity;
  for (let j = 0; j < o.length; j += 2) {
    minX = Math.min(minX, o[j]); maxX = Math.max(maxX, o[j]);
    minY = Math.min(minY, o[j + 1]); maxY = Math.max(maxY, o[j + 1]);
  }
  r.extent = { minX, maxX, minY, maxY };
  const P = r.ch.outline.per;
  let bx0 = Infinity, bx1 = -Infinity, by0 = Infinity, by1 = -Infinity;
  for (let j = 0; j < P; j += 2) {
    bx0 = Math.min(bx0, o[j]); bx1 = Math.max(bx1, o[j]);
    by0 = Math.min(by0, o[j + 1]); by1 = Math.max(by1, o[j + 1]);
  }
  r.bodySize = Math.max(bx1 - bx0, by1 - by0, r.side);
  // Footprints: where a unit's lowest corner was when it started touching.
  r.footprints = [];
  const touch = r.ch.touch;
  if (touch) {
    for (let k = 0; k < r.frames; k++) {
      for (let u = 0; u < touch.per; u++) {
        const now = touch.values[k * touch.per + u] > 0.5;
        const before = k > 0 && touch.values[(k - 1) * touch.per + u] > 0.5;
        if (now && !before && u < r.corners.length) {
          let lx = 0, ly = Infinity;
          const start = r.polygonStart[u];
          for (let c = 0; c < r.corners[u]; c++) {
            const j = k * P + 2 * (start + c);
            if (o[j + 1] < ly) { ly = o[j + 1]; lx = o[j]; }
          }
          r.footprints.push({ frame: k, x: lx, y: ly });
        }
      }
    }
  }
}

// ---------------------------------------------------------------- labelling (a `vsrlab label` folder)

// The robots and classes of a labelling folder, and the choices made so far (kept in this browser).
const labelling = { data: null, byId: {}, choices: {}, key: "" };

async function loadLabelling() {
  try {
    const response = await fetch("api/labelling");
    if (!response.ok) return;
    labelling.data = await response.json();
  } catch (e) {
    return;
  }
  const items = labelling.data.items || [];
  for (const it of items) labelling.byId[it.id] = it;
  labelling.key = `vsrlab-viewer-labels-${items.length}:${location.host}`;
  labelling.choices = JSON.parse(localStorage.getItem(labelling.key) || "{}");
  if (labelling.data.prefill && Object.keys(labelling.choices).length === 0) {
    for (const it of items) labelling.choices[it.id] = { shape: it.proposal[0], behaviour: it.proposal[1] };
  }
  const save = document.createElement("button");
  save.id = "save-labels";
  save.textContent = "Save labels.csv";
  save.addEventListener("click", saveLabels);
  const progress = document.createElement("span");
  progress.id = "label-progress";
  document.querySelector("header").append(save, progress);
  labelProgress();
}

function labelProgress() {
  const items = labelling.data.items || [];
  const done = items.filter((it) => (labelling.choices[it.id] || {}).shape && (labelling.choices[it.id] || {}).behaviour).length;
  document.getElementById("label-progress").textContent = `${done} / ${items.length} labelled`;
}

// The morphology and behaviour choices under a pane whose replay is a labelled robot.
function labelBar(it) {
  const bar = document.createElement("div");
  bar.className = "labels";
  for (const [kind, classes, title] of [["shape", labelling.data.shapes, "morphology"], ["behaviour", labelling.data.behaviours, "behaviour"]]) {
    const label = document.createElement("label");
    const select = document.createElement("select");
    select.dataset.kind = kind;
    select.append(new Option("—", ""));
    for (const c of classes) select.append(new Option(c, c));
    select.value = (labelling.choices[it.id] || {})[kind] || "";
    select.addEventListener("change", () => {
      labelling.choices[it.id] = Object.assign({}, labelling.choices[it.id], { [kind]: select.value });
      localStorage.setItem(labelling.key, JSON.stringify(labelling.choices));
      labelProgress();
    });
    label.append(`${title} `, select);
    bar.append(label);
  }
  const v = it.velocity == null ? "–" : it.velocity.toFixed(2);
  const hint = document.createElement("span");
  hint.className = "hint";
  hint.textContent = `suggested: ${it.proposal[0]} / ${it.proposal[1]} · ${it.setting} run ${it.run} · velocity ${v} · voxels ${it.voxels}`;
  bar.append(hint);
  return bar;
}

function csvField(s) {
  s = String(s);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

// labels.csv as `vsrlab label`'s page writes it (robot paths relative to the labelling folder).
function labelsCsv() {
  const lines = ["robot,terrain,duration,transient,seed,shape,behaviour,id"];
  for (const it of labelling.data.items) {
    const c = labelling.choices[it.id] || {};
    lines.push([it.robot, it.terrain, it.duration, it.transient, it.seed, c.shape || "", c.behaviour || "", it.id].map(csvField).join(","));
  }
  return lines.join("\n") + "\n";
}

function saveLabels() {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([labelsCsv()], { type: "text/csv" }));
  a.download = "labels.csv";
  document.body.appendChild(a);
  a.click();
  a.remove();
}

// ---------------------------------------------------------------- panes

function addPane(replay, error, name) {
  const pane = { replay, name, colour: PANE_COLOURS[state.panes.length % PANE_COLOURS.length] };
  const el = document.createElement("div");
  el.className = "pane";
  el.style.setProperty("--pane-colour", pane.colour);
  const title = document.createElement("h2");
  title.textContent = replay ? replay.title : name;
  title.title = title.textContent;
  el.appendChild(title);
  if (replay) {
    const canvas = document.createElement("canvas");
    el.appendChild(canvas);
    pane.canvas = canvas;
    pane.ctx = canvas.getContext("2d");
    canvas.addEventListener("click", (e) => selectAt(pane, e));
    canvas.addEventListener("wheel", (e) => { e.preventDefault(); zoomBy(e.deltaY < 0 ? 0.1 : -0.1); }, { passive: false });
    if (replay.solid) {
      el.classList.add("solid");
      listenOrbit(pane);
    }
  } else {
    const p = document.createElement("div");
    p.className = "error";
    p.textContent = `Cannot show this replay.\n${error}`;
    el.appendChild(p);
  }
  if (replay && labelling.byId[name]) el.appendChild(labelBar(labelling.byId[name]));
  pane.el = el;
  document.getElementById("panes").appendChild(el);
  state.panes.push(pane);
  updateDuration();
  state.chartsDirty = true;
  return pane;
}

function removePane(name) {
  const i = state.panes.findIndex((p) => p.name === name);
  if (i < 0) return;
  state.panes[i].el.remove();
  if (state.selected && state.selected.pane === state.panes[i]) state.selected = null;
  state.panes.splice(i, 1);
  updateDuration();
  state.chartsDirty = true;
}

function updateDuration() {
  state.duration = Math.max(0, ...state.panes.filter((p) => p.replay).map((p) => p.replay.duration));
  const scrub = document.getElementById("scrub");
  scrub.max = String(state.duration || 1);
  setTime(Math.min(state.time, state.duration));
}

function loadText(text, name) {
  let replay = null, error = null;
  try {
    let json;
    try { json = JSON.parse(text); } catch (e) { throw new ReplayError(`${name}: not JSON (${e.message})`); }
    replay = readReplay(json, name);
  } catch (e) {
    error = e instanceof ReplayError ? e.message : `${name}: ${e}`;
  }
  return addPane(replay, error, name);
}

// Fetches a replay's text; the pane is added by the caller, in list order.
async function fetchReplay(url, name) {
  try {
    const response = await fetch(url);
    const text = await response.text();
    if (!response.ok) return { error: `${name}: the server answered ${response.status}: ${text}` };
    return { text };
  } catch (e) {
    return { error: `${name}: cannot load (${e})` };
  }
}

function addFetched(fetched, name) {
  return fetched.error ? addPane(null, fetched.error, name) : loadText(fetched.text, name);
}

// ---------------------------------------------------------------- drawing

function areaColour(ratio) {
  const mix = (a, b, t) => a.map((v, i) => Math.round(v + (b[i] - v) * t));
  const c = ratio <= 1 ? mix(RED, YELLOW, Math.min(1, Math.max(0, (ratio - 0.75) / 0.25)))
    : mix(YELLOW, GREEN, Math.min(1, Math.max(0, (ratio - 1) / 0.25)));
  return `rgba(${c[0]},${c[1]},${c[2]},0.5)`;
}

// Frame index and interpolation weight at the viewer's time (seconds from each replay's start).
function frameAt(r, t) {
  const f = Math.min(Math.max(t / r.dt, 0), r.frames - 1);
  const k = Math.min(Math.floor(f), r.frames - 1);
  return { k, a: k + 1 < r.frames ? f - k : 0 };
}

function value(channel, k, a, i) {
  const v = channel.values, per = channel.per;
  const x = v[k * per + i];
  return a > 0 ? x + (v[(k + 1) * per + i] - x) * a : x;
}

function groundY(terrain, x) {
  let lo = 0, hi = terrain.length - 1;
  if (x <= terrain[0][0]) return terrain[0][1];
  if (x >= terrain[hi][0]) return terrain[hi][1];
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (terrain[mid][0] <= x) lo = mid; else hi = mid;
  }
  const [x0, y0] = terrain[lo], [x1, y1] = terrain[hi];
  return x1 > x0 ? y0 + (y1 - y0) * (x - x0) / (x1 - x0) : y0;
}

// The pane's camera: world (x, y) to pixels.
function cameraOf(pane, k, a) {
  const r = pane.replay, canvas = pane.canvas;
  const w = canvas.width, h = canvas.height;
  let cx, cy, scale;
  if (state.follow) {
    cx = value(r.ch.center, k, a, 0);
    cy = value(r.ch.center, k, a, 1);
    scale = 0.3 * Math.min(w, h) / r.bodySize;
  } else {
    const e = r.extent;
    cx = (e.minX + e.maxX) / 2;
    cy = (e.minY + e.maxY) / 2;
    scale = 0.9 * Math.min(w / Math.max(e.maxX - e.minX, r.side), h / Math.max(e.maxY - e.minY, r.side));
  }
  scale *= state.zoom;
  return { w, h, cx, cy, scale, x: (x) => (x - cx) * scale + w / 2, y: (y) => h / 2 - (y - cy) * scale };
}

function polygonPath(ctx, cam, r, k, a, u) {
  const o = r.ch.outline, start = r.polygonStart[u];
  ctx.beginPath();
  for (let c = 0; c < r.corners[u]; c++) {
    const j = 2 * (start + c);
    const x = cam.x(value(o, k, a, j)), y = cam.y(value(o, k, a, j + 1));
    if (c === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
  }
  ctx.closePath();
}

function unitCentre(r, k, a, u) {
  const o = r.ch.outline, start = r.polygonStart[u], n = r.corners[u];
  let x = 0, y = 0;
  for (let c = 0; c < n; c++) {
    const j = 2 * (start + c);
    x += value(o, k, a, j); y += value(o, k, a, j + 1);
  }
  return [x / n, y / n];
}

function unitAngle(r, k, a, u) {
  if (r.ch.angle) return value(r.ch.angle, k, a, u);
  const o = r.ch.outline, j = 2 * r.polygonStart[u];
  if (r.corners[u] !== 4) return 0;
  const p = (c, d) => value(o, k, a, j + 2 * c + d);
  return Math.atan2(p(1, 1) - p(0, 1) + p(2, 1) - p(3, 1), p(1, 0) - p(0, 0) + p(2, 0) - p(3, 0));
}

function drawPane(pane) {
  const r = pane.replay, canvas = pane.canvas, ctx = pane.ctx;
  const dpr = window.devicePixelRatio || 1;
  const width = Math.round(canvas.clientWidth * dpr), height = Math.round(canvas.clientHeight * dpr);
  if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
  if (r.solid) return drawSolidPane(pane);
  const { k, a } = frameAt(r, state.time);
  const cam = cameraOf(pane, k, a);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, cam.w, cam.h);
  ctx.lineJoin = "round";
  const ov = state.overlays;
  const left = cam.cx - cam.w / 2 / cam.scale, right = cam.cx + cam.w / 2 / cam.scale;
  // Ground (a world without one, as EvoGym's, has only its obstacles).
  const t = r.terrain;
  if (t.length) {
    ctx.beginPath();
    ctx.moveTo(cam.x(t[0][0]), cam.h + 10);
    for (const p of t) ctx.lineTo(cam.x(p[0]), cam.y(p[1]));
    ctx.lineTo(cam.x(t[t.length - 1][0]), cam.h + 10);
    ctx.closePath();
    ctx.fillStyle = "rgb(180,180,180)";
    ctx.fill();
    ctx.strokeStyle = "#000";
    ctx.lineWidth = 1;
    ctx.stroke();
    if (ov.ticks) drawTicks(ctx, cam, r, left, right);
  }
  ctx.fillStyle = "rgb(150,150,150)";
  for (const poly of r.obstacles) {
    ctx.beginPath();
    poly.forEach((p, i) => (i ? ctx.lineTo(cam.x(p[0]), cam.y(p[1])) : ctx.moveTo(cam.x(p[0]), cam.y(p[1]))));
    ctx.closePath();
    ctx.fill();
  }
  if (ov.footprints && t.length) {
    ctx.fillStyle = "rgba(60,40,20,0.8)";
    for (const f of r.footprints) {
      if (f.frame > k) break;
      const x = cam.x(f.x), y = cam.y(groundY(r.terrain, f.x));
      ctx.beginPath();
      ctx.moveTo(x, y + 1); ctx.lineTo(x - 4, y + 8); ctx.lineTo(x + 4, y + 8);
      ctx.closePath();
      ctx.fill();
    }
  }
  if (ov.trail) {
    ctx.beginPath();
    const c = r.ch.center.values;
    for (let j = 0; j <= k; j++) {
      const x = cam.x(c[2 * j]), y = cam.y(c[2 * j + 1]);
      if (j === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    ctx.strokeStyle = "rgba(0,0,0,0.45)";
    ctx.lineWidth = 1.5;
    ctx.stroke();
  }
  drawBody(ctx, cam, r, k, a, pane);
  if (ov.lidar && r.ch.lidar) drawLidar(ctx, cam, r, k, a);
  drawBalls(ctx, cam, r, k, a);
  drawHud(ctx, r, k, a);
}

function drawTicks(ctx, cam, r, left, right) {
  const step = r.side;
  const x0 = r.ch.center.values[0];
  ctx.strokeStyle = "rgba(0,0,0,0.6)";
  ctx.fillStyle = "#333";
  ctx.font = "11px sans-serif";
  ctx.lineWidth = 1;
  const first = Math.ceil((left - x0) / step), last = Math.floor((right - x0) / step);
  if (last - first > 400) return;
  for (let i = first; i <= last; i++) {
    const x = x0 + i * step, px = cam.x(x), py = cam.y(groundY(r.terrain, x));
    const long = i % 10 === 0;
    ctx.beginPath(); ctx.moveTo(px, py); ctx.lineTo(px, py + (long ? 12 : 6)); ctx.stroke();
    if (long) ctx.fillText(`${(i * step).toFixed(0)}`, px + 2, py + 22);
  }
}

function drawBody(ctx, cam, r, k, a, pane) {
  const ov = state.overlays, units = r.cells.length;
  const pressure = r.ch.pressure ? value(r.ch.pressure, k, a, 0) : null;
  const time = r.t0 + (k + a) * r.dt;
  for (let u = 0; u < r.corners.length; u++) {
    polygonPath(ctx, cam, r, k, a, u);
    let fill;
    if (units === 0) {
      const p = pressure === null ? 0 : Math.min(1, Math.max(0, pressure));
      fill = ov.colours ? `rgba(${Math.round(40 + 190 * p)},${Math.round(90 - 50 * p)},${Math.round(230 - 190 * p)},0.45)` : "rgba(160,160,220,0.5)";
    } else if (ov.colours && u < r.unitFill.length) {
      fill = "#" + r.unitFill[u].toString(16).padStart(6, "0");
    } else {
      fill = ov.colours && r.ch.area_ratio ? areaColour(value(r.ch.area_ratio, k, a, u)) : "rgba(170,170,255,0.5)";
    }
    const broken = r.damage && time >= r.damage.time && r.damage.broken[u];
    ctx.fillStyle = broken ? "rgba(60,60,60,0.6)" : fill;
    ctx.fill();
    const touching = ov.touch && r.ch.touch && u < units && r.ch.touch.values[k * r.ch.touch.per + u] > 0.5;
    ctx.strokeStyle = touching ? "rgb(0,0,120)" : "rgb(0,0,255)";
    ctx.lineWidth = touching ? 3 : 1;
    ctx.stroke();
  }
  if (state.selected && state.selected.pane === pane) {
    polygonPath(ctx, cam, r, k, a, state.selected.unit);
    ctx.strokeStyle = "#e0e";
    ctx.lineWidth = 3;
    ctx.stroke();
  }
}

function drawLidar(ctx, cam, r, k, a) {
  ctx.strokeStyle = "rgb(255,0,0)";
  ctx.lineWidth = 1;
  r.rays.forEach((ray, i) => {
    const d = value(r.ch.lidar, k, a, i);
    const hit = d >= 0 && d < ray.range;
    const length = hit ? d : ray.range;
    const [x, y] = unitCentre(r, k, a, ray.unit);
    const dir = unitAngle(r, k, a, ray.unit) + ray.angle;
    const ex = x + Math.cos(dir) * length, ey = y + Math.sin(dir) * length;
    ctx.beginPath(); ctx.moveTo(cam.x(x), cam.y(y)); ctx.lineTo(cam.x(ex), cam.y(ey)); ctx.stroke();
    if (hit) { ctx.beginPath(); ctx.arc(cam.x(ex), cam.y(ey), Math.max(2, 0.25 * cam.scale), 0, 2 * Math.PI); ctx.stroke(); }
  });
}

function drawBalls(ctx, cam, r, k, a) {
  if (!r.ch.ball_xy) return;
  r.balls.forEach((radius, b) => {
    const x = value(r.ch.ball_xy, k, a, 2 * b), y = value(r.ch.ball_xy, k, a, 2 * b + 1);
    const angle = r.ch.ball_angle ? value(r.ch.ball_angle, k, a, b) : 0;
    ctx.beginPath(); ctx.arc(cam.x(x), cam.y(y), radius * cam.scale, 0, 2 * Math.PI);
    ctx.fillStyle = "rgba(230,60,60,0.9)"; ctx.fill();
    ctx.beginPath(); ctx.moveTo(cam.x(x), cam.y(y));
    ctx.lineTo(cam.x(x + Math.cos(angle) * radius), cam.y(y + Math.sin(angle) * radius));
    ctx.strokeStyle = "#fff"; ctx.stroke();
  });
}

function drawHud(ctx, r, k, a) {
  const x = value(r.ch.center, k, a, 0) - r.ch.center.values[0];
  const t = (k + a) * r.dt;
  const lines = [`t = ${(r.t0 + t).toFixed(2)} s`, `distance ${x >= 0 ? "+" : ""}${x.toFixed(1)} (${(x / r.side).toFixed(1)} voxels)`];
  if (t > 0) lines.push(`velocity ${(x / t).toFixed(2)} /s (last 1 s: ${r.velocity[k].toFixed(2)})`);
  if (r.ch.pressure) lines.push(`pressure ${value(r.ch.pressure, k, a, 0).toFixed(2)} p_max`);
  drawHudLines(ctx, lines);
}

// The HUD's lines in a box at the top left of a pane.
function drawHudLines(ctx, lines) {
  ctx.font = "13px sans-serif";
  ctx.fillStyle = "rgba(255,255,255,0.75)";
  ctx.fillRect(4, 4, 290, 6 + 17 * lines.length);
  ctx.fillStyle = "#000";
  lines.forEach((l, i) => ctx.fillText(l, 10, 20 + 17 * i));
}

// ---------------------------------------------------------------- 3D replays

// The look of 3D frames, the same as the PNG renderer's (crates/render/src/solid3d/) so the page
// and the videos look alike: palette, light, camera and floor.
const SOLID = {
  sky: [214, 230, 245],
  floorLight: [226, 226, 226],
  floorDark: [196, 196, 196],
  floorFar: [211, 211, 211], // the floor far away, where its squares fade
  fixedVoxel: [140, 140, 140], // walls, before shading
  voxel: [79, 155, 217], // a moving voxel at rest, before shading
  contracted: [222, 84, 84], // what actuation −1 tints it towards
  expanded: [92, 196, 92], // what actuation +1 tints it towards
  tint: 0.6, // how far full actuation moves the colour towards its extreme
  passable: [40, 90, 225], // a voxel voting "passable" (vote > 0)
  impassable: [220, 45, 45], // a voxel voting "impassable" (vote ≤ 0)
  votePale: [205, 205, 215], // what a vote of 0 tends to
  touchBorder: "rgb(250,205,0)", // the border of a voxel touching another (its touch sensor fires)
  ambient: 0.35, // light reaching a face whatever its direction
  outline: 0.55, // a face's outline is its colour times this
  light: normalise3([0.35, -0.55, 0.76]), // towards the light: above, in front, a little right
  azimuth: -60, // default direction of the camera from its target, degrees from +x (in front, right)
  elevation: 25, // default height of the camera above the target's plane, degrees
  minElevation: 5,
  maxElevation: 85,
  fov: 55, // field of view across the canvas's shorter side, degrees
  targetRow: 0.55, // canvas row of the target, as a fraction of the height
  margin: 1.4, // room around the framed sphere (1: it touches the edges)
  near: 0.02, // nearest depth drawn, as a fraction of the camera's distance
  fadeStart: 1.5, // depth (× the distance) where the floor starts to fade
  fadeFull: 4, // depth (× the distance) from where it shows only its far colour
  reach: 7, // half-side (× the distance) of the floor's squares drawn around the target
  maxSquares: 60, // most squares along a half-side (larger squares beyond)
  degreesPerPixel: 0.4, // orbit speed when dragging
};
const NO_TURN = [1, 0, 0, 0];

function add3(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
function sub3(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function scale3(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function cross3(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function length3(a) { return Math.sqrt(dot3(a, a)); }
function normalise3(a) { return scale3(a, 1 / length3(a)); }

// `v` turned by the unit quaternion q = (w, x, y, z): v + 2w (u × v) + 2 u × (u × v), u its vector part.
function rotate(q, v) {
  const u = [q[1], q[2], q[3]];
  const t = scale3(cross3(u, v), 2);
  return add3(add3(v, scale3(t, q[0])), cross3(u, t));
}

// The quaternion w, x, y, z normalised (the identity when all zero): interpolated ones are not unit.
function unitQuat(w, x, y, z) {
  const n = Math.sqrt(w * w + x * x + y * y + z * z);
  return n > 0 ? [w / n, x / n, y / n, z / n] : NO_TURN;
}

// Checks and decodes a 3D replay (channel `voxel_xyz`); throws ReplayError naming the field.
function readSolidReplay(json, name) {
  const frames = json.frames;
  const ch = {};
  for (const [key, channel] of Object.entries(json.channels)) ch[key] = decodeChannel(name, key, channel, frames);
  const xyz = ch.voxel_xyz;
  need(xyz.per % 3 === 0, name, `channel 'voxel_xyz' has ${xyz.per} values per frame, expected 3 per voxel`);
  const voxels = xyz.per / 3;
  for (const [key, width] of [["voxel_quat", 4], ["voxel_edge", 1], ["actuation", 1], ["vote", 1], ["touch", 1]]) {
    if (ch[key]) need(ch[key].per === width * voxels, name, `channel '${key}' has ${ch[key].per} values per frame, expected ${width * voxels} (${width} per voxel of 'voxel_xyz')`);
  }
  need(ch.center && ch.center.per === 2, name, "channel 'center' is missing or does not hold 2 values per frame");
  const world = json.world || {}, body = json.body || {};
  const fixed = world.fixed_voxels || [];
  need(Array.isArray(fixed), name, "field 'world.fixed_voxels' must be a list of [x, y, z] centres");
  fixed.forEach((p, i) => need(Array.isArray(p) && p.length === 3 && p.every(isNumber), name, `field 'world.fixed_voxels[${i}]' is not an [x, y, z] centre`));
  const unitFill = body.unit_fill || [];
  need(Array.isArray(unitFill) && unitFill.every((c) => Number.isInteger(c) && c >= 0 && c <= 0xffffff), name, "field 'body.unit_fill' must be a list of 0xRRGGBB colours");
  const r = {
    solid: true, name, title: json.title || name, frames, t0: json.t0, dt: json.frame_dt, side: json.side,
    floorZ: -json.side / 2, voxels, fixed, unitFill, ch, cells: [], corners: [], rays: [], damage: null, graph: null,
  };
  deriveSolid(r);
  return r;
}

// Quantities a 3D replay's page computes once: horizontal velocity over the last second, the
// body's size (framing when following) and the whole run's extent (framing when not).
function deriveSolid(r) {
  const c = r.ch.center.values, w = Math.max(1, Math.round(1 / r.dt));
  r.velocity = new Float64Array(r.frames);
  for (let k = 1; k < r.frames; k++) {
    const j = Math.max(0, k - w);
    r.velocity[k] = Math.hypot(c[2 * k] - c[2 * j], c[2 * k + 1] - c[2 * j + 1]) / ((k - j) * r.dt);
  }
  r.duration = (r.frames - 1) * r.dt;
  const xyz = r.ch.voxel_xyz.values, per = r.ch.voxel_xyz.per, cube = [r.side, r.side, r.side];
  let radius = r.side, height = r.side;
  const runLo = [Infinity, Infinity, Infinity], runHi = [-Infinity, -Infinity, -Infinity];
  for (let k = 0; k < r.frames; k++) {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let j = k * per; j < (k + 1) * per; j += 3) {
      for (let d = 0; d < 3; d++) { lo[d] = Math.min(lo[d], xyz[j + d]); hi[d] = Math.max(hi[d], xyz[j + d]); }
    }
    radius = Math.max(radius, length3(add3(sub3(hi, lo), cube)) / 2);
    height = Math.max(height, hi[2] + r.side / 2 - r.floorZ);
    for (let d = 0; d < 3; d++) { runLo[d] = Math.min(runLo[d], lo[d]); runHi[d] = Math.max(runHi[d], hi[d]); }
  }
  r.radius = radius; // the largest sphere around the body's bounding box at any frame
  r.targetZ = r.floorZ + height / 2; // the camera looks at half the body's greatest height
  r.square = r.side * Math.max(1, Math.round(radius / r.side)); // floor squares
  r.runCentre = scale3(add3(runLo, runHi), 0.5);
  r.runRadius = length3(add3(sub3(runHi, runLo), cube)) / 2;
}

// The pane's perspective camera: `distance` from `target` in the orbit's direction; projects world
// points (z up) to canvas pixels.
function solidCamera(target, distance, w, h) {
  const az = state.orbit.azimuth * Math.PI / 180, el = state.orbit.elevation * Math.PI / 180;
  const toEye = [Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el)];
  const forward = scale3(toEye, -1);
  const right = normalise3(cross3(forward, [0, 0, 1]));
  return {
    eye: add3(target, scale3(toEye, distance)), right, up: cross3(right, forward), forward, target, distance, el, w, h,
    focal: 0.5 * Math.min(w, h) / Math.tan(SOLID.fov * Math.PI / 360),
    cx: w / 2, cy: h * SOLID.targetRow, near: distance * SOLID.near,
  };
}

// The camera of a pane at frame k + a: following the body's centre, or framing the whole run.
function solidCameraOf(pane, k, a) {
  const r = pane.replay;
  const [x, y, radius] = state.follow
    ? [value(r.ch.center, k, a, 0), value(r.ch.center, k, a, 1), r.radius]
    : [r.runCentre[0], r.runCentre[1], r.runRadius];
  const distance = radius * SOLID.margin / Math.sin(SOLID.fov * Math.PI / 360) / state.zoom;
  return solidCamera([x, y, r.targetZ], distance, pane.canvas.width, pane.canvas.height);
}

// `p` in camera coordinates: x right, y up, z depth along the view direction.
function cameraSpace(cam, p) {
  const d = sub3(p, cam.eye);
  return [dot3(d, cam.right), dot3(d, cam.up), dot3(d, cam.forward)];
}

function pixelOf(cam, c) {
  return [cam.cx + cam.focal * c[0] / c[2], cam.cy - cam.focal * c[1] / c[2]];
}

// The polygon of world points in pixels, cut at the near plane (Sutherland–Hodgman against one
// plane); empty when it lies wholly behind it.
function projectPolygon(cam, corners) {
  const poly = corners.map((p) => cameraSpace(cam, p)), out = [];
  for (let i = 0; i < poly.length; i++) {
    const p = poly[i], q = poly[(i + 1) % poly.length];
    const pIn = p[2] >= cam.near, qIn = q[2] >= cam.near;
    if (pIn) out.push(pixelOf(cam, p));
    if (pIn !== qIn) {
      const t = (cam.near - p[2]) / (q[2] - p[2]);
      out.push(pixelOf(cam, add3(p, scale3(sub3(q, p), t))));
    }
  }
  return out;
}

// Canvas row of the horizon (where the floor meets the sky far away).
function horizonRow(cam) {
  return cam.cy - cam.focal * Math.tan(cam.el);
}

// Canvas row where the floor at height z is `depth` away: on a plane, depth depends on the row only.
function floorRow(cam, z, depth) {
  const v = (Math.sin(cam.el) - (cam.eye[2] - z) / depth) / Math.cos(cam.el);
  return cam.cy - cam.focal * v;
}

function rgb(c) {
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

// `c` times `factor`, rounded and clamped per channel.
function scaledColour(c, factor) {
  return c.map((v) => Math.min(255, Math.max(0, Math.round(v * factor))));
}

// `a` moved a fraction t (clamped to [0, 1]) towards `b`.
function mixColour(a, b, t) {
  t = Math.min(1, Math.max(0, t));
  return a.map((v, i) => Math.round(v + (b[i] - v) * t));
}

// Brightness of a face with outward unit normal n: ambient plus a Lambert term.
function brightness(n) {
  return SOLID.ambient + (1 - SOLID.ambient) * Math.max(0, dot3(n, SOLID.light));
}

// The colour of a vote in [−1, 1]: blue when > 0 ("passable"), red otherwise, paler near 0 (as
// the PNG renderer's `vote_color`).
function voteColour(vote) {
  const v = Number.isFinite(vote) ? Math.min(1, Math.max(-1, vote)) : 0;
  return mixColour(SOLID.votePale, v > 0 ? SOLID.passable : SOLID.impassable, 0.35 + 0.65 * Math.abs(v));
}

// Base colour of moving voxel v: its vote's colour where the replay has votes, else the
// replay's own fill where it gives one, else blue tinted red when contracting and green when
// expanding by its actuation in [−1, 1] (untinted blue with the colours overlay off).
function voxelColour(r, v, actuation, k) {
  if (!state.overlays.colours) return SOLID.voxel;
  if (r.ch.vote) return voteColour(r.ch.vote.values[k * r.voxels + v]);
  if (v < r.unitFill.length) { const c = r.unitFill[v]; return [c >> 16, (c >> 8) & 255, c & 255]; }
  const act = Math.min(1, Math.max(-1, actuation));
  return act < 0 ? mixColour(SOLID.voxel, SOLID.contracted, -act * SOLID.tint) : mixColour(SOLID.voxel, SOLID.expanded, act * SOLID.tint);
}

// Every cube at frame k + a: the moving voxels (unit = voxel index), then the fixed ones (unit −1).
function solidCubes(r, k, a) {
  const { voxel_xyz: xyz, voxel_quat: quat, voxel_edge: edge, actuation, touch } = r.ch;
  const cubes = [];
  for (let v = 0; v < r.voxels; v++) {
    const centre = [value(xyz, k, a, 3 * v), value(xyz, k, a, 3 * v + 1), value(xyz, k, a, 3 * v + 2)];
    const turn = quat ? unitQuat(value(quat, k, a, 4 * v), value(quat, k, a, 4 * v + 1), value(quat, k, a, 4 * v + 2), value(quat, k, a, 4 * v + 3)) : NO_TURN;
    const e = edge ? value(edge, k, a, v) : r.side;
    const colour = voxelColour(r, v, actuation ? value(actuation, k, a, v) : 0, k);
    const touching = state.overlays.touch && touch && touch.values[k * r.voxels + v] > 0.5;
    cubes.push({ centre, turn, edge: e > 0 ? e : r.side, colour, unit: v, border: touching ? SOLID.touchBorder : null });
  }
  for (const centre of r.fixed) cubes.push({ centre, turn: NO_TURN, edge: r.side, colour: SOLID.fixedVoxel, unit: -1 });
  return cubes;
}

// Appends to `out` the faces of `cube` turned towards the eye (back faces culled), each with its
// corners in order around it, its shaded fill and outline, and its distance from the eye.
function visibleFaces(cube, eye, out) {
  const h = cube.edge / 2;
  const axes = [rotate(cube.turn, [1, 0, 0]), rotate(cube.turn, [0, 1, 0]), rotate(cube.turn, [0, 0, 1])];
  const outline = cube.border || rgb(scaledColour(cube.colour, SOLID.outline));
  for (let i = 0; i < 6; i++) {
    const axis = i >> 1, normal = scale3(axes[axis], i % 2 === 0 ? -1 : 1);
    const centre = add3(cube.centre, scale3(normal, h));
    if (dot3(normal, sub3(eye, centre)) <= 0) continue;
    const u = scale3(axes[(axis + 1) % 3], h), v = scale3(axes[(axis + 2) % 3], h);
    const corners = [add3(add3(centre, u), v), add3(sub3(centre, u), v), sub3(sub3(centre, u), v), sub3(add3(centre, u), v)];
    out.push({
      corners, unit: cube.unit, distance: length3(sub3(centre, eye)),
      fill: rgb(scaledColour(cube.colour, brightness(normal))), outline, wide: Boolean(cube.border),
    });
  }
}

// The camera and the visible faces of a pane at the viewer's time, far to near, each with its
// pixels (the drawing and the click use the same).
function solidScene(pane) {
  const r = pane.replay;
  const { k, a } = frameAt(r, state.time);
  const cam = solidCameraOf(pane, k, a);
  const faces = [];
  for (const cube of solidCubes(r, k, a)) visibleFaces(cube, cam.eye, faces);
  faces.sort((p, q) => q.distance - p.distance);
  for (const f of faces) f.pixels = projectPolygon(cam, f.corners);
  return { k, a, cam, faces: faces.filter((f) => f.pixels.length >= 3) };
}

function pixelPath(ctx, pixels) {
  ctx.beginPath();
  pixels.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.closePath();
}

// Sky, the floor (a checkerboard on z = floorZ fading to one grey far away), the trail, then
// every visible face painted far to near, the selected voxel outlined, and the HUD.
function drawSolidPane(pane) {
  const r = pane.replay, ctx = pane.ctx;
  const { k, a, cam, faces } = solidScene(pane);
  ctx.lineJoin = "round";
  drawSolidFloor(ctx, cam, r);
  if (state.overlays.trail) drawSolidTrail(ctx, cam, r, k);
  const selected = state.selected && state.selected.pane === pane ? state.selected.unit : -1;
  for (const f of faces) {
    pixelPath(ctx, f.pixels);
    ctx.fillStyle = f.fill;
    ctx.fill();
    const chosen = f.unit >= 0 && f.unit === selected;
    ctx.strokeStyle = chosen ? "#e0e" : f.outline;
    ctx.lineWidth = chosen ? 2.5 : f.wide ? 2 : 1;
    ctx.stroke();
  }
  drawSolidHud(ctx, r, k, a);
}

function drawSolidFloor(ctx, cam, r) {
  ctx.fillStyle = rgb(SOLID.sky);
  ctx.fillRect(0, 0, cam.w, cam.h);
  const horizon = Math.max(0, Math.floor(horizonRow(cam)));
  ctx.fillStyle = rgb(SOLID.floorLight);
  ctx.fillRect(0, horizon, cam.w, cam.h - horizon);
  // the dark squares (the light ones are the floor's own colour), nearer than the full fade, in one path
  const reach = SOLID.reach * cam.distance, square = Math.max(r.square, reach / SOLID.maxSquares);
  const farthest = SOLID.fadeFull * cam.distance, z = r.floorZ, [tx, ty] = cam.target;
  ctx.beginPath();
  for (let i = Math.floor((tx - reach) / square); i <= Math.ceil((tx + reach) / square); i++) {
    for (let j = Math.floor((ty - reach) / square); j <= Math.ceil((ty + reach) / square); j++) {
      if (((i + j) & 1) === 0) continue;
      const corners = [[i, j], [i + 1, j], [i + 1, j + 1], [i, j + 1]].map(([x, y]) => [x * square, y * square, z]);
      if (corners.every((c) => dot3(sub3(c, cam.eye), cam.forward) > farthest)) continue;
      const pixels = projectPolygon(cam, corners);
      if (pixels.length < 3 || pixels.every(([x]) => x < 0) || pixels.every(([x]) => x > cam.w) || pixels.every(([, y]) => y > cam.h)) continue;
      pixels.forEach(([x, y], n) => (n ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      ctx.closePath();
    }
  }
  ctx.fillStyle = rgb(SOLID.floorDark);
  ctx.fill();
  // the fade: the far colour from the horizon, clearing towards where fading starts
  const start = floorRow(cam, z, SOLID.fadeStart * cam.distance), full = floorRow(cam, z, farthest);
  const bottom = Math.min(cam.h, Math.ceil(start));
  if (bottom > horizon && start > full) {
    const [cr, cg, cb] = SOLID.floorFar;
    const fade = ctx.createLinearGradient(0, full, 0, start);
    fade.addColorStop(0, `rgba(${cr},${cg},${cb},1)`);
    fade.addColorStop(1, `rgba(${cr},${cg},${cb},0)`);
    ctx.fillStyle = fade;
    ctx.fillRect(0, horizon, cam.w, bottom - horizon);
  }
}

// The path of the body's centre so far, on the floor.
function drawSolidTrail(ctx, cam, r, k) {
  const c = r.ch.center.values;
  ctx.beginPath();
  let pen = false;
  for (let j = 0; j <= k; j++) {
    const p = cameraSpace(cam, [c[2 * j], c[2 * j + 1], r.floorZ]);
    if (p[2] < cam.near) { pen = false; continue; }
    const [x, y] = pixelOf(cam, p);
    if (pen) ctx.lineTo(x, y); else ctx.moveTo(x, y);
    pen = true;
  }
  ctx.strokeStyle = "rgba(0,0,0,0.45)";
  ctx.lineWidth = 1.5;
  ctx.stroke();
}

// Time, horizontal distance of the body's centre from the start (m and voxel edges), velocity.
function drawSolidHud(ctx, r, k, a) {
  const c = r.ch.center.values;
  const d = Math.hypot(value(r.ch.center, k, a, 0) - c[0], value(r.ch.center, k, a, 1) - c[1]);
  const t = (k + a) * r.dt;
  const lines = [`t = ${(r.t0 + t).toFixed(2)} s`, `distance ${d.toFixed(3)} m (${(d / r.side).toFixed(1)} voxels)`];
  if (t > 0) lines.push(`velocity ${(d / t).toFixed(3)} m/s (last 1 s: ${r.velocity[k].toFixed(3)})`);
  if (r.ch.vote) {
    // the collective decision of the affordance study: passable when at least as many vote > 0
    const votes = r.ch.vote.values.subarray(k * r.voxels, (k + 1) * r.voxels);
    const yes = votes.filter((v) => v > 0).length, no = r.voxels - yes;
    lines.push(`votes: ${yes} passable, ${no} impassable → ${yes >= no ? "passable" : "impassable"}`);
  }
  drawHudLines(ctx, lines);
}

// Selects the voxel whose visible face is under the pointer (the nearest face there), not after a drag.
function selectSolidAt(pane, event) {
  if (pane.dragged) { pane.dragged = false; return; }
  const canvas = pane.canvas, rect = canvas.getBoundingClientRect();
  const px = (event.clientX - rect.left) * canvas.width / rect.width;
  const py = (event.clientY - rect.top) * canvas.height / rect.height;
  const { faces } = solidScene(pane);
  for (let i = faces.length - 1; i >= 0; i--) {
    pixelPath(pane.ctx, faces[i].pixels);
    if (!pane.ctx.isPointInPath(px, py)) continue;
    if (faces[i].unit < 0) return; // a wall
    state.selected = { pane, unit: faces[i].unit };
    listUnitChannels(pane.replay);
    state.chartsDirty = true;
    draw();
    return;
  }
}

// Dragging on a 3D pane orbits the camera of every 3D pane (azimuth, and elevation within
// 5–85°); a double click returns to the default view.
function listenOrbit(pane) {
  const canvas = pane.canvas;
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => {
    if (e.button !== 0) return;
    drag = { x: e.clientX, y: e.clientY, moved: 0 };
    pane.dragged = false;
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    drag.moved += Math.abs(dx) + Math.abs(dy);
    if (drag.moved > 3) pane.dragged = true;
    orbitBy(-dx * SOLID.degreesPerPixel, dy * SOLID.degreesPerPixel);
  });
  const end = () => { drag = null; };
  canvas.addEventListener("pointerup", end);
  canvas.addEventListener("pointercancel", end);
  canvas.addEventListener("dblclick", () => {
    state.orbit.azimuth = SOLID.azimuth;
    state.orbit.elevation = SOLID.elevation;
    draw();
  });
}

function orbitBy(dAzimuth, dElevation) {
  const o = state.orbit;
  o.azimuth = ((((o.azimuth + dAzimuth) % 360) + 540) % 360) - 180; // within [−180, 180)
  o.elevation = Math.min(SOLID.maxElevation, Math.max(SOLID.minElevation, o.elevation + dElevation));
  draw();
}

// ---------------------------------------------------------------- charts

const chartCache = {};

function chartFrame(canvas, title, tMax, yMin, yMax) {
  const dpr = window.devicePixelRatio || 1;
  const width = Math.round(canvas.clientWidth * dpr), height = Math.round(canvas.clientHeight * dpr);
  if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
  const ctx = canvas.getContext("2d");
  const m = { l: 46, r: 8, t: 18, b: 20 };
  const w = canvas.width - m.l - m.r, h = canvas.height - m.t - m.b;
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#000"; ctx.font = "12px sans-serif";
  ctx.fillText(title, m.l, 13);
  if (yMax - yMin < 1e-9) { yMax += 1; yMin -= 1; }
  const X = (t) => m.l + w * t / Math.max(tMax, 1e-9);
  const Y = (v) => m.t + h * (1 - (v - yMin) / (yMax - yMin));
  ctx.strokeStyle = "#999"; ctx.lineWidth = 1;
  ctx.strokeRect(m.l, m.t, w, h);
  ctx.fillStyle = "#444"; ctx.font = "10px sans-serif";
  ctx.fillText(yMax.toFixed(2), 2, m.t + 8);
  ctx.fillText(yMin.toFixed(2), 2, m.t + h);
  ctx.fillText("0 s", m.l, m.t + h + 14);
  ctx.fillText(`${tMax.toFixed(1)} s`, m.l + w - 30, m.t + h + 14);
  if (yMin < 0 && yMax > 0) { ctx.strokeStyle = "#ddd"; ctx.beginPath(); ctx.moveTo(m.l, Y(0)); ctx.lineTo(m.l + w, Y(0)); ctx.stroke(); }
  return { ctx, X, Y, m, w, h };
}

function plotSeries(f, r, series, colour, dash) {
  const { ctx, X, Y } = f;
  ctx.beginPath();
  for (let k = 0; k < r.frames; k++) {
    const x = X(k * r.dt), y = Y(series(k));
    if (k === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
  }
  ctx.setLineDash(dash ? [4, 3] : []);
  ctx.strokeStyle = colour; ctx.lineWidth = 1.2; ctx.stroke();
  ctx.setLineDash([]);
}

function renderCharts() {
  const shown = state.panes.filter((p) => p.replay);
  const vCanvas = document.getElementById("velocity-chart");
  let lo = 0, hi = 0;
  for (const p of shown) for (const v of p.replay.velocity) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  const f = chartFrame(vCanvas, "velocity over the last 1 s (units/s), one line per replay", state.duration, lo, hi);
  for (const p of shown) plotSeries(f, p.replay, (k) => p.replay.velocity[k], p.colour, false);
  chartCache.velocity = { image: f.ctx.getImageData(0, 0, vCanvas.width, vCanvas.height), f };
  const uCanvas = document.getElementById("voxel-chart");
  const sel = state.selected;
  const chosen = sel && state.unitChannel && sel.pane.replay.ch[state.unitChannel];
  if (chosen) {
    // any per-unit channel a robot kind or brain recorded, scaled to its own range
    const r = sel.pane.replay, u = sel.unit, c = chosen;
    const series = (k) => c.values[k * c.per + u];
    let lo = Infinity, hi = -Infinity;
    for (let k = 0; k < r.frames; k++) { lo = Math.min(lo, series(k)); hi = Math.max(hi, series(k)); }
    if (!(hi > lo)) { lo -= 1; hi += 1; }
    const g = chartFrame(uCanvas, `unit ${u} of ${r.title}: ${state.unitChannel}`, state.duration, lo, hi);
    plotSeries(g, r, series, sel.pane.colour, false);
    chartCache.voxel = { image: g.ctx.getImageData(0, 0, uCanvas.width, uCanvas.height), f: g };
  } else if (sel && sel.pane.replay.ch.actuation) {
    const r = sel.pane.replay, u = sel.unit, cell = r.cells[u];
    const title = r.solid ? `voxel ${u} of ${r.title}: actuation`
      : `voxel (${cell[0]}, ${cell[1]}) of ${r.title}: actuation (solid), area ratio − 1 (dashed)`;
    const g = chartFrame(uCanvas, title, state.duration, -1, 1);
    plotSeries(g, r, (k) => r.ch.actuation.values[k * r.ch.actuation.per + u], sel.pane.colour, false);
    if (r.ch.area_ratio) plotSeries(g, r, (k) => r.ch.area_ratio.values[k * r.ch.area_ratio.per + u] - 1, "#555", true);
    chartCache.voxel = { image: g.ctx.getImageData(0, 0, uCanvas.width, uCanvas.height), f: g };
  } else {
    const g = chartFrame(uCanvas, "click a voxel to plot its actuation and area ratio", state.duration, -1, 1);
    chartCache.voxel = { image: g.ctx.getImageData(0, 0, uCanvas.width, uCanvas.height), f: g };
  }
  state.chartsDirty = false;
}

function drawCharts() {
  if (state.chartsDirty) renderCharts();
  for (const c of [chartCache.velocity, chartCache.voxel]) {
    if (!c) continue;
    const { ctx, X, m, h } = c.f;
    ctx.putImageData(c.image, 0, 0);
    ctx.strokeStyle = "#e0e"; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(X(state.time), m.t); ctx.lineTo(X(state.time), m.t + h); ctx.stroke();
  }
}

// ---------------------------------------------------------------- interaction

function selectAt(pane, event) {
  if (pane.replay.solid) return selectSolidAt(pane, event);
  const r = pane.replay, canvas = pane.canvas;
  const rect = canvas.getBoundingClientRect();
  const px = (event.clientX - rect.left) * canvas.width / rect.width;
  const py = (event.clientY - rect.top) * canvas.height / rect.height;
  const { k, a } = frameAt(r, state.time);
  const cam = cameraOf(pane, k, a);
  for (let u = 0; u < r.cells.length && u < r.corners.length; u++) {
    polygonPath(pane.ctx, cam, r, k, a, u);
    if (pane.ctx.isPointInPath(px, py)) {
      state.selected = { pane, unit: u };
      listUnitChannels(r);
      state.chartsDirty = true;
      draw();
      return;
    }
  }
}

// The per-unit channels of the selected robot's replay, offered in the unit chart's menu: every
// channel with one value per unit, whatever kind or brain recorded it.
function listUnitChannels(r) {
  const menu = document.getElementById("unit-channel");
  const units = r.solid ? r.voxels : r.corners.length;
  const names = Object.keys(r.ch).filter((n) => !["outline", "center"].includes(n) && r.ch[n].per === units).sort();
  menu.replaceChildren(new Option("actuation and area ratio", ""), ...names.map((n) => new Option(n, n)));
  if (!names.includes(state.unitChannel)) state.unitChannel = "";
  menu.value = state.unitChannel;
}

function setTime(t) {
  state.time = Math.min(Math.max(t, 0), state.duration);
  document.getElementById("scrub").value = String(state.time);
  document.getElementById("time").textContent = `${state.time.toFixed(2)} s`;
}

function setPlaying(on) {
  if (on && state.time >= state.duration) setTime(0);
  state.playing = on && state.duration > 0;
  document.getElementById("play").textContent = state.playing ? "❚❚ pause" : "▶ play";
  if (state.playing) { stats.playedFrames = 0; stats.playStart = performance.now(); stats.drawMs = 0; stats.drawn = 0; stats.maxDrawMs = 0; }
}

function zoomBy(d) {
  const z = document.getElementById("zoom");
  z.value = String(Math.min(2, Math.max(-2, Number(z.value) + d)));
  state.zoom = Math.pow(2, Number(z.value));
  draw();
}

function frameStep() {
  const dts = state.panes.filter((p) => p.replay).map((p) => p.replay.dt);
  return dts.length ? Math.min(...dts) : 1 / 30;
}

function draw() {
  const start = performance.now();
  for (const p of state.panes) if (p.replay) drawPane(p);
  drawCharts();
  const ms = performance.now() - start;
  stats.drawMs += ms; stats.drawn += 1; stats.maxDrawMs = Math.max(stats.maxDrawMs, ms);
}

let last = null;
function loop(now) {
  if (state.playing) {
    if (last !== null) setTime(state.time + (now - last) / 1000 * state.speed);
    stats.playedFrames += 1;
    stats.playEnd = now;
    if (state.time >= state.duration) setPlaying(false);
  }
  last = now;
  draw();
  requestAnimationFrame(loop);
}

function showMessage(text) {
  const m = document.getElementById("message");
  m.textContent = text;
  m.hidden = !text;
}

async function start() {
  document.getElementById("play").addEventListener("click", () => setPlaying(!state.playing));
  document.getElementById("scrub").addEventListener("input", (e) => { setTime(Number(e.target.value)); draw(); });
  document.getElementById("speed").addEventListener("change", (e) => { state.speed = Number(e.target.value); });
  document.getElementById("follow").addEventListener("change", (e) => { state.follow = e.target.checked; draw(); });
  document.getElementById("unit-channel").addEventListener("change", (e) => { state.unitChannel = e.target.value; state.chartsDirty = true; draw(); });
  document.getElementById("zoom").addEventListener("input", (e) => { state.zoom = Math.pow(2, Number(e.target.value)); draw(); });
  for (const key of Object.keys(state.overlays)) {
    document.getElementById(`ov-${key}`).addEventListener("change", (e) => { state.overlays[key] = e.target.checked; draw(); });
  }
  document.getElementById("open").addEventListener("change", async (e) => {
    for (const file of e.target.files) loadText(await file.text(), file.name);
    draw();
  });
  window.addEventListener("keydown", (e) => {
    if (e.target instanceof HTMLInputElement && e.target.type !== "checkbox" && e.target.type !== "range") return;
    if (e.key === " ") { e.preventDefault(); setPlaying(!state.playing); }
    else if (e.key === "ArrowRight") { setTime(state.time + frameStep()); draw(); }
    else if (e.key === "ArrowLeft") { setTime(state.time - frameStep()); draw(); }
    else if (e.key === "Home") { setTime(0); draw(); }
    else if (e.key === "End") { setTime(state.duration); draw(); }
  });
  window.addEventListener("resize", () => { state.chartsDirty = true; draw(); });
  requestAnimationFrame(loop);
  await loadLabelling();
  let list = [];
  try {
    const response = await fetch("api/replays");
    if (response.ok) list = await response.json();
  } catch (e) {
    showMessage("No server: open replay files with “open files…”.");
  }
  const box = document.getElementById("replays");
  if (list.length === 0) document.getElementById("list-label").hidden = true;
  const loads = [];
  for (const entry of list) {
    const label = document.createElement("label");
    const check = document.createElement("input");
    check.type = "checkbox";
    check.checked = entry.shown;
    check.dataset.name = entry.name;
    check.addEventListener("change", async () => {
      if (check.checked) addFetched(await fetchReplay(entry.url, entry.name), entry.name); else removePane(entry.name);
      draw();
    });
    label.append(check, ` ${entry.name} `);
    box.appendChild(label);
    if (entry.shown) loads.push(fetchReplay(entry.url, entry.name).then((f) => ({ f, name: entry.name })));
  }
  for (const { f, name } of await Promise.all(loads)) addFetched(f, name);
  draw();
  window.viewer.ready = true;
}

// ---------------------------------------------------------------- live monitor

// An experiment folder served by `vsrlab view OUT` (docs/viewer.md): each run's curves, progress
// and ETA, polled every `interval` ms, and the best robot so far of each followed run, reloaded
// when a newer one lands.
const monitor = { data: null, interval: 2000, polls: 0, stamps: {}, follow: {}, loading: false };

function humanSeconds(s) {
  if (s === null || s === undefined || !isFinite(s)) return "–";
  if (s < 60) return `${Math.round(s)} s`;
  if (s < 3600) return `${Math.floor(s / 60)} min ${Math.round(s % 60)} s`;
  return `${Math.floor(s / 3600)} h ${Math.round((s % 3600) / 60)} min`;
}

function fitnessText(v) {
  return v === null || v === undefined || !isFinite(v) ? "–" : Number(v).toPrecision(4);
}

function monitorRuns() {
  const out = [];
  (monitor.data ? monitor.data.experiments : []).forEach((e, ei) => e.runs.forEach((r) => out.push({ e, ei, r })));
  return out;
}

function bestPaneName(e, r) { return `${e.name} ${r.name} best so far`; }

function renderMonitorLines() {
  const box = document.getElementById("monitor-lines");
  box.replaceChildren();
  let k = 0;
  for (const [ei, e] of monitor.data.experiments.entries()) {
    const head = document.createElement("div");
    head.className = "experiment";
    const eta = e.eta === null ? "" : ` · ETA ${humanSeconds(e.eta)}`;
    head.textContent = `${e.name}${eta}`;
    box.appendChild(head);
    for (const r of e.runs) {
      const line = document.createElement("div");
      line.className = "run";
      line.dataset.run = `${ei}/${r.run}`;
      const swatch = document.createElement("span");
      swatch.className = "swatch";
      swatch.style.background = PANE_COLOURS[k++ % PANE_COLOURS.length];
      const text = document.createElement("span");
      text.className = "text";
      const eta = r.eta === null ? "" : ` · ETA ${humanSeconds(r.eta)}`;
      text.textContent = r.state === "waiting" ? `${r.name}: waiting`
        : `${r.name}: ${r.state} · generation ${r.generation} · ${r.evaluations} evaluations · best ${fitnessText(r.best)} · ${Math.round(100 * r.fraction)}%${eta}`;
      const follow = document.createElement("label");
      const check = document.createElement("input");
      check.type = "checkbox";
      check.checked = !!monitor.follow[`${ei}/${r.run}`];
      check.disabled = r.best_stamp === null;
      check.addEventListener("change", () => {
        monitor.follow[`${ei}/${r.run}`] = check.checked;
        if (!check.checked) { removePane(bestPaneName(e, r)); delete monitor.stamps[`${ei}/${r.run}`]; draw(); }
        followBest();
      });
      follow.append(check, " watch best so far");
      line.append(swatch, text, follow);
      box.appendChild(line);
    }
  }
}

function renderMonitorChart() {
  const canvas = document.getElementById("monitor-chart");
  const runs = monitorRuns();
  const values = [];
  let xMax = 1;
  for (const { r } of runs) for (const [x, b, m] of r.curve) {
    xMax = Math.max(xMax, x);
    for (const v of [b, m]) if (v !== null && isFinite(v)) values.push(v);
  }
  const yMin = values.length ? Math.min(...values) : 0, yMax = values.length ? Math.max(...values) : 1;
  const f = chartFrame(canvas, "fitness per run: best so far (solid), population median (dashed)", xMax, yMin, yMax);
  const { ctx, X, Y, m, w, h } = f;
  ctx.fillStyle = "#fff"; ctx.fillRect(m.l, m.t + h + 2, w, 16);
  ctx.fillStyle = "#444"; ctx.font = "10px sans-serif";
  ctx.fillText("0", m.l, m.t + h + 14);
  ctx.fillText(`${xMax} evaluations`, m.l + w - 90, m.t + h + 14);
  runs.forEach(({ r }, k) => {
    for (const [column, dash] of [[1, false], [2, true]]) {
      ctx.beginPath();
      let open = false;
      for (const point of r.curve) {
        const v = point[column];
        if (v === null || !isFinite(v)) { open = false; continue; }
        if (open) ctx.lineTo(X(point[0]), Y(v)); else ctx.moveTo(X(point[0]), Y(v));
        open = true;
      }
      ctx.setLineDash(dash ? [4, 3] : []);
      ctx.strokeStyle = PANE_COLOURS[k % PANE_COLOURS.length]; ctx.lineWidth = 1.5; ctx.stroke();
      ctx.setLineDash([]);
    }
  });
}

// Loads the best so far of every followed run whose best changed since it was shown.
async function followBest() {
  if (monitor.loading) return;
  monitor.loading = true;
  try {
    for (const { e, ei, r } of monitorRuns()) {
      const key = `${ei}/${r.run}`;
      if (!monitor.follow[key] || r.best_stamp === null || monitor.stamps[key] === r.best_stamp) continue;
      const fetched = await fetchReplay(`live/${ei}/${r.run}`, bestPaneName(e, r));
      const time = state.time;
      removePane(bestPaneName(e, r));
      addFetched(fetched, bestPaneName(e, r));
      setTime(time);
      monitor.stamps[key] = r.best_stamp;
      draw();
    }
  } finally {
    monitor.loading = false;
  }
}

async function pollMonitor() {
  let response;
  try { response = await fetch("api/monitor"); } catch (e) { return; }
  if (!response.ok) return;
  const first = monitor.data === null;
  monitor.data = await response.json();
  monitor.polls += 1;
  if (first) {
    // follow the first run that is running, else the first with a best
    const runs = monitorRuns();
    const pick = runs.find(({ r }) => r.state === "running") || runs.find(({ r }) => r.best_stamp !== null) || runs[0];
    if (pick) monitor.follow[`${pick.ei}/${pick.r.run}`] = true;
  }
  document.getElementById("monitor").hidden = false;
  renderMonitorLines();
  renderMonitorChart();
  await followBest();
  setTimeout(pollMonitor, monitor.interval);
}

window.viewer = { state, stats, setTime, setPlaying, draw, ready: false, readReplay, monitor };
start().then(pollMonitor);
