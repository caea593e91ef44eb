//! `vsrlab analyze`: figures and a summary table from the output of `vsrlab run`
//! (docs/analysis.md). The analysis itself lives in `vsrlab-analysis`; this file finds the runs,
//! replays robots where features are needed, and writes the files.

use clap::Args;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vsrlab_analysis::curves::{band, grid_for};
use vsrlab_analysis::diversity::{inverse_simpson, Classifier};
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::forest::{Folds, ForestParams};
use vsrlab_analysis::labels::read_labels;
use vsrlab_analysis::morphology::MorphologyDescriptors;
use vsrlab_analysis::pca::Pca;
use vsrlab_analysis::plot::{
    self, BandChart, BandFigure, BandSeries, BoxFigure, BoxGroup, Bubble, BubbleFigure, BubblePanel, ScatterFigure,
    ScatterPoint,
};
use vsrlab_analysis::report::{csv_field, SettingSummary, Summary};
use vsrlab_analysis::results::{self, ExperimentData, SnapshotRow};
use vsrlab_body::Morphology;
use vsrlab_tasks::files::load_robot;
use vsrlab_tasks::{locomotion, Locomotion, RobotSpec, Terrain, Trace, TraceLevel};

/// Arguments of `vsrlab analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// Output folders of `vsrlab run`: experiment folders, or folders holding several. Runs of
    /// experiments with the same name are pooled into one setting.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Labels CSV (made with `vsrlab label`): trains the shape and behaviour classifiers, which
    /// enables the species figures and the Inverse Simpson Index.
    #[arg(long)]
    pub labels: Option<PathBuf>,
    /// Output folder for figures and tables.
    #[arg(long, default_value = "analysis")]
    pub out: PathBuf,
    /// With --labels: individuals replayed per snapshot (evenly spread over the population;
    /// 0 = all). Every individual is a full episode, so this bounds the cost.
    #[arg(long, default_value_t = 0)]
    pub sample: usize,
    /// Cross-validation folds of the classifiers.
    #[arg(long, default_value_t = 5)]
    pub folds: usize,
    /// Seed of the random forests.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads for replays (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// How to replay an individual of an experiment.
pub(crate) struct Replay {
    pub representation: vsrlab_tasks::Representation,
    pub task: Locomotion,
    pub episode_seed: u64,
    pub random_terrain: bool,
}

impl Replay {
    pub fn of(exp: &ExperimentData) -> Result<Replay, String> {
        let e = vsrlab_experiment::config::load(&exp.dir.join("experiment.toml")).map_err(|e| e.to_string())?;
        Ok(Replay {
            representation: e.representation.clone(),
            task: e.task.locomotion(),
            episode_seed: e.task.episode_seed,
            random_terrain: e.task.random_terrain_per_evaluation,
        })
    }

    /// The robot and full trace of a snapshot row (replayed with the row's episode seed).
    pub fn row(&self, row: &SnapshotRow) -> Result<(RobotSpec, Trace), String> {
        let robot = self.representation.robot(&row.genotype).map_err(|e| e.to_string())?;
        let trace = full_trace(&robot, &self.task, row.seed)?;
        Ok((robot, trace))
    }
}

/// Runs one episode with a full trace.
pub(crate) fn full_trace(robot: &RobotSpec, task: &Locomotion, seed: u64) -> Result<Trace, String> {
    let outcome = locomotion::run(robot, task, seed, TraceLevel::Full).map_err(|e| e.to_string())?;
    outcome.trace.ok_or_else(|| "the episode recorded no trace".to_string())
}

/// A thread pool of `threads` workers (0 or None: every core).
pub(crate) fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| e.to_string())
}

/// Evenly spread indices: `k` of `0..n` (all when k = 0 or k ≥ n).
pub(crate) fn spread(n: usize, k: usize) -> Vec<usize> {
    if k == 0 || k >= n {
        (0..n).collect()
    } else {
        (0..k).map(|i| i * n / k).collect()
    }
}

/// Body of a snapshot row, when it has one.
pub(crate) fn row_body(row: &SnapshotRow) -> Option<Morphology> {
    row.body.as_deref().and_then(|b| Morphology::parse(b).ok())
}

struct Setting {
    name: String,
    color: usize,
    experiments: Vec<usize>,
}

/// The best robot of one run and what was computed from it.
struct BestRobot {
    setting: usize,
    run: String,
    fitness: f64,
    descriptors: MorphologyDescriptors,
    features: Option<RobotFeatures>,
}

struct Classifiers {
    shape: Classifier,
    behaviour: Classifier,
    examples: (usize, usize),
}

/// Species of one replayed individual.
struct Labelled {
    shape: usize,
    behaviour: usize,
    velocity: f64,
}

/// ISI of one snapshot.
struct SnapshotIsi {
    evaluations: u64,
    shape: f64,
    behaviour: f64,
    species: f64,
}

pub fn run(args: AnalyzeArgs) -> Result<(), String> {
    let experiments = results::discover(&args.results).map_err(|e| e.to_string())?;
    let settings: Vec<Setting> = results::settings(&experiments)
        .into_iter()
        .enumerate()
        .map(|(i, (name, experiments))| Setting {
            name,
            color: i,
            experiments,
        })
        .collect();
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    let pool = pool(args.threads)?;
    let runs: usize = experiments.iter().map(|e| e.runs.len()).sum();
    eprintln!(
        "{} setting(s), {} experiment folder(s), {runs} run(s)",
        settings.len(),
        experiments.len()
    );
    let fitness = fitness_label(&experiments);
    let mut figures: Vec<(String, String)> = Vec::new();
    let out = |name: &str| args.out.join(name);
    let mut note = |fig: &str, what: &str| figures.push((fig.to_string(), what.to_string()));

    // 1. Fitness curves: best so far and population median, median ± sd across runs.
    let band_panel = |title: &str, pick: &dyn Fn(&results::GenerationRow) -> f64| {
        let series = settings
            .iter()
            .map(|s| {
                let curves: Vec<Vec<(f64, f64)>> = s
                    .experiments
                    .iter()
                    .flat_map(|&e| experiments[e].runs.iter())
                    .map(|r| {
                        r.generations
                            .iter()
                            .map(|g| (g.evaluations as f64, pick(g)))
                            .filter(|p| p.1.is_finite())
                            .collect()
                    })
                    .filter(|c: &Vec<(f64, f64)>| !c.is_empty())
                    .collect();
                median_band(s, &curves)
            })
            .collect();
        BandChart {
            title: title.into(),
            x_label: "fitness evaluations".into(),
            y_label: fitness.clone(),
            series,
        }
    };
    let fig = BandFigure {
        title: format!("Fitness ({fitness}) during evolution"),
        legend_title: "setting".into(),
        panels: vec![
            band_panel("best so far", &|g| g.best_fitness),
            band_panel("population median", &|g| g.population_median),
        ],
    };
    plot::save(&fig, &out("fitness")).map_err(|e| e.to_string())?;
    note(
        "fitness",
        "best-so-far and population-median fitness vs evaluations, median ± sd across runs",
    );

    // 2. Final best fitness per run, boxplots with pairwise Mann–Whitney p-values.
    let best_values: Vec<Vec<f64>> = settings
        .iter()
        .map(|s| {
            s.experiments
                .iter()
                .flat_map(|&e| experiments[e].runs.iter())
                .map(|r| r.final_best())
                .collect()
        })
        .collect();

    // 3. Best robots: descriptors, and features from a replay (for the PCA).
    eprintln!("replaying the best robot of every run…");
    let mut best_jobs = Vec::new();
    for s in &settings {
        for &e in &s.experiments {
            let exp = &experiments[e];
            for r in &exp.runs {
                if let Some(p) = &r.best_robot {
                    best_jobs.push((
                        s.color,
                        e,
                        format!("{}/run-{:02}", exp.dir.display(), r.index),
                        p.clone(),
                        r.final_best(),
                    ));
                }
            }
        }
    }
    let replays: Vec<Option<Replay>> = experiments
        .iter()
        .map(|e| match Replay::of(e) {
            Ok(r) => Some(r),
            Err(msg) => {
                eprintln!("warning: {}: cannot replay robots: {msg}", e.dir.display());
                None
            }
        })
        .collect();
    let bests: Vec<BestRobot> = pool.install(|| {
        best_jobs
            .par_iter()
            .filter_map(|(setting, e, run, path, fitness)| {
                let robot = load_robot(path).map_err(|err| eprintln!("warning: {err}")).ok()?;
                let features = replays[*e].as_ref().and_then(|rp| {
                    let seed = if rp.random_terrain { 0 } else { rp.episode_seed };
                    full_trace(&robot, &rp.task, seed)
                        .map_err(|err| eprintln!("warning: {}: {err}", path.display()))
                        .ok()
                        .map(|t| RobotFeatures::from_trace(&t, &FeatureParams::default()))
                });
                Some(BestRobot {
                    setting: *setting,
                    run: run.clone(),
                    fitness: *fitness,
                    descriptors: MorphologyDescriptors::of(&robot.body),
                    features,
                })
            })
            .collect()
    });
    write_best_csv(&out("best.csv"), &settings, &bests)?;

    // Descriptor scatter of the best robots.
    let max_voxels = bests.iter().map(|b| b.descriptors.voxels).max().unwrap_or(1).max(1) as f64;
    let radius = |v: f64| 4.0 + 16.0 * (v / max_voxels).sqrt();
    let size_entries: Vec<(String, f64)> = size_legend_values(max_voxels)
        .into_iter()
        .map(|v| (format!("{v}"), radius(v as f64)))
        .collect();
    let fig = ScatterFigure {
        title: "Morphology descriptors of the best robots".into(),
        x_label: "elongation".into(),
        y_label: "compactness".into(),
        groups: settings.iter().map(|s| s.name.clone()).collect(),
        legend_title: "setting".into(),
        points: bests
            .iter()
            .map(|b| ScatterPoint {
                x: b.descriptors.elongation,
                y: b.descriptors.compactness,
                radius: radius(b.descriptors.voxels as f64),
                group: b.setting,
            })
            .collect(),
        x_range: Some((-0.03, 1.03)),
        y_range: Some((0.0, 1.03)),
        size_legend: Some(("voxels".into(), size_entries)),
    };
    plot::save(&fig, &out("descriptors")).map_err(|e| e.to_string())?;
    note(
        "descriptors",
        "elongation vs compactness of each run's best robot (marker size: voxels)",
    );

    // PCA of the best robots' features (dynamic pose + behaviour), standardised.
    let with_features: Vec<&BestRobot> = bests.iter().filter(|b| b.features.is_some()).collect();
    if with_features.len() >= 3 {
        let rows: Vec<Vec<f64>> = with_features
            .iter()
            .map(|b| {
                let f = b.features.as_ref().unwrap();
                let mut v = f.morphology_vector();
                v.extend(f.behaviour_vector());
                v
            })
            .collect();
        let pca = Pca::fit(&rows, true);
        let fig = ScatterFigure {
            title: "PCA of the best robots (dynamic pose + behaviour features, standardised)".into(),
            x_label: format!(
                "PC1 ({:.0}% of variance)",
                100.0 * pca.variance_ratio.first().copied().unwrap_or(0.0)
            ),
            y_label: format!(
                "PC2 ({:.0}% of variance)",
                100.0 * pca.variance_ratio.get(1).copied().unwrap_or(0.0)
            ),
            groups: settings.iter().map(|s| s.name.clone()).collect(),
            legend_title: "setting".into(),
            points: with_features
                .iter()
                .zip(&rows)
                .map(|(b, r)| {
                    let z = pca.transform(r, 2);
                    ScatterPoint {
                        x: z[0],
                        y: z.get(1).copied().unwrap_or(0.0),
                        radius: 9.0,
                        group: b.setting,
                    }
                })
                .collect(),
            x_range: None,
            y_range: None,
            size_legend: None,
        };
        plot::save(&fig, &out("pca-best")).map_err(|e| e.to_string())?;
        note(
            "pca-best",
            "best robots on the first two principal components of their features",
        );
    } else {
        eprintln!("note: fewer than 3 replayable best robots: no PCA figure");
    }

    // 4. Species and ISI, with labels.
    let mut classifier_text = String::new();
    let mut final_isi: Vec<Vec<f64>> = vec![Vec::new(); settings.len()];
    if let Some(labels) = &args.labels {
        let cls = train_classifiers(labels, args.folds, args.seed, &pool)?;
        let _ = writeln!(
            classifier_text,
            "Classifiers (random forests, 100 trees, ⌊√p⌋ features per split, {} examples for shape, {} for behaviour; {}-fold cross-validation):\n",
            cls.examples.0, cls.examples.1, args.folds
        );
        let _ = writeln!(
            classifier_text,
            "| classifier | classes | CV accuracy | majority-class accuracy |\n|---|---|---:|---:|"
        );
        for (name, c) in [
            ("shape (dynamic pose, 256 features)", &cls.shape),
            ("behaviour (spectra + gait, 205 features)", &cls.behaviour),
        ] {
            let _ = writeln!(
                classifier_text,
                "| {name} | {} | {:.3} | {:.3} |",
                c.classes.join(", "),
                c.cv.accuracy,
                c.cv.majority_accuracy
            );
            eprintln!(
                "{name}: CV accuracy {:.3} (majority class {:.3})",
                c.cv.accuracy, c.cv.majority_accuracy
            );
        }
        let (isi, finals) = species_over_time(&experiments, &settings, &replays, &cls, args.sample, &pool)?;
        write_isi_csv(&out("isi.csv"), &settings, &experiments, &isi)?;
        // ISI curves: shape, behaviour, species.
        let isi_panel = |title: &str, pick: &dyn Fn(&SnapshotIsi) -> f64| {
            let series = settings
                .iter()
                .map(|s| {
                    let curves: Vec<Vec<(f64, f64)>> = isi
                        .iter()
                        .filter(|(si, _, _)| *si == s.color)
                        .map(|(_, _, snaps)| snaps.iter().map(|x| (x.evaluations as f64, pick(x))).collect())
                        .collect();
                    median_band(s, &curves)
                })
                .collect();
            BandChart {
                title: title.into(),
                x_label: "fitness evaluations".into(),
                y_label: "Inverse Simpson Index".into(),
                series,
            }
        };
        let fig = BandFigure {
            title: "Diversity of the population (Inverse Simpson Index)".into(),
            legend_title: "setting".into(),
            panels: vec![
                isi_panel("species", &|x| x.species),
                isi_panel("morphology", &|x| x.shape),
                isi_panel("behaviour", &|x| x.behaviour),
            ],
        };
        plot::save(&fig, &out("isi")).map_err(|e| e.to_string())?;
        note("isi", "Inverse Simpson Index of species, morphology and behaviour classes vs evaluations, median ± sd across runs");
        for (si, _, snaps) in &isi {
            if let Some(last) = snaps.last() {
                final_isi[*si].push(last.species);
            }
        }
        let fig = BoxFigure {
            title: "Final species diversity per run (Inverse Simpson Index)".into(),
            y_label: "ISI of the final population".into(),
            groups: box_groups(&settings, &final_isi),
            pvalues: pairs(&final_isi),
            max_brackets: 6,
        };
        plot::save(&fig, &out("isi-boxplot")).map_err(|e| e.to_string())?;
        note(
            "isi-boxplot",
            "ISI of the final population of each run, with pairwise Mann–Whitney p-values",
        );
        // Bubble plot of the species of the final populations.
        let panels = settings
            .iter()
            .map(|s| {
                let members: Vec<&Labelled> = finals
                    .iter()
                    .filter(|(si, _)| *si == s.color)
                    .flat_map(|(_, v)| v.iter())
                    .collect();
                let n = members.len().max(1) as f64;
                let mut bubbles = Vec::new();
                for (x, _) in cls.shape.classes.iter().enumerate() {
                    for (y, _) in cls.behaviour.classes.iter().enumerate() {
                        let of: Vec<&&Labelled> = members.iter().filter(|m| m.shape == x && m.behaviour == y).collect();
                        if !of.is_empty() {
                            let best = of
                                .iter()
                                .map(|m| m.velocity)
                                .filter(|v| v.is_finite())
                                .fold(f64::NAN, f64::max);
                            bubbles.push(Bubble {
                                x,
                                y,
                                share: of.len() as f64 / n,
                                value: best,
                            });
                        }
                    }
                }
                BubblePanel {
                    title: format!("{} ({} individuals)", s.name, members.len()),
                    bubbles,
                }
            })
            .collect();
        let fig = BubbleFigure {
            title: "Species of the final populations".into(),
            x_classes: cls.shape.classes.clone(),
            y_classes: cls.behaviour.classes.clone(),
            x_label: "morphology class".into(),
            y_label: "behaviour class".into(),
            value_label: "best velocity".into(),
            panels,
        };
        plot::save(&fig, &out("species")).map_err(|e| e.to_string())?;
        note(
            "species",
            "share of each species in the final populations (bubble area) and its best velocity (colour)",
        );
    } else {
        classifier_text.push_str(
            "No labels given (--labels): species, ISI and the species bubble plot are skipped. \
             Make a labels file with `vsrlab label` and pass it with --labels.\n",
        );
    }

    let fig = BoxFigure {
        title: format!("Best {fitness} of each run"),
        y_label: format!("best {fitness}"),
        groups: box_groups(&settings, &best_values),
        pvalues: pairs(&best_values),
        max_brackets: 6,
    };
    plot::save(&fig, &out("best-boxplot")).map_err(|e| e.to_string())?;
    note(
        "best-boxplot",
        "best fitness of each run per setting, with pairwise Mann–Whitney p-values",
    );

    // 5. Tables.
    let summary = Summary::new(
        &fitness,
        settings
            .iter()
            .map(|s| SettingSummary {
                name: s.name.clone(),
                best: best_values[s.color].clone(),
                final_isi: final_isi[s.color].clone(),
            })
            .collect(),
    );
    write(&out("summary.csv"), &summary.settings_csv())?;
    write(&out("pvalues.csv"), &summary.pvalues_csv())?;
    let mut md = String::from("# vsrlab analysis\n\n");
    let _ = writeln!(
        md,
        "Results: {}\n",
        args.results
            .iter()
            .map(|p| format!("`{}`", p.display()))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(md, "Settings and their experiment folders:\n");
    for s in &settings {
        let dirs: Vec<String> = s
            .experiments
            .iter()
            .map(|&e| {
                format!(
                    "`{}` ({} runs)",
                    experiments[e].dir.display(),
                    experiments[e].runs.len()
                )
            })
            .collect();
        let _ = writeln!(md, "- **{}**: {}", s.name, dirs.join(", "));
    }
    let _ = writeln!(md, "\n{}", summary.to_markdown());
    let _ = writeln!(md, "\n{classifier_text}");
    let _ = writeln!(md, "Figures (PNG and SVG):\n");
    for (f, what) in &figures {
        let _ = writeln!(md, "- `{f}.png`: {what}");
    }
    let _ = writeln!(
        md,
        "\nTables: `summary.csv` (per setting), `pvalues.csv` (pairwise tests), `best.csv` (best robot of each run){}.",
        if args.labels.is_some() {
            ", `isi.csv` (ISI per snapshot)"
        } else {
            ""
        }
    );
    write(&out("summary.md"), &md)?;
    println!("{}", summary.to_markdown());
    println!(
        "wrote {} figures and the tables to {}",
        figures.len(),
        args.out.display()
    );
    Ok(())
}

fn fitness_label(experiments: &[ExperimentData]) -> String {
    let mut kinds: Vec<String> = experiments.iter().map(|e| e.fitness_kind()).collect();
    kinds.sort();
    kinds.dedup();
    if kinds.len() == 1 {
        kinds.remove(0)
    } else {
        "fitness".into()
    }
}

/// The median ± sd band across runs of one setting's curves, on a common grid of 200 points.
fn median_band(setting: &Setting, curves: &[Vec<(f64, f64)>]) -> BandSeries {
    let grid = grid_for(curves, 200);
    let b = band(curves, &grid, true);
    BandSeries {
        label: setting.name.clone(),
        color: setting.color,
        x: b.x,
        center: b.median,
        spread: b.sd,
    }
}

/// One box per setting, from `values[setting colour]`.
fn box_groups(settings: &[Setting], values: &[Vec<f64>]) -> Vec<BoxGroup> {
    settings
        .iter()
        .map(|s| BoxGroup {
            label: s.name.clone(),
            color: s.color,
            values: values[s.color].clone(),
        })
        .collect()
}

fn pairs(values: &[Vec<f64>]) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    for a in 0..values.len() {
        for b in a + 1..values.len() {
            let clean = |v: &Vec<f64>| v.iter().copied().filter(|x| x.is_finite()).collect::<Vec<f64>>();
            if let Some(t) = vsrlab_analysis::mann_whitney_u(&clean(&values[a]), &clean(&values[b])) {
                out.push((a, b, t.p));
            }
        }
    }
    out
}

fn size_legend_values(max: f64) -> Vec<usize> {
    let max = max.max(1.0) as usize;
    let mut v: Vec<usize> = [1, max / 4, max / 2, max].into_iter().filter(|&x| x >= 1).collect();
    v.dedup();
    v
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

fn write_best_csv(path: &Path, settings: &[Setting], bests: &[BestRobot]) -> Result<(), String> {
    let mut s = String::from("setting,run,best_fitness,voxels,elongation,compactness,gait_duration,gait_touch_area,gait_occurrences,gait_mode_interval,gait_purity\n");
    for b in bests {
        let g = b
            .features
            .as_ref()
            .map(|f| f.gait.features().map(|v| v.to_string()).join(","))
            .unwrap_or_else(|| ",,,,".into());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{g}",
            csv_field(&settings[b.setting].name),
            csv_field(&b.run),
            b.fitness,
            b.descriptors.voxels,
            b.descriptors.elongation,
            b.descriptors.compactness
        );
    }
    write(path, &s)
}

fn train_classifiers(labels: &Path, folds: usize, seed: u64, pool: &rayon::ThreadPool) -> Result<Classifiers, String> {
    let rows = read_labels(labels).map_err(|e| e.to_string())?;
    eprintln!("replaying {} labelled robots from {}…", rows.len(), labels.display());
    let feats: Vec<Result<RobotFeatures, String>> = pool.install(|| {
        rows.par_iter()
            .map(|r| {
                let robot = load_robot(&r.robot_path(labels)).map_err(|e| e.to_string())?;
                let terrain: Terrain = r
                    .terrain
                    .parse()
                    .map_err(|e| format!("{}: terrain '{}': {e}", r.robot, r.terrain))?;
                let task = Locomotion {
                    terrain,
                    duration: r.duration,
                    transient: r.transient,
                    ..Locomotion::default()
                };
                let trace = full_trace(&robot, &task, r.seed)?;
                Ok(RobotFeatures::from_trace(&trace, &FeatureParams::default()))
            })
            .collect()
    });
    let (mut sx, mut sy, mut bx, mut by) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (r, f) in rows.iter().zip(feats) {
        let f = f?;
        if !r.shape.trim().is_empty() {
            sx.push(f.morphology_vector());
            sy.push(r.shape.trim().to_string());
        }
        if !r.behaviour.trim().is_empty() {
            bx.push(f.behaviour_vector());
            by.push(r.behaviour.trim().to_string());
        }
    }
    if sx.len() < folds.max(2) || bx.len() < folds.max(2) {
        return Err(format!(
            "{}: too few labelled robots ({} with a shape, {} with a behaviour) for {folds}-fold cross-validation",
            labels.display(),
            sx.len(),
            bx.len()
        ));
    }
    let params = ForestParams {
        seed,
        ..Default::default()
    };
    // Labels come in the page's order (stratified bins): shuffle the folds, seeded.
    let shape = Classifier::train(&sx, &sy, folds, Folds::Shuffled(seed), &params);
    let behaviour = Classifier::train(&bx, &by, folds, Folds::Shuffled(seed), &params);
    Ok(Classifiers {
        shape,
        behaviour,
        examples: (sx.len(), bx.len()),
    })
}

type IsiRuns = Vec<(usize, String, Vec<SnapshotIsi>)>;
type Finals = Vec<(usize, Vec<Labelled>)>;

fn species_over_time(
    experiments: &[ExperimentData],
    settings: &[Setting],
    replays: &[Option<Replay>],
    cls: &Classifiers,
    sample: usize,
    pool: &rayon::ThreadPool,
) -> Result<(IsiRuns, Finals), String> {
    let mut isi = Vec::new();
    let mut finals = Vec::new();
    let nb = cls.behaviour.classes.len();
    for s in settings {
        for &e in &s.experiments {
            let exp = &experiments[e];
            let Some(rp) = &replays[e] else { continue };
            for r in &exp.runs {
                let mut snaps = Vec::new();
                let mut last = Vec::new();
                eprintln!(
                    "species: {} run {:02}: {} snapshots…",
                    s.name,
                    r.index,
                    r.snapshots.len()
                );
                for (evals, path) in &r.snapshots {
                    let rows = results::read_snapshot(path).map_err(|e| e.to_string())?;
                    let rows: Vec<&SnapshotRow> = rows
                        .iter()
                        .filter(|x| x.error.is_none() && x.fitness.is_some())
                        .collect();
                    let picked: Vec<&SnapshotRow> = spread(rows.len(), sample).into_iter().map(|i| rows[i]).collect();
                    let labelled: Vec<Labelled> = pool.install(|| {
                        picked
                            .par_iter()
                            .filter_map(|row| {
                                let (_, trace) = rp
                                    .row(row)
                                    .map_err(|err| eprintln!("warning: {}: {err}", path.display()))
                                    .ok()?;
                                let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
                                Some(Labelled {
                                    shape: cls.shape.predict_index(&f.morphology_vector()),
                                    behaviour: cls.behaviour.predict_index(&f.behaviour_vector()),
                                    velocity: row.velocity.unwrap_or(f64::NAN),
                                })
                            })
                            .collect()
                    });
                    if labelled.is_empty() {
                        continue;
                    }
                    let shapes: Vec<usize> = labelled.iter().map(|l| l.shape).collect();
                    let behaviours: Vec<usize> = labelled.iter().map(|l| l.behaviour).collect();
                    let species: Vec<usize> = labelled
                        .iter()
                        .map(|l| vsrlab_analysis::species_index(l.shape, l.behaviour, nb))
                        .collect();
                    snaps.push(SnapshotIsi {
                        evaluations: *evals,
                        shape: inverse_simpson(&shapes),
                        behaviour: inverse_simpson(&behaviours),
                        species: inverse_simpson(&species),
                    });
                    last = labelled;
                }
                isi.push((s.color, format!("{}/run-{:02}", exp.dir.display(), r.index), snaps));
                finals.push((s.color, last));
            }
        }
    }
    Ok((isi, finals))
}

fn write_isi_csv(
    path: &Path,
    settings: &[Setting],
    _experiments: &[ExperimentData],
    isi: &IsiRuns,
) -> Result<(), String> {
    let mut s = String::from("setting,run,evaluations,isi_species,isi_shape,isi_behaviour\n");
    for (si, run, snaps) in isi {
        for x in snaps {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                csv_field(&settings[*si].name),
                csv_field(run),
                x.evaluations,
                x.species,
                x.shape,
                x.behaviour
            );
        }
    }
    write(path, &s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_picks_evenly() {
        assert_eq!(spread(10, 0), (0..10).collect::<Vec<_>>());
        assert_eq!(spread(10, 5), vec![0, 2, 4, 6, 8]);
        assert_eq!(spread(3, 5), vec![0, 1, 2]);
        assert_eq!(size_legend_values(40.0), vec![1, 10, 20, 40]);
    }
}
