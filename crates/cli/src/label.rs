//! `vsrlab label`: a labelling aid for the species classifiers (thesis §3.3.2.2). It draws a
//! sample of evolved robots stratified by the three morphology descriptors, replays each one,
//! saves its robot file and a GIF, and writes a local HTML page (no network) where a person
//! picks a morphology and a behaviour class per robot and saves `labels.csv` for
//! `vsrlab analyze --labels`.

use crate::analyze::{pool, row_body, Replay};
use clap::Args;
use rayon::prelude::*;
use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vsrlab_analysis::diversity::{propose_behaviour, propose_shape};
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::labels::{write_labels, LabelRow};
use vsrlab_analysis::morphology::MorphologyDescriptors;
use vsrlab_analysis::results::{self, SnapshotRow};
use vsrlab_analysis::sampling::stratified_sample;
use vsrlab_tasks::files::save_robot;

/// Arguments of `vsrlab label`.
#[derive(Args, Debug)]
pub struct LabelArgs {
    /// Output folders of `vsrlab run` to draw robots from (every snapshot of every run).
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Folder for the page, the robot files and the videos.
    #[arg(long, default_value = "labelling")]
    pub out: PathBuf,
    /// Number of robots on the page.
    #[arg(long, default_value_t = 64)]
    pub count: usize,
    /// Equal-size bins per descriptor (voxels, elongation, compactness): bins³ strata.
    #[arg(long, default_value_t = 4)]
    pub bins: usize,
    /// Leave out robots slower than this (the thesis discarded poor walkers before sampling).
    #[arg(long)]
    pub min_velocity: Option<f64>,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Morphology classes, comma-separated (default: the thesis').
    #[arg(long, default_value = "blob,limbed,elongated,other")]
    pub shape_classes: String,
    /// Behaviour classes, comma-separated (default: the thesis').
    #[arg(long, default_value = "jumping,walking,rolling,other")]
    pub behaviour_classes: String,
    /// Pre-select the rule-of-thumb proposals on the page (otherwise they are only shown).
    #[arg(long)]
    pub prefill: bool,
    /// Also write labels.csv right away from the proposals (rule-of-thumb labels, for trying the
    /// pipeline; not a substitute for looking at the robots).
    #[arg(long)]
    pub auto: bool,
    /// Video width in pixels.
    #[arg(long, default_value_t = 360)]
    pub width: u32,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
}

struct Candidate {
    experiment: usize,
    setting: String,
    run: usize,
    row: SnapshotRow,
    descriptors: MorphologyDescriptors,
}

struct Entry {
    id: String,
    robot: String,
    video: String,
    terrain: String,
    duration: f64,
    transient: f64,
    seed: u64,
    candidate: usize,
    proposal: (String, String),
}

pub fn run(args: LabelArgs) -> Result<(), String> {
    let shapes: Vec<String> = split_classes(&args.shape_classes)?;
    let behaviours: Vec<String> = split_classes(&args.behaviour_classes)?;
    let experiments = results::discover(&args.results).map_err(|e| e.to_string())?;
    let mut pool_rows: Vec<Candidate> = Vec::new();
    let mut seen: HashSet<(String, Vec<u64>)> = HashSet::new();
    for (e, exp) in experiments.iter().enumerate() {
        for r in &exp.runs {
            for (_, path) in &r.snapshots {
                for row in results::read_snapshot(path).map_err(|e| e.to_string())? {
                    if row.error.is_some() || row.fitness.is_none() || row.genotype.is_empty() {
                        continue;
                    }
                    if args
                        .min_velocity
                        .is_some_and(|v| row.velocity.unwrap_or(f64::NEG_INFINITY) < v)
                    {
                        continue;
                    }
                    let Some(body) = row_body(&row) else { continue };
                    // Survivors appear in many snapshots: keep each genotype once.
                    let key = (
                        exp.dir.display().to_string(),
                        row.genotype.iter().map(|g| g.to_bits()).collect(),
                    );
                    if !seen.insert(key) {
                        continue;
                    }
                    pool_rows.push(Candidate {
                        experiment: e,
                        setting: exp.name.clone(),
                        run: r.index,
                        descriptors: MorphologyDescriptors::of(&body),
                        row,
                    });
                }
            }
        }
    }
    if pool_rows.is_empty() {
        return Err("no evaluated individual found in the snapshots".into());
    }
    let keys: Vec<Vec<f64>> = pool_rows.iter().map(|c| c.descriptors.to_vec().to_vec()).collect();
    let picked = stratified_sample(&keys, args.bins, args.count, args.seed);
    eprintln!(
        "{} distinct individuals in the snapshots; replaying {} of them…",
        pool_rows.len(),
        picked.len()
    );
    let replays: Vec<Option<Replay>> = experiments.iter().map(|e| Replay::of(e).ok()).collect();
    for dir in ["robots", "videos"] {
        std::fs::create_dir_all(args.out.join(dir)).map_err(|e| format!("{}: {e}", args.out.join(dir).display()))?;
    }
    let render = vsrlab_render::RenderOptions {
        width: args.width,
        height: (args.width * 9 / 16).max(90),
        fps: 15.0,
        draw_sensors: false,
        draw_lidar: false,
    };
    let threads = pool(args.threads)?;
    let entries: Vec<Result<Entry, String>> = threads.install(|| {
        picked
            .par_iter()
            .enumerate()
            .map(|(k, &i)| {
                let c = &pool_rows[i];
                let rp = replays[c.experiment]
                    .as_ref()
                    .ok_or_else(|| format!("{}: cannot replay", experiments[c.experiment].dir.display()))?;
                let (robot, trace) = rp.row(&c.row)?;
                let id = format!("r-{:04}", k + 1);
                let robot_rel = format!("robots/{id}.robot.json");
                let video_rel = format!("videos/{id}.gif");
                let note = format!(
                    "{} run {} evaluations {} index {}",
                    c.setting, c.run, c.row.evaluations, c.row.index
                );
                save_robot(&args.out.join(&robot_rel), &robot, Some(&note)).map_err(|e| e.to_string())?;
                vsrlab_render::save_video(&trace, &render, args.out.join(&video_rel)).map_err(|e| e.to_string())?;
                let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
                let proposal = (
                    nearest_class(propose_shape(&c.descriptors), &shapes),
                    nearest_class(propose_behaviour(&f), &behaviours),
                );
                Ok(Entry {
                    id,
                    robot: robot_rel,
                    video: video_rel,
                    terrain: rp.task.terrain.to_string(),
                    duration: rp.task.duration,
                    transient: rp.task.transient,
                    seed: c.row.seed,
                    candidate: i,
                    proposal,
                })
            })
            .collect()
    });
    let entries: Vec<Entry> = entries.into_iter().collect::<Result<_, _>>()?;
    write_manifest(&args.out.join("manifest.csv"), &entries, &pool_rows)?;
    let page = page(&entries, &pool_rows, &shapes, &behaviours, args.prefill);
    let index = args.out.join("index.html");
    std::fs::write(&index, page).map_err(|e| format!("{}: {e}", index.display()))?;
    if args.auto {
        let rows: Vec<LabelRow> = entries
            .iter()
            .map(|e| LabelRow {
                robot: e.robot.clone(),
                terrain: e.terrain.clone(),
                duration: e.duration,
                transient: e.transient,
                seed: e.seed,
                shape: e.proposal.0.clone(),
                behaviour: e.proposal.1.clone(),
            })
            .collect();
        write_labels(&args.out.join("labels.csv"), &rows).map_err(|e| e.to_string())?;
        println!(
            "wrote rule-of-thumb labels to {}",
            args.out.join("labels.csv").display()
        );
    }
    println!(
        "open {} in a browser, pick a class per robot and save labels.csv into {}; then run\n  vsrlab analyze {} --labels {}",
        index.display(),
        args.out.display(),
        args.results.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(" "),
        args.out.join("labels.csv").display()
    );
    Ok(())
}

fn split_classes(s: &str) -> Result<Vec<String>, String> {
    let v: Vec<String> = s
        .split(',')
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect();
    if v.len() < 2 {
        return Err(format!("need at least two classes, got '{s}'"));
    }
    if v.iter().any(|c| c.contains(['"', '<', '>', '&'])) {
        return Err(format!("class names may not contain quotes or <>&: '{s}'"));
    }
    Ok(v)
}

/// The proposal if it is one of the classes, else the last class (the "other" bin by convention).
fn nearest_class(proposal: &str, classes: &[String]) -> String {
    classes
        .iter()
        .find(|c| c.as_str() == proposal)
        .cloned()
        .unwrap_or_else(|| classes.last().cloned().unwrap_or_default())
}

fn write_manifest(path: &Path, entries: &[Entry], pool: &[Candidate]) -> Result<(), String> {
    let mut s = String::from("id,robot,video,terrain,duration,transient,seed,setting,run,evaluations,index,velocity,voxels,elongation,compactness,proposed_shape,proposed_behaviour\n");
    for e in entries {
        let c = &pool[e.candidate];
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4},{:.4},{},{}",
            e.id,
            e.robot,
            e.video,
            e.terrain,
            e.duration,
            e.transient,
            e.seed,
            vsrlab_analysis::report::csv_field(&c.setting),
            c.run,
            c.row.evaluations,
            c.row.index,
            c.row.velocity.map_or(String::new(), |v| v.to_string()),
            c.descriptors.voxels,
            c.descriptors.elongation,
            c.descriptors.compactness,
            e.proposal.0,
            e.proposal.1
        );
    }
    std::fs::write(path, s).map_err(|e| format!("{}: {e}", path.display()))
}

fn json_str(s: &str) -> String {
    serde_json::to_string(s).expect("strings serialise")
}

fn page(entries: &[Entry], pool: &[Candidate], shapes: &[String], behaviours: &[String], prefill: bool) -> String {
    let items: Vec<serde_json::Value> = entries
        .iter()
        .map(|e| {
            let c = &pool[e.candidate];
            serde_json::json!({
                "id": e.id, "robot": e.robot, "video": e.video, "terrain": e.terrain,
                "duration": e.duration, "transient": e.transient, "seed": e.seed,
                "setting": c.setting, "run": c.run, "evaluations": c.row.evaluations,
                "velocity": c.row.velocity, "voxels": c.descriptors.voxels,
                "elongation": c.descriptors.elongation, "compactness": c.descriptors.compactness,
                "body": c.row.body, "proposal": [e.proposal.0, e.proposal.1],
            })
        })
        .collect();
    let data = serde_json::json!({ "items": items, "shapes": shapes, "behaviours": behaviours, "prefill": prefill });
    // "</" cannot appear inside the script element.
    let data = serde_json::to_string(&data).expect("json").replace("</", "<\\/");
    PAGE.replace("/*DATA*/null", &data)
        .replace("{{TITLE}}", &format!("vsrlab labelling: {} robots", entries.len()))
        .replace("{{KEY}}", &json_str(&format!("vsrlab-labels-{}", entries.len())))
}

const PAGE: &str = r#"<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<title>{{TITLE}}</title>
<style>
body { font-family: system-ui, sans-serif; margin: 0; background: #f4f4f4; color: #222; }
header { position: sticky; top: 0; background: #fff; border-bottom: 1px solid #ccc; padding: 10px 16px; z-index: 2; }
header h1 { font-size: 18px; margin: 0 0 6px 0; }
header p { margin: 4px 0; font-size: 13px; }
button { font-size: 14px; padding: 6px 12px; margin-right: 8px; cursor: pointer; }
#grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(380px, 1fr)); gap: 14px; padding: 14px; }
.card { background: #fff; border: 2px solid #ddd; border-radius: 6px; padding: 8px; }
.card.done { border-color: #59a14f; }
.card img { width: 100%; background: #eee; display: block; }
.meta { font-size: 12px; color: #555; margin: 6px 0; }
.body { font-family: monospace; font-size: 10px; line-height: 10px; white-space: pre; float: right; margin-left: 8px; }
.group { margin: 4px 0; font-size: 13px; }
.group b { display: block; margin-bottom: 2px; }
.group label { margin-right: 8px; white-space: nowrap; }
.hint { color: #888; font-size: 12px; }
</style></head><body>
<header>
<h1>{{TITLE}}</h1>
<p>Watch each robot and pick its <b>morphology</b> and <b>behaviour</b> class. Choices are kept in this browser as you go.
When done, press <b>Save labels.csv</b> and save the file <b>into this page's folder</b> (robot paths in it are relative to it), then run
<code>vsrlab analyze RESULTS --labels labels.csv</code>.</p>
<p><button id="save">Save labels.csv</button><button id="clear">Clear all choices</button>
<span id="progress"></span> <span class="hint">Suggestions are rule-of-thumb guesses from the descriptors and the gait, not labels.</span></p>
</header>
<div id="grid"></div>
<script>
const DATA = /*DATA*/null;
const KEY = {{KEY}} + ":" + location.pathname;
let choices = JSON.parse(localStorage.getItem(KEY) || "{}");
if (DATA.prefill && Object.keys(choices).length === 0) {
  for (const it of DATA.items) choices[it.id] = { shape: it.proposal[0], behaviour: it.proposal[1] };
}
function store() { localStorage.setItem(KEY, JSON.stringify(choices)); progress(); }
function progress() {
  let n = 0;
  for (const it of DATA.items) {
    const c = choices[it.id] || {};
    const done = c.shape && c.behaviour;
    if (done) n++;
    const card = document.getElementById("card-" + it.id);
    if (card) card.classList.toggle("done", !!done);
  }
  document.getElementById("progress").textContent = n + " / " + DATA.items.length + " labelled";
}
function group(it, kind, classes, title) {
  const div = document.createElement("div");
  div.className = "group";
  const b = document.createElement("b"); b.textContent = title; div.appendChild(b);
  for (const cls of classes) {
    const label = document.createElement("label");
    const input = document.createElement("input");
    input.type = "radio"; input.name = kind + "-" + it.id; input.value = cls;
    input.checked = (choices[it.id] || {})[kind] === cls;
    input.addEventListener("change", () => { choices[it.id] = Object.assign({}, choices[it.id], { [kind]: cls }); store(); });
    label.appendChild(input); label.appendChild(document.createTextNode(" " + cls));
    div.appendChild(label);
  }
  return div;
}
const grid = document.getElementById("grid");
for (const it of DATA.items) {
  const card = document.createElement("div"); card.className = "card"; card.id = "card-" + it.id;
  const img = document.createElement("img"); img.src = it.video; img.loading = "lazy"; img.alt = it.id;
  card.appendChild(img);
  const meta = document.createElement("div"); meta.className = "meta";
  const body = document.createElement("span"); body.className = "body"; body.textContent = (it.body || "").split("/").join("\n");
  meta.appendChild(body);
  const v = it.velocity == null ? "–" : it.velocity.toFixed(2);
  meta.appendChild(document.createTextNode(it.id + " · " + it.setting + " run " + it.run + " · " + it.evaluations + " evaluations · velocity " + v +
    " · voxels " + it.voxels + " · elongation " + it.elongation.toFixed(2) + " · compactness " + it.compactness.toFixed(2)));
  meta.appendChild(document.createElement("br"));
  const hint = document.createElement("span"); hint.className = "hint";
  hint.textContent = "suggested: " + it.proposal[0] + " / " + it.proposal[1];
  meta.appendChild(hint);
  card.appendChild(meta);
  card.appendChild(group(it, "shape", DATA.shapes, "morphology"));
  card.appendChild(group(it, "behaviour", DATA.behaviours, "behaviour"));
  grid.appendChild(card);
}
function csvField(s) { s = String(s); return /[",\n]/.test(s) ? '"' + s.replace(/"/g, '""') + '"' : s; }
document.getElementById("save").addEventListener("click", () => {
  const lines = ["robot,terrain,duration,transient,seed,shape,behaviour,id"];
  for (const it of DATA.items) {
    const c = choices[it.id] || {};
    lines.push([it.robot, it.terrain, it.duration, it.transient, it.seed, c.shape || "", c.behaviour || "", it.id].map(csvField).join(","));
  }
  const blob = new Blob([lines.join("\n") + "\n"], { type: "text/csv" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob); a.download = "labels.csv";
  document.body.appendChild(a); a.click(); a.remove();
});
document.getElementById("clear").addEventListener("click", () => {
  if (confirm("Clear every choice on this page?")) { choices = {}; store(); location.reload(); }
});
progress();
</script></body></html>
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_and_proposals() {
        assert_eq!(split_classes("a, b,,c").unwrap(), vec!["a", "b", "c"]);
        assert!(split_classes("only").is_err());
        assert!(split_classes("a,<b>").is_err());
        let cls = vec!["block".to_string(), "legged".to_string(), "other".to_string()];
        assert_eq!(nearest_class("limbed", &cls), "other");
        assert_eq!(nearest_class("legged", &cls), "legged");
    }
}
