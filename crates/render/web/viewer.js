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
  const world = json.world, body = json.body;
  need(world && Array.isArray(world.terrain) && world.terrain.length >= 2, name, "field 'world.terrain' must be a list of at least 2 points");
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
  const { k, a } = frameAt(r, state.time);
  const cam = cameraOf(pane, k, a);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, cam.w, cam.h);
  ctx.lineJoin = "round";
  const ov = state.overlays;
  const left = cam.cx - cam.w / 2 / cam.scale, right = cam.cx + cam.w / 2 / cam.scale;
  // Ground.
  ctx.beginPath();
  const t = r.terrain;
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
  ctx.fillStyle = "rgb(150,150,150)";
  for (const poly of r.obstacles) {
    ctx.beginPath();
    poly.forEach((p, i) => (i ? ctx.lineTo(cam.x(p[0]), cam.y(p[1])) : ctx.moveTo(cam.x(p[0]), cam.y(p[1]))));
    ctx.closePath();
    ctx.fill();
  }
  if (ov.footprints) {
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
  ctx.font = "13px sans-serif";
  ctx.fillStyle = "rgba(255,255,255,0.75)";
  ctx.fillRect(4, 4, 290, 6 + 17 * lines.length);
  ctx.fillStyle = "#000";
  lines.forEach((l, i) => ctx.fillText(l, 10, 20 + 17 * i));
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
    const g = chartFrame(uCanvas, `voxel (${cell[0]}, ${cell[1]}) of ${r.title}: actuation (solid), area ratio − 1 (dashed)`, state.duration, -1, 1);
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
  const units = r.corners.length;
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

window.viewer = { state, stats, setTime, setPlaying, draw, ready: false, readReplay };
start();
