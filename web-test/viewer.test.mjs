// Browser test of `vsrlab view` (docs/viewer.md): Playwright drives Debian's chromium, headless.
// It writes replays with `vsrlab simulate --replay`, serves them, plays, scrubs, toggles overlays,
// clicks a voxel, orbits a 3D replay's camera and checks the drawn pixels; screenshots go to
// $VIEWER_SCREENSHOTS (default web-test/screenshots) to be looked at. Run by web-test/run.sh.
import { chromium } from "playwright-core";
import { spawn, execFileSync } from "node:child_process";
import { mkdtempSync, writeFileSync, statSync, mkdirSync, readFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import assert from "node:assert/strict";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const bin = process.env.VSRLAB_BIN || join(root, "target/debug/vsrlab");
const browserPath = process.env.CHROMIUM || "/usr/bin/chromium";
const shots = process.env.VIEWER_SCREENSHOTS || join(root, "web-test/screenshots");
mkdirSync(shots, { recursive: true });
const work = mkdtempSync(join(tmpdir(), "vsrlab-viewer-"));
const results = [];

// Every server and run this test starts is stopped when the test ends, however it ends: a failed
// check throws, and the servers must not outlive it.
const children = new Set();
process.on("exit", () => {
  for (const child of children) {
    if (child.exitCode === null && child.signalCode === null) child.kill("SIGKILL");
  }
});
function started(child) {
  children.add(child);
  return child;
}

function check(name, cond, detail) {
  results.push(`${cond ? "ok  " : "FAIL"} ${name}${detail ? `: ${detail}` : ""}`);
  console.log(results[results.length - 1]);
  assert.ok(cond, `${name}: ${detail}`);
}

function vsrlab(...args) {
  return execFileSync(bin, args, { cwd: root, encoding: "utf8" });
}

// Replays: the shipped evolved biped (30 s), a 10×10 block (10 s), and two bad files.
const walk = join(work, "walk.replay.json");
const box = join(work, "box.replay.json");
vsrlab("simulate", "--robot", "examples/biped-distributed.robot.json", "--duration", "30", "--replay", walk);
vsrlab("simulate", "--body", Array(10).fill("##########").join("/"), "--duration", "10", "--replay", box);
// Other kinds, listed but not shown at first: a PSA in its cage, a robot with lidar, a graph brain.
const psa = join(work, "psa.replay.json");
const sighted = join(work, "sighted.replay.json");
vsrlab("simulate", "--body", "psa", "--task", "escape", "--duration", "5", "--replay", psa);
vsrlab("simulate", "--sensors", "spinedTouchSighted-f-f-0", "--brain", "graph:10", "--task", "locomotion:hilly-1-10", "--duration", "5", "--replay", sighted);
const walkBytes = statSync(walk).size;
check("a 30 s biped replay is under 1 MB", walkBytes < 1e6, `${(walkBytes / 1e3).toFixed(0)} kB`);
const broken = JSON.parse(readFileSync(walk, "utf8"));
broken.channels.outline.data.pop();
writeFileSync(join(work, "broken.replay.json"), JSON.stringify(broken));
writeFileSync(join(work, "text.replay.json"), "this is not a replay");

// Starts `vsrlab view args…`; resolves to the server process, its output so far and its URL.
function startViewer(args) {
  const proc = started(spawn(bin, ["view", ...args, "--port", "0"], { cwd: root }));
  const out = { text: "" };
  proc.stdout.on("data", (d) => { out.text += d; });
  proc.stderr.on("data", (d) => { out.text += d; });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`no URL from vsrlab view: ${out.text}`)), 15000);
    const look = () => {
      const m = out.text.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) { clearTimeout(timer); resolve({ proc, out, url: m[0] }); } else setTimeout(look, 50);
    };
    look();
  });
}

const viewer = await startViewer([walk, box, join(work, "broken.replay.json"), join(work, "text.replay.json"), psa, sighted]);
const { proc: server, out: serverOutput, url } = viewer;
check("the server listens on 127.0.0.1 only", url.startsWith("http://127.0.0.1:"), url);
for (const outside of ["../Cargo.toml", "replay/9", "crates/render/web/viewer.js", "..%2f..%2fetc/passwd"]) {
  const r = await fetch(url + outside);
  check(`the server refuses /${outside}`, r.status === 404, `status ${r.status}`);
}

const browser = await chromium.launch({
  executablePath: browserPath,
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const page = await browser.newPage({ viewport: { width: 1300, height: 1000 } });
const consoleErrors = [];
page.on("pageerror", (e) => consoleErrors.push(String(e)));
await page.goto(url);
await page.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
const panes = await page.locator(".pane").count();
check("four panes, one per replay shown (four of six)", panes === 4, `${panes}`);
const errors = await page.locator(".pane .error").allTextContents();
check("a damaged replay gets a message naming the field", errors.some((t) => t.includes("channel 'outline'") && t.includes("expected")), JSON.stringify(errors));
check("a file that is not JSON gets a message", errors.some((t) => t.includes("not JSON")), JSON.stringify(errors));

// Pixels of the first pane's canvas: the centroid of voxel-coloured pixels, and raw data.
async function robotPixels(index = 0) {
  return page.evaluate((i) => {
    const c = document.querySelectorAll(".pane canvas")[i];
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0, sx = 0, sy = 0;
    for (let p = 0; p < d.length; p += 4) {
      const [r, g, b] = [d[p], d[p + 1], d[p + 2]];
      if (b < 150 && Math.max(r, g) >= 200) { n++; sx += (p / 4) % c.width; sy += Math.floor(p / 4 / c.width); }
    }
    return { n, x: n ? sx / n : NaN, y: n ? sy / n : NaN, width: c.width, height: c.height, rect: c.getBoundingClientRect().toJSON() };
  }, index);
}
async function canvasData(index = 0) {
  return page.evaluate((i) => Array.from(document.querySelectorAll(".pane canvas")[i].getContext("2d").getImageData(0, 0, 600, 300).data), index);
}
const scrubTo = (t) => page.evaluate((t) => { const s = document.getElementById("scrub"); s.value = String(t); s.dispatchEvent(new Event("input")); }, t);

// A fixed camera: the walking robot's drawn centre moves right from start to end.
await page.uncheck("#follow");
await scrubTo(0);
const atStart = await robotPixels();
await page.screenshot({ path: join(shots, "start-fixed-camera.png") });
await page.keyboard.press("End");
const atEnd = await robotPixels();
await page.screenshot({ path: join(shots, "end-fixed-camera.png") });
check("the robot is drawn at the start", atStart.n > 50, `${atStart.n} voxel pixels`);
check("scrubbing to the end moves the drawn robot right", atEnd.x > atStart.x + 0.5 * atStart.width,
  `centre x ${atStart.x.toFixed(0)} → ${atEnd.x.toFixed(0)} px of ${atStart.width}`);

// Playing advances time with the wall clock.
await page.check("#follow");
await scrubTo(0);
await page.click("#play");
await page.waitForTimeout(1500);
await page.click("#play");
const played = await page.evaluate(() => window.viewer.state.time);
check("play advances the time at 1×", played > 1.0 && played < 2.5, `${played.toFixed(2)} s after 1.5 s`);

// Overlays: turning the area colours off changes the robot's pixels; turning them on restores them.
await scrubTo(12);
const withColours = await canvasData();
await page.screenshot({ path: join(shots, "middle-follow.png") });
await page.uncheck("#ov-colours");
const without = await canvasData();
await page.screenshot({ path: join(shots, "middle-no-colours.png") });
let changed = 0;
for (let i = 0; i < withColours.length; i += 4) if (withColours[i + 2] !== without[i + 2]) changed++;
check("the area-colour toggle changes pixels", changed > 500, `${changed} pixels changed`);
await page.check("#ov-colours");
const back = await canvasData();
check("toggling it back restores the frame", back.every((v, i) => v === withColours[i]), "");
await page.uncheck("#ov-trail");
const noTrail = await canvasData();
let trailPixels = 0;
for (let i = 0; i < back.length; i += 4) if (back[i] !== noTrail[i]) trailPixels++;
check("the trail toggle changes pixels", trailPixels > 20, `${trailPixels} pixels`);
await page.check("#ov-trail");

// Clicking a voxel selects it and plots its actuation.
const now = await robotPixels();
await page.mouse.click(now.rect.x + now.x * now.rect.width / now.width, now.rect.y + now.y * now.rect.height / now.height);
const selected = await page.evaluate(() => window.viewer.state.selected && window.viewer.state.selected.unit);
check("clicking the robot selects a voxel", Number.isInteger(selected), `voxel ${selected}`);

// The unit chart offers every per-unit channel of the replay and plots the one chosen.
const offered = await page.locator("#unit-channel option").allTextContents();
check("the unit chart offers the replay's per-unit channels", ["actuation", "area_ratio", "touch"].every((n) => offered.includes(n)), JSON.stringify(offered));
const chartBefore = await page.evaluate(() => Array.from(document.getElementById("voxel-chart").getContext("2d").getImageData(0, 0, 900, 150).data));
await page.selectOption("#unit-channel", "touch");
const chartAfter = await page.evaluate(() => Array.from(document.getElementById("voxel-chart").getContext("2d").getImageData(0, 0, 900, 150).data));
const chartChanged = chartBefore.filter((v, i) => v !== chartAfter[i]).length;
const heading = await page.evaluate(() => window.viewer.state.unitChannel);
check("choosing a channel replots the unit chart", chartChanged > 200 && heading === "touch", `${chartChanged} values changed, channel ${heading}`);
await page.selectOption("#unit-channel", "");

// The list removes panes: the two bad files go, the two replays stay side by side.
await page.uncheck('input[data-name="broken"]');
await page.uncheck('input[data-name="text"]');
check("unchecking replays in the list removes their panes", (await page.locator(".pane").count()) === 2, "");

// The other kinds draw without errors: membrane, cage, lidar rays.
await page.check('input[data-name="psa"]');
await page.check('input[data-name="sighted"]');
await page.waitForFunction(() => window.viewer.state.panes.length === 4);
await scrubTo(4);
const paneColours = (i) => page.evaluate((i) => {
    const c = document.querySelectorAll(".pane canvas")[i];
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let red = 0, coloured = 0;
    for (let p = 0; p < d.length; p += 4) {
      if (d[p] > 200 && d[p + 1] < 110 && d[p + 2] < 110) red++;
      if (Math.max(d[p], d[p + 1], d[p + 2]) - Math.min(d[p], d[p + 1], d[p + 2]) > 60) coloured++;
    }
    return { red, coloured };
  }, i);
for (const i of [2, 3]) {
  const drawn = await paneColours(i);
  check(`pane ${i + 1} (${i === 2 ? "PSA" : "lidar and graph brain"}) draws its body`, drawn.coloured > 200, JSON.stringify(drawn));
}
const withRays = await paneColours(3);
await page.uncheck("#ov-lidar");
const withoutRays = await paneColours(3);
await page.check("#ov-lidar");
check("the lidar toggle removes the red rays", withRays.red - withoutRays.red > 50, `${withRays.red} → ${withoutRays.red} red pixels`);
await page.screenshot({ path: join(shots, "kinds.png") });
await page.uncheck('input[data-name="psa"]');
await page.uncheck('input[data-name="sighted"]');

// Side by side: both replays follow the same clock.
const times = await page.evaluate(() => window.viewer.state.panes.filter((p) => p.replay).map((p) => p.replay.duration));
check("the 30 s and 10 s replays are side by side", times.length === 2 && Math.abs(times[0] - 30) < 0.05 && Math.abs(times[1] - 10) < 0.1, JSON.stringify(times));
await page.screenshot({ path: join(shots, "viewer.png") });

// Frame rate while playing both (the second is a 10×10 body): 3 s of playback.
await scrubTo(0);
await page.click("#play");
await page.waitForTimeout(3000);
await page.click("#play");
const stats = await page.evaluate(() => ({ ...window.viewer.stats }));
const fps = (stats.playedFrames - 1) / ((stats.playEnd - stats.playStart) / 1000);
const drawMs = stats.drawMs / stats.drawn;
console.log(`playback: ${fps.toFixed(1)} frames/s, draw ${drawMs.toFixed(2)} ms mean, ${stats.maxDrawMs.toFixed(1)} ms max per frame (biped + 10×10 block, ${stats.drawn} frames)`);
check("playback keeps 60 fps with a 10×10 body on screen", fps >= 55, `${fps.toFixed(1)} fps`);
check("no script errors on the page", consoleErrors.length === 0, consoleErrors.join("; "));
// Labelling: a `vsrlab label` folder in the viewer offers the classes beside each replay and saves
// labels.csv as the labelling page does.
writeFileSync(join(work, "tiny.toml"), [
  "runs = 1", "seed = 3", "[representation]", 'body = "biped-4x3"', 'sensors = "uniform-vxy+a+t-0"',
  'brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }',
  "[task]", "duration = 3.0", "[optimizer]", 'kind = "ga"', "population_size = 8", "offspring_size = 8",
  "[stop]", "generations = 2",
].join("\n") + "\n");
vsrlab("run", join(work, "tiny.toml"), "--out", join(work, "tiny"));
vsrlab("label", join(work, "tiny"), "--out", join(work, "lab"), "--count", "4", "--width", "100");
const lab = await startViewer([join(work, "lab")]);
const labPage = await browser.newPage({ viewport: { width: 1300, height: 1000 } });
labPage.on("pageerror", (e) => consoleErrors.push(String(e)));
await labPage.goto(lab.url);
await labPage.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
const selects = await labPage.locator(".pane select").count();
check("a labelling folder shows the class choices beside each replay", selects === 8, `${selects} choices in ${await labPage.locator(".pane").count()} panes`);
const first = labPage.locator(".pane").first();
const firstId = (await first.locator("h2").textContent()).trim();
await first.locator('select[data-kind="shape"]').selectOption("limbed");
await first.locator('select[data-kind="behaviour"]').selectOption("walking");
const progress = await labPage.locator("#label-progress").textContent();
check("the progress counts the labelled robot", progress.startsWith("1 / 4"), progress);
await labPage.screenshot({ path: join(shots, "labelling.png") });
const [download] = await Promise.all([labPage.waitForEvent("download"), labPage.click("#save-labels")]);
const csv = readFileSync(await download.path(), "utf8").trim().split("\n");
check("labels.csv has the labelling page's columns", csv[0] === "robot,terrain,duration,transient,seed,shape,behaviour,id", csv[0]);
const row = csv.find((l) => l.endsWith(`,${firstId}`)) || "";
check("labels.csv holds the choice for the robot", row.includes(",limbed,walking,") && csv.length === 5, row);
lab.proc.kill("SIGINT");

// A kind that colours its own units (channel unit_fill, e.g. one colour per material): the page
// fills every voxel of the 10×10 block with the replay's colour instead of the area colours.
const coloured = JSON.parse(readFileSync(box, "utf8"));
coloured.body.unit_fill = coloured.body.corners.map(() => 0x2060d0);
writeFileSync(join(work, "coloured.replay.json"), JSON.stringify(coloured));
const paint = await startViewer([join(work, "coloured.replay.json")]);
const paintPage = await browser.newPage({ viewport: { width: 1300, height: 1000 } });
paintPage.on("pageerror", (e) => consoleErrors.push(String(e)));
await paintPage.goto(paint.url);
await paintPage.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
const fills = await paintPage.evaluate(() => {
  const c = document.querySelector(".pane canvas");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let kind = 0, area = 0;
  for (let p = 0; p < d.length; p += 4) {
    const [r, g, b] = [d[p], d[p + 1], d[p + 2]];
    if (Math.abs(r - 0x20) < 12 && Math.abs(g - 0x60) < 12 && Math.abs(b - 0xd0) < 12) kind++;
    if (b < 150 && Math.max(r, g) >= 200) area++;
  }
  return { kind, area };
});
check("a replay's unit_fill colours its units instead of the area colours", fills.kind > 2000 && fills.area < 50, JSON.stringify(fills));
await paintPage.screenshot({ path: join(shots, "unit-fill.png") });
paint.proc.kill("SIGINT");

// An EvoGym replay has no ground besides its world's objects (world.terrain is empty): the page
// plays it without errors and draws no ground colour (issue 56, item 5: a grey slab was drawn
// under BridgeWalker's bridge).
const evogym = join(work, "evogym.replay.json");
vsrlab("simulate", "--body", "evogym:33333/33333/33333/33333/33333", "--task", "bridge-walker", "--duration", "0.3", "--replay", evogym);
check("an EvoGym replay has no ground line", JSON.parse(readFileSync(evogym, "utf8")).world.terrain.length === 0);
const bridge = await startViewer([evogym]);
const bridgePage = await browser.newPage({ viewport: { width: 1300, height: 1000 } });
bridgePage.on("pageerror", (e) => consoleErrors.push(String(e)));
await bridgePage.goto(bridge.url);
await bridgePage.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
const ground = await bridgePage.evaluate(() => {
  const c = document.querySelector(".pane canvas");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let grey = 0, inked = 0;
  for (let p = 0; p < d.length; p += 4) {
    if (d[p] === 180 && d[p + 1] === 180 && d[p + 2] === 180) grey++;
    if (d[p] + d[p + 1] + d[p + 2] < 600) inked++;
  }
  return { grey, inked };
});
check("an EvoGym replay draws its world and robot but no ground", ground.grey < 50 && ground.inked > 500, JSON.stringify(ground));
await bridgePage.screenshot({ path: join(shots, "evogym-bridge.png") });
bridge.proc.kill("SIGINT");

// 3D replays: a quadruped beside a small wall of fixed voxels (1 s), next to the 2D biped. The 3D
// pane draws shaded cubes on a checkerboard under the sky; scrubbing, dragging (orbit), the wheel
// and the follow toggle change its pixels; clicking a voxel selects it.
writeFileSync(join(work, "wall3d.toml"), [
  "runs = 1", "[representation]", 'body = { kind = "voxel3d", body = "quadruped", sensors = "cpg:5,touch,floor,vy,vx" }',
  'brain = { kind = "distributed-mlp", signals = 1 }', "[task]", 'kind = "locomotion3d"', "duration = 1.0",
  "obstacles = [[6, 0, 0], [6, 1, 0], [6, 2, 0], [6, 1, 1]]", "[optimizer]", 'kind = "cma-es"', "[stop]", "evaluations = 10",
].join("\n") + "\n");
const solid = join(work, "solid.replay.json");
vsrlab("simulate", "--body", "3d:quadruped", "--task-of", join(work, "wall3d.toml"), "--duration", "1", "--replay", solid);
const view3d = await startViewer([solid, walk]);
const page3d = await browser.newPage({ viewport: { width: 1300, height: 1000 } });
page3d.on("pageerror", (e) => consoleErrors.push(String(e)));
await page3d.goto(view3d.url);
await page3d.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
// Counts of the 3D pane's colours (below the HUD): shaded blue voxels (and their centroid on the
// page), the sky, the floor's two greys, the shaded grey of the wall. The frame is kept in the page
// as `name` for `changed3d`, which counts the pixels that differ between two kept frames.
const solidPixels = (name) => page3d.evaluate((name) => {
  const c = document.querySelector(".pane canvas");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  (window.frames3d = window.frames3d || {})[name] = d;
  const n = { blue: 0, sky: 0, light: 0, dark: 0, wall: 0, bx: 0, by: 0 };
  for (let p = 0; p < d.length; p += 4) {
    const [r, g, b] = [d[p], d[p + 1], d[p + 2]], y = Math.floor(p / 4 / c.width);
    if (r === 214 && g === 230 && b === 245) n.sky++;
    if (y < 80) continue;
    if (b > 100 && b - r > 60 && b > g) { n.blue++; n.bx += (p / 4) % c.width; n.by += y; }
    if (r === g && g === b) {
      if (r === 226) n.light++; else if (r === 196) n.dark++; else if (r >= 60 && r <= 130) n.wall++;
    }
  }
  const rect = c.getBoundingClientRect();
  return { ...n, bx: rect.x + n.bx / n.blue * rect.width / c.width, by: rect.y + n.by / n.blue * rect.height / c.height };
}, name);
const changed3d = (a, b) => page3d.evaluate(([a, b]) => {
  const x = window.frames3d[a], y = window.frames3d[b];
  let n = 0;
  for (let i = 0; i < x.length; i += 4) if (x[i] !== y[i] || x[i + 1] !== y[i + 1] || x[i + 2] !== y[i + 2]) n++;
  return n;
}, [a, b]);
const scrub3d = (t) => page3d.evaluate((t) => { const s = document.getElementById("scrub"); s.value = String(t); s.dispatchEvent(new Event("input")); }, t);
await scrub3d(0);
const first3d = await solidPixels("first");
await page3d.screenshot({ path: join(shots, "solid-3d.png") });
const counts = first3d;
check("the 3D pane draws shaded blue cubes", first3d.blue > 3000, JSON.stringify(counts));
check("the 3D pane draws the sky and the floor's two greys", first3d.sky > 1000 && first3d.light > 5000 && first3d.dark > 5000, JSON.stringify(counts));
check("the 3D pane draws the fixed voxels grey", first3d.wall > 500, JSON.stringify(counts));
await scrub3d(1);
await solidPixels("end");
const startToEnd = await changed3d("first", "end");
check("the 3D frame changes from the start to the end of the episode", startToEnd > 1000, `${startToEnd} pixels`);
const canvas3d = await page3d.locator(".pane canvas").first().boundingBox();
await page3d.mouse.move(canvas3d.x + canvas3d.width / 2, canvas3d.y + canvas3d.height / 2);
await page3d.mouse.down();
await page3d.mouse.move(canvas3d.x + canvas3d.width / 2 + 120, canvas3d.y + canvas3d.height / 2 + 40, { steps: 6 });
await page3d.mouse.up();
await solidPixels("orbited");
const byDrag = await changed3d("end", "orbited");
const orbit = await page3d.evaluate(() => ({ ...window.viewer.state.orbit, selected: window.viewer.state.selected }));
await page3d.screenshot({ path: join(shots, "solid-3d-orbit.png") });
check("dragging the 3D pane orbits the camera", byDrag > 5000 && orbit.azimuth !== -60 && orbit.elevation > 25 && orbit.selected === null,
  `${byDrag} pixels, ${JSON.stringify(orbit)}`);
await page3d.mouse.wheel(0, -200);
await solidPixels("zoomed");
const byWheel = await changed3d("orbited", "zoomed");
check("the wheel zooms the 3D pane", byWheel > 5000, `${byWheel} pixels`);
await page3d.uncheck("#follow");
await solidPixels("whole");
const byFollow = await changed3d("zoomed", "whole");
check("the follow toggle reframes the 3D pane", byFollow > 1000, `${byFollow} pixels`);
await page3d.check("#follow");
await scrub3d(0);
const atBody = await solidPixels("click");
await page3d.mouse.click(atBody.bx, atBody.by);
const picked = await page3d.evaluate(() => window.viewer.state.selected && window.viewer.state.selected.unit);
const offered3d = await page3d.locator("#unit-channel option").allTextContents();
check("clicking a 3D voxel selects it and offers its channels", Number.isInteger(picked) && ["actuation", "voxel_edge"].every((n) => offered3d.includes(n)),
  `voxel ${picked}, ${JSON.stringify(offered3d)}`);
view3d.proc.kill("SIGINT");

// An affordance episode (ch. 5.1): each voxel is coloured by its vote. At t = 0 no voxel has
// voted yet (votes 0 count as "impassable"): every voxel is red, none keeps the default blue.
const voting = join(work, "votes.replay.json");
vsrlab("simulate", "--body", "3d:flatworm", "--brain", "elman", "--task", "affordance:impassable", "--duration", "0.3", "--replay", voting);
const viewVotes = await startViewer([voting]);
const pageVotes = await browser.newPage({ viewport: { width: 1000, height: 800 } });
pageVotes.on("pageerror", (e) => consoleErrors.push(String(e)));
await pageVotes.goto(viewVotes.url);
await pageVotes.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 30000 });
await pageVotes.evaluate(() => { const s = document.getElementById("scrub"); s.value = "0"; s.dispatchEvent(new Event("input")); });
const voteColours = await pageVotes.evaluate(() => {
  const c = document.querySelector(".pane canvas");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  const n = { red: 0, blue: 0 };
  for (let p = 0; p < d.length; p += 4) {
    const [r, g, b] = [d[p], d[p + 1], d[p + 2]];
    if (Math.floor(p / 4 / c.width) < 80) continue;
    if (r > 100 && r - g > 25 && r - b > 25) n.red++;
    if (b > 100 && b - r > 60 && b > g) n.blue++;
  }
  return n;
});
await pageVotes.screenshot({ path: join(shots, "solid-3d-votes.png") });
check("a 3D replay with votes colours each voxel by its vote", voteColours.red > 1000 && voteColours.blue < 50, JSON.stringify(voteColours));
viewVotes.proc.kill("SIGINT");
// The live monitor: `vsrlab view OUT` on a quickstart that is still running shows each run's
// curves and best so far, and they advance as generations land.
const liveFile = join(work, "live.toml");
writeFileSync(liveFile, readFileSync(join(root, "experiments/quickstart.toml"), "utf8")
  .replace("runs = 1", "runs = 2").replace("duration = 10.0", "duration = 2.0")
  .replace("population_size = 40", "population_size = 8").replace("offspring_size = 40", "offspring_size = 8")
  .replace("evaluations = 8000", "evaluations = 1000000").replace("snapshot_every = 40", "snapshot_every = 8"));
const liveOut = join(work, "live-out");
const running = started(spawn(bin, ["run", liveFile, "--out", liveOut, "--threads", "1"], { cwd: root, stdio: "ignore" }));
const waitFor = async (cond, ms, what) => {
  const until = Date.now() + ms;
  while (!cond()) { if (Date.now() > until) throw new Error(`timed out waiting for ${what}`); await new Promise((r) => setTimeout(r, 100)); }
};
await waitFor(() => { try { return statSync(join(liveOut, "run-00", "generations.csv")).size > 0; } catch { return false; } }, 60000, "the first generation");
const viewLive = await startViewer([liveOut]);
const pageLive = await browser.newPage({ viewport: { width: 1100, height: 900 } });
pageLive.on("pageerror", (e) => consoleErrors.push(String(e)));
await pageLive.addInitScript(() => { window.addEventListener("load", () => { if (window.viewer) window.viewer.monitor.interval = 500; }); });
await pageLive.goto(viewLive.url);
await pageLive.waitForFunction(() => window.viewer && window.viewer.monitor.polls >= 1, null, { timeout: 30000 });
const liveState = () => pageLive.evaluate(() => {
  const r = window.viewer.monitor.data.experiments[0].runs[0];
  const c = document.getElementById("monitor-chart");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let coloured = 0;
  for (let p = 0; p < d.length; p += 4) if (Math.max(d[p], d[p + 1], d[p + 2]) - Math.min(d[p], d[p + 1], d[p + 2]) > 60) coloured++;
  return { state: r.state, evaluations: r.evaluations, points: r.curve.length, eta: r.eta, coloured,
    line: document.querySelector('#monitor-lines .run[data-run="0/0"] .text').textContent,
    panes: window.viewer.state.panes.map((p) => p.replay ? p.replay.title : p.name) };
});
const before = await liveState();
await pageLive.waitForFunction((n) => window.viewer.monitor.data.experiments[0].runs[0].evaluations > n, before.evaluations, { timeout: 60000 });
await pageLive.waitForFunction(() => window.viewer.state.panes.some((p) => p.replay && p.replay.title.includes("best so far")), null, { timeout: 60000 });
const after = await liveState();
await pageLive.screenshot({ path: join(shots, "live-monitor.png") });
check("the live monitor shows a running run's progress and ETA", before.state === "running" && /generation \d+ · \d+ evaluations · best .* · ETA /.test(after.line), after.line);
check("the live monitor's curves advance as generations land", after.evaluations > before.evaluations && after.points > before.points && after.coloured > 200,
  `${before.points} → ${after.points} points, ${before.evaluations} → ${after.evaluations} evaluations, ${after.coloured} coloured pixels`);
check("the live monitor shows the running run's best robot so far", after.panes.some((t) => /run 0: best so far \(after \d+ evaluations/.test(t)), JSON.stringify(after.panes));
running.kill("SIGINT");
viewLive.proc.kill("SIGINT");
check("no script errors on the later pages (labelling, unit fill, 3D, live monitor)", consoleErrors.length === 0, consoleErrors.join("; "));
await browser.close();

// Ctrl-C stops the server cleanly.
const exited = new Promise((resolve) => server.on("exit", (code, signal) => resolve({ code, signal })));
server.kill("SIGINT");
const exit = await Promise.race([exited, new Promise((r) => setTimeout(() => r({ code: "timeout" }), 5000))]);
check("Ctrl-C stops vsrlab view with status 0", exit.code === 0 && serverOutput.text.includes("viewer stopped"), JSON.stringify(exit));
console.log(`${results.length} checks passed; screenshots in ${shots}`);
