//! `vsrlab codesign`: the analyses of thesis ch. 5.2 (§5.2.5.5–8) over co-design runs (the
//! `material-grid` and `cppn` genotype kinds), read from the snapshots, whose records carry each
//! body's learning curve (`learning_curve`: the off-line reward per step before PPO and after
//! each of its iterations) and its material grid.
//!
//! - **Learning curves** (fig. 5.17): for each run, the populations of four stages of evolution
//!   (the first snapshot, the snapshots nearest 1/3 and 2/3 of the run's evaluations, the last);
//!   each member's curve smoothed by a moving average over `window` iterations
//!   (r̄′(j) = mean of r̄(j … j + window − 1)), the median across the population per iteration;
//!   then median ± sd across runs.
//! - **Learning radius** (fig. 5.18): ρ = r̄′ at the end of learning − r̄′ at its start, the median
//!   across the final population of a run; one value per run, boxplots per setting with the
//!   Mann–Whitney p-value of the two encodings of a task (settings named `…-direct-<task>` and
//!   `…-cppn-<task>`).
//! - **Learning over evolution**: the population's median ρ, initial and final r̄′, and learning
//!   speed (the gain in the first third of training, r̄′(⌊(n − 1)/3⌋) − r̄′(0)) at every
//!   snapshot.
//! - **Morphology descriptors** (fig. 5.19): the population's mean share of cells present and
//!   of rigid, soft, horizontal and vertical actuator voxels at every snapshot.
//! - **Fitness** (fig. 5.14): the best fitness after each generation.
//!
//! Files: `learning-curves.csv`, `learning-radius.csv`, `over-evolution.csv` and a PNG and SVG
//! of each figure: `learning-curves`, `learning-radius`, `learning-over-evolution`, `materials`,
//! `fitness`.

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use std::fmt::Write as _;
use std::path::PathBuf;
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries, BoxFigure, BoxGroup};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::{discover, read_snapshot, settings, ExperimentData};
use vsrlab_analysis::rows::SnapshotRow;
use vsrlab_analysis::stats::{mann_whitney_u, mean, median, std_dev};

/// The series name of a learning curve in an evaluation record.
pub const LEARNING_CURVE: &str = "learning_curve";

/// Options of [`codesign`].
#[derive(Debug, Clone, PartialEq)]
pub struct CodesignOptions {
    /// Output folders of `vsrlab run` (or folders above them).
    pub results: Vec<PathBuf>,
    /// Output folder for the tables and figures.
    pub out: PathBuf,
    /// Iterations of the moving average (the thesis: 10); cut to a curve's length.
    pub window: usize,
}

/// One population's learning, at one snapshot of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct PopulationLearning {
    /// Setting (experiment name).
    pub setting: String,
    /// Run index.
    pub run: usize,
    /// Evaluations at the snapshot.
    pub evaluations: u64,
    /// Median across members of the smoothed curve, per iteration.
    pub curve: Vec<f64>,
    /// Median across members of ρ.
    pub radius: f64,
    /// Median across members of the smoothed curve's first value.
    pub initial: f64,
    /// Median across members of the smoothed curve's last value.
    pub last: f64,
    /// Learning speed: median across members of the gain in the first third of training,
    /// r̄′(⌊(len − 1)/3⌋) − r̄′(0), the share of ρ learned early.
    pub early_gain: f64,
    /// Mean across members of the five morphology descriptors.
    pub materials: [f64; 5],
}

/// What [`codesign`] found and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct CodesignReport {
    /// Every snapshot of every run with learning curves.
    pub populations: Vec<PopulationLearning>,
    /// Per setting: the final best fitness of each run.
    pub best: Vec<(String, Vec<f64>)>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// The names of the morphology descriptors, in [`PopulationLearning::materials`] order.
pub const DESCRIPTORS: [&str; 5] = ["size", "rigid", "soft", "horizontal", "vertical"];

/// The moving average of `curve` over `window` points (r̄′(j), j = 0 … len − window).
pub fn moving_average(curve: &[f64], window: usize) -> Vec<f64> {
    let w = window.clamp(1, curve.len().max(1));
    curve.windows(w).map(mean).collect()
}

/// The descriptors of a material grid's rows (digits 0–4): the share of cells present, then the
/// shares of present voxels that are rigid (1), soft (2), horizontal (3) and vertical (4).
pub fn descriptors(rows: &str) -> [f64; 5] {
    let cells: Vec<char> = rows.chars().filter(|c| c.is_ascii_digit()).collect();
    let present = cells.iter().filter(|&&c| c != '0').count();
    let share = |d: char| cells.iter().filter(|&&c| c == d).count() as f64 / present.max(1) as f64;
    [
        present as f64 / cells.len().max(1) as f64,
        share('1'),
        share('2'),
        share('3'),
        share('4'),
    ]
}

/// One snapshot's population as a [`PopulationLearning`]; `None` when no member recorded a
/// learning curve.
fn population(
    setting: &str,
    run: usize,
    evaluations: u64,
    rows: &[SnapshotRow],
    window: usize,
) -> Option<PopulationLearning> {
    let records: Vec<_> = rows.iter().filter_map(|r| r.record.as_ref()).collect();
    let curves: Vec<Vec<f64>> = records
        .iter()
        .filter_map(|r| r.series.get(LEARNING_CURVE))
        .filter(|c| !c.is_empty())
        .map(|c| moving_average(c, window))
        .collect();
    let length = curves.iter().map(Vec::len).min()?;
    let at = |j: usize| median(&curves.iter().map(|c| c[j]).collect::<Vec<_>>());
    let bodies: Vec<[f64; 5]> = records
        .iter()
        .filter_map(|r| r.body.as_deref())
        .map(descriptors)
        .collect();
    let mut materials = [f64::NAN; 5];
    for (k, m) in materials.iter_mut().enumerate() {
        *m = mean(&bodies.iter().map(|d| d[k]).collect::<Vec<_>>());
    }
    Some(PopulationLearning {
        setting: setting.to_string(),
        run,
        evaluations,
        curve: (0..length).map(at).collect(),
        radius: median(&curves.iter().map(|c| c[c.len() - 1] - c[0]).collect::<Vec<_>>()),
        initial: median(&curves.iter().map(|c| c[0]).collect::<Vec<_>>()),
        last: median(&curves.iter().map(|c| c[c.len() - 1]).collect::<Vec<_>>()),
        early_gain: median(&curves.iter().map(|c| c[(c.len() - 1) / 3] - c[0]).collect::<Vec<_>>()),
        materials,
    })
}

/// Every snapshot of every run of `experiment`, as populations.
fn experiment_populations(
    experiment: &ExperimentData,
    window: usize,
    progress: &dyn Progress,
) -> Result<Vec<PopulationLearning>, AnalysisError> {
    let mut out = Vec::new();
    for run in &experiment.runs {
        for (evaluations, path) in &run.snapshots {
            let rows = read_snapshot(path)?;
            match population(&experiment.name, run.index, *evaluations, &rows, window) {
                Some(p) => out.push(p),
                None => progress.note(&format!("{}: no learning curves, skipped", path.display())),
            }
        }
    }
    Ok(out)
}

/// The stages of a run's snapshots (fig. 5.17): the first, those nearest 1/3 and 2/3 of the
/// last one's evaluations, and the last; each with its label.
fn stages(populations: &[&PopulationLearning]) -> Vec<(&'static str, usize)> {
    let Some(last) = populations.iter().map(|p| p.evaluations).max() else {
        return Vec::new();
    };
    let nearest = |target: f64| {
        (0..populations.len())
            .min_by(|&a, &b| {
                let d = |i: usize| (populations[i].evaluations as f64 - target).abs();
                d(a).total_cmp(&d(b))
            })
            .expect("populations")
    };
    let first = (0..populations.len())
        .min_by_key(|&i| populations[i].evaluations)
        .expect("populations");
    vec![
        ("start", first),
        ("1/3", nearest(last as f64 / 3.0)),
        ("2/3", nearest(2.0 * last as f64 / 3.0)),
        ("end", nearest(last as f64)),
    ]
}

/// Groups of stages that are the same population in every run (with few snapshots, "start",
/// "1/3" and "2/3" can all be the first): their curves lie on top of each other, so the panel
/// says so.
fn coinciding_stages(runs: &[Vec<(&'static str, usize)>]) -> Vec<Vec<&'static str>> {
    let Some(first) = runs.first().filter(|r| !r.is_empty()) else {
        return Vec::new();
    };
    if runs.iter().any(|r| r.len() != first.len()) {
        return Vec::new();
    }
    let same = |k: usize| runs.iter().all(|r| r[k].1 == r[k + 1].1);
    let mut groups: Vec<Vec<&'static str>> = Vec::new();
    let mut current = vec![first[0].0];
    for k in 0..first.len() - 1 {
        if !same(k) {
            groups.push(std::mem::take(&mut current));
        }
        current.push(first[k + 1].0);
    }
    groups.push(current);
    groups.retain(|g| g.len() > 1);
    groups
}

/// A panel's coinciding stages, as "start = 1/3 = 2/3" (groups joined by "; "), or empty.
fn coinciding_label(runs: &[Vec<(&'static str, usize)>]) -> String {
    let groups: Vec<String> = coinciding_stages(runs).iter().map(|g| g.join(" = ")).collect();
    groups.join("; ")
}

/// The figure's note on coinciding stages, from each panel's (setting, label): one line for
/// all panels when they agree, else one line per panel that has any.
fn coinciding_note(panels: &[(String, String)]) -> Vec<String> {
    let with: Vec<&(String, String)> = panels.iter().filter(|(_, c)| !c.is_empty()).collect();
    let Some(first) = with.first() else {
        return Vec::new();
    };
    if with.len() == panels.len() && with.iter().all(|(_, c)| *c == first.1) {
        return vec![format!("{}:", first.1), "the same population".into()];
    }
    let mut lines = vec!["the same population:".to_string()];
    lines.extend(with.iter().map(|(name, c)| format!("{name}: {c}")));
    lines
}

/// Median and sd across runs of equal-length prefixes of `curves`.
fn across_runs(curves: &[&[f64]]) -> (Vec<f64>, Vec<f64>) {
    let length = curves.iter().map(|c| c.len()).min().unwrap_or(0);
    (0..length)
        .map(|j| {
            let v: Vec<f64> = curves.iter().map(|c| c[j]).collect();
            (median(&v), if v.len() > 1 { std_dev(&v) } else { 0.0 })
        })
        .unzip()
}

/// The populations of one setting, grouped by run.
fn runs_of<'a>(populations: &'a [PopulationLearning], setting: &str) -> Vec<Vec<&'a PopulationLearning>> {
    let mut runs: Vec<usize> = populations
        .iter()
        .filter(|p| p.setting == setting)
        .map(|p| p.run)
        .collect();
    runs.sort_unstable();
    runs.dedup();
    runs.iter()
        .map(|&r| {
            let mut of_run: Vec<&PopulationLearning> = populations
                .iter()
                .filter(|p| p.setting == setting && p.run == r)
                .collect();
            of_run.sort_by_key(|p| p.evaluations);
            of_run
        })
        .collect()
}

/// Figure 5.17: one panel per setting, one curve per stage.
fn curves_figure(names: &[String], populations: &[PopulationLearning], window: usize) -> (BandFigure, String) {
    let mut csv = String::from("setting,stage,run,evaluations,iteration,median_reward\n");
    let (panels, coinciding): (Vec<BandChart>, Vec<(String, String)>) = names
        .iter()
        .map(|name| {
            let runs = runs_of(populations, name);
            let indices: Vec<Vec<(&'static str, usize)>> = runs.iter().map(|r| stages(r)).collect();
            let staged: Vec<Vec<(&str, &PopulationLearning)>> = runs
                .iter()
                .zip(&indices)
                .map(|(r, s)| s.iter().map(|&(label, i)| (label, r[i])).collect())
                .collect();
            for (run, stages) in runs.iter().zip(&staged) {
                for (label, p) in stages {
                    for (j, v) in p.curve.iter().enumerate() {
                        let _ = writeln!(csv, "{name},{label},{},{},{j},{v}", run[0].run, p.evaluations);
                    }
                }
            }
            let series = ["start", "1/3", "2/3", "end"]
                .iter()
                .enumerate()
                .map(|(k, label)| {
                    let curves: Vec<&[f64]> = staged
                        .iter()
                        .filter_map(|s| s.iter().find(|(l, _)| l == label).map(|(_, p)| p.curve.as_slice()))
                        .collect();
                    let (center, spread) = across_runs(&curves);
                    BandSeries {
                        label: format!("{label} of evolution"),
                        color: k,
                        x: (0..center.len()).map(|j| j as f64).collect(),
                        center,
                        spread,
                    }
                })
                .collect();
            let chart = BandChart {
                title: name.clone(),
                x_label: "PPO iteration".into(),
                y_label: format!("reward per step, moving average of {window}"),
                series,
            };
            (chart, (name.clone(), coinciding_label(&indices)))
        })
        .unzip();
    let mut note = population_note();
    note.extend(coinciding_note(&coinciding));
    let figure = BandFigure {
        title: "Learning curves at four stages of evolution".into(),
        panels,
        legend_title: "population".into(),
        note,
    };
    (figure, csv)
}

/// The final population's radius of each run of a setting.
fn final_radii(populations: &[PopulationLearning], setting: &str) -> Vec<f64> {
    runs_of(populations, setting)
        .iter()
        .filter_map(|r| r.last().map(|p| p.radius))
        .collect()
}

/// The (direct, cppn) settings of the same task: names equal but for `direct` / `cppn`.
fn encoding_pairs(names: &[String]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for (i, a) in names.iter().enumerate() {
        for (j, b) in names.iter().enumerate() {
            if a.contains("direct") && a.replacen("direct", "cppn", 1) == *b {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

/// Figure 5.18: learning radius at the end of evolution, one box per setting.
fn radius_figure(names: &[String], populations: &[PopulationLearning]) -> BoxFigure {
    let groups: Vec<BoxGroup> = names
        .iter()
        .enumerate()
        .map(|(i, name)| BoxGroup {
            label: name.clone(),
            color: i,
            values: final_radii(populations, name),
        })
        .collect();
    let pvalues = encoding_pairs(names)
        .into_iter()
        .filter_map(|(i, j)| mann_whitney_u(&groups[i].values, &groups[j].values).map(|m| (i, j, m.p)))
        .collect();
    BoxFigure {
        title: "Learning radius at the end of evolution".into(),
        y_label: "ρ = r̄′(end) − r̄′(start)".into(),
        groups,
        pvalues,
        max_brackets: 6,
    }
}

/// Per setting, a quantity of each snapshot as median ± sd across runs over evaluations.
fn over_evolution(
    names: &[String],
    populations: &[PopulationLearning],
    value: &dyn Fn(&PopulationLearning) -> f64,
) -> Vec<BandSeries> {
    names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let runs = runs_of(populations, name);
            let points: Vec<Vec<(f64, f64)>> = runs
                .iter()
                .map(|r| r.iter().map(|p| (p.evaluations as f64, value(p))).collect())
                .collect();
            band(name, i, &points)
        })
        .collect()
}

/// One setting's curve from its runs' (x, y) points: median ± sd of y across runs at each
/// point of the shortest run, at the first run's x.
fn band(name: &str, color: usize, runs: &[Vec<(f64, f64)>]) -> BandSeries {
    let values: Vec<Vec<f64>> = runs.iter().map(|r| r.iter().map(|p| p.1).collect()).collect();
    let refs: Vec<&[f64]> = values.iter().map(Vec::as_slice).collect();
    let (center, spread) = across_runs(&refs);
    let x = runs
        .first()
        .map(|r| r.iter().map(|p| p.0).take(center.len()).collect())
        .unwrap_or_default();
    BandSeries {
        label: name.to_string(),
        color,
        x,
        center,
        spread,
    }
}

/// The note of curves of population medians, median ± sd across runs.
fn population_note() -> Vec<String> {
    vec![
        "line: median over runs".into(),
        "of the population's median".into(),
        "band: ± sd over runs".into(),
    ]
}

fn panel(title: &str, y_label: &str, series: Vec<BandSeries>) -> BandChart {
    BandChart {
        title: title.into(),
        x_label: "evaluations".into(),
        y_label: y_label.into(),
        series,
    }
}

/// Runs the analyses over every co-design experiment found under `options.results`.
pub fn codesign(options: &CodesignOptions, progress: &dyn Progress) -> Result<CodesignReport, AnalysisError> {
    if options.window == 0 {
        return Err(AnalysisError::Option {
            option: "window",
            message: "must be at least 1".into(),
        });
    }
    let experiments = discover(&options.results)?;
    let mut populations = Vec::new();
    let mut best = Vec::new();
    for (name, members) in settings(&experiments) {
        let mut finals = Vec::new();
        for &e in &members {
            populations.extend(experiment_populations(&experiments[e], options.window, progress)?);
            finals.extend(experiments[e].runs.iter().map(|r| r.final_best()));
        }
        best.push((name, finals));
    }
    let names: Vec<String> = best
        .iter()
        .map(|b| b.0.clone())
        .filter(|n| populations.iter().any(|p| &p.setting == n))
        .collect();
    if names.is_empty() {
        return Err(AnalysisError::Option {
            option: "results",
            message: "no snapshot holds a learning curve: give the output of co-design runs (genotype kind material-grid or cppn, learning_curve = true)".into(),
        });
    }
    create_folder(&options.out)?;
    let mut files = Vec::new();
    let (curves, curves_csv) = curves_figure(&names, &populations, options.window);
    files.extend(plot::save(&curves, &options.out.join("learning-curves"))?);
    files.extend(plot::save(
        &radius_figure(&names, &populations),
        &options.out.join("learning-radius"),
    )?);
    let learning = BandFigure {
        title: "Learning over evolution".into(),
        panels: vec![
            panel(
                "learning radius ρ",
                "reward per step",
                over_evolution(&names, &populations, &|p| p.radius),
            ),
            panel(
                "before learning",
                "reward per step",
                over_evolution(&names, &populations, &|p| p.initial),
            ),
            panel(
                "after learning",
                "reward per step",
                over_evolution(&names, &populations, &|p| p.last),
            ),
            panel(
                "learning speed: gain in the first third",
                "reward per step",
                over_evolution(&names, &populations, &|p| p.early_gain),
            ),
        ],
        legend_title: "setting".into(),
        note: population_note(),
    };
    files.extend(plot::save(&learning, &options.out.join("learning-over-evolution"))?);
    let materials = BandFigure {
        title: "Morphology over evolution (population means)".into(),
        panels: DESCRIPTORS
            .iter()
            .enumerate()
            .map(|(k, d)| panel(d, "share", over_evolution(&names, &populations, &|p| p.materials[k])))
            .collect(),
        legend_title: "setting".into(),
        note: plot::band::median_sd_note(),
    };
    files.extend(plot::save(&materials, &options.out.join("materials"))?);
    let fitness = BandFigure {
        title: "Best fitness".into(),
        panels: vec![panel(
            "best so far",
            "reward per step (eq. 5.7)",
            fitness_series(&names, &experiments),
        )],
        legend_title: "setting".into(),
        note: plot::band::median_sd_note(),
    };
    files.extend(plot::save(&fitness, &options.out.join("fitness"))?);
    let mut radius_csv = String::from("setting,run,evaluations,radius,initial,final,early_gain");
    for d in DESCRIPTORS {
        let _ = write!(radius_csv, ",mean_{d}");
    }
    radius_csv.push('\n');
    for p in &populations {
        let _ = write!(
            radius_csv,
            "{},{},{},{},{},{},{}",
            p.setting, p.run, p.evaluations, p.radius, p.initial, p.last, p.early_gain
        );
        for m in p.materials {
            let _ = write!(radius_csv, ",{m}");
        }
        radius_csv.push('\n');
    }
    for (name, text) in [("learning-curves.csv", curves_csv), ("over-evolution.csv", radius_csv)] {
        let path = options.out.join(name);
        write_output(&path, text.as_bytes())?;
        files.push(path);
    }
    let mut final_csv = String::from("setting,run,radius\n");
    for name in &names {
        for (run, r) in final_radii(&populations, name).iter().enumerate() {
            let _ = writeln!(final_csv, "{name},{run},{r}");
        }
    }
    let path = options.out.join("learning-radius.csv");
    write_output(&path, final_csv.as_bytes())?;
    files.push(path);
    Ok(CodesignReport {
        populations,
        best: best.into_iter().filter(|b| names.contains(&b.0)).collect(),
        files,
    })
}

/// The best fitness after each generation, median ± sd across a setting's runs.
fn fitness_series(names: &[String], experiments: &[ExperimentData]) -> Vec<BandSeries> {
    names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let runs: Vec<Vec<(f64, f64)>> = experiments
                .iter()
                .filter(|e| &e.name == name)
                .flat_map(|e| &e.runs)
                .map(|r| {
                    r.generations
                        .iter()
                        .map(|g| (g.evaluations as f64, g.best_fitness))
                        .collect()
                })
                .collect();
            band(name, i, &runs)
        })
        .collect()
}

impl CodesignReport {
    /// Per setting: runs, the median final best fitness, the median learning radius at the end.
    pub fn to_markdown(&self) -> String {
        let mut s = String::from(
            "| setting | runs | best fitness, median | learning radius at the end, median | final population's reward after learning, median |\n|---|---|---|---|---|\n",
        );
        for (name, finals) in &self.best {
            let radii = final_radii(&self.populations, name);
            let last: Vec<f64> = runs_of(&self.populations, name)
                .iter()
                .filter_map(|r| r.last().map(|p| p.last))
                .collect();
            let _ = writeln!(
                s,
                "| {name} | {} | {:.5} | {:.5} | {:.5} |",
                finals.len(),
                median(finals),
                median(&radii),
                median(&last)
            );
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_analysis::rows::Record;

    fn member(curve: &[f64], body: &str) -> SnapshotRow {
        SnapshotRow {
            generation: 1,
            evaluations: 10,
            index: 0,
            birth_generation: 0,
            record: Some(Record {
                seed: 0,
                fitness: curve.last().copied(),
                distance: None,
                velocity: None,
                voxels: None,
                body: Some(body.into()),
                error: None,
                objectives: None,
                series: [(LEARNING_CURVE.to_string(), curve.to_vec())].into_iter().collect(),
            }),
            descriptor: Vec::new(),
            genotype: serde_json::Value::Null,
        }
    }

    #[test]
    fn moving_averages_and_descriptors_follow_the_thesis() {
        assert_eq!(moving_average(&[1.0, 2.0, 3.0, 4.0], 2), [1.5, 2.5, 3.5]);
        assert_eq!(moving_average(&[1.0, 3.0], 10), [2.0], "the window is cut to the curve");
        let d = descriptors("33000/01100/00000/00000");
        assert_eq!(d, [0.2, 0.5, 0.0, 0.5, 0.0]);
        assert_eq!(descriptors("12/34"), [1.0, 0.25, 0.25, 0.25, 0.25]);
    }

    #[test]
    fn a_population_takes_the_median_of_its_members() {
        let rows = vec![
            member(&[0.0, 1.0, 2.0], "33/00"),
            member(&[1.0, 1.0, 1.0], "44/44"),
            member(&[2.0, 4.0, 9.0], "12/34"),
        ];
        let p = population("s", 0, 10, &rows, 2).unwrap();
        // smoothed: [0.5, 1.5], [1, 1], [3, 6.5]; medians per iteration
        assert_eq!(p.curve, [1.0, 1.5]);
        assert_eq!((p.initial, p.last, p.radius), (1.0, 1.5, 1.0));
        assert!((p.materials[0] - (0.5 + 1.0 + 1.0) / 3.0).abs() < 1e-12);
        assert!(population("s", 0, 10, &[], 2).is_none());
        // learning speed: the gain by a third of the curve (index 2 of 7), median of 4, 0, 1
        let rows = vec![
            member(&[0.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0], "3"),
            member(&[1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0], "3"),
            member(&[0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0], "3"),
        ];
        let p = population("s", 0, 10, &rows, 1).unwrap();
        assert_eq!((p.early_gain, p.radius), (1.0, 3.0));
    }

    #[test]
    fn stages_pick_the_start_thirds_and_end_and_pairs_match_encodings() {
        let p = |evaluations| PopulationLearning {
            setting: "s".into(),
            run: 0,
            evaluations,
            curve: vec![],
            radius: 0.0,
            initial: 0.0,
            last: 0.0,
            early_gain: 0.0,
            materials: [0.0; 5],
        };
        let all = [p(25), p(125), p(175), p(350), p(500)];
        let refs: Vec<&PopulationLearning> = all.iter().collect();
        let picked: Vec<u64> = stages(&refs).iter().map(|s| refs[s.1].evaluations).collect();
        assert_eq!(picked, [25, 175, 350, 500]);
        assert_eq!(coinciding_label(&[stages(&refs)]), "");
        // two snapshots (10 and 26 evaluations): start, 1/3 and 2/3 are all the first
        let two = [p(10), p(26)];
        let two: Vec<&PopulationLearning> = two.iter().collect();
        assert_eq!(coinciding_stages(&[stages(&two)]), [vec!["start", "1/3", "2/3"]]);
        assert_eq!(coinciding_label(&[stages(&two), stages(&two)]), "start = 1/3 = 2/3");
        // a stage coincides in the figure only if it does in every run
        let three = [p(10), p(20), p(30)];
        let three: Vec<&PopulationLearning> = three.iter().collect();
        assert_eq!(
            coinciding_stages(&[stages(&two), stages(&three)]),
            [vec!["start", "1/3"]]
        );
        assert!(coinciding_stages(&[]).is_empty() && coinciding_stages(&[vec![]]).is_empty());
        assert!(
            coinciding_stages(&[stages(&two), vec![]]).is_empty(),
            "a run without stages"
        );
        // the note: one line pair when every panel agrees, else a line per panel with any
        let panel = |n: &str, c: &str| (n.to_string(), c.to_string());
        let agree = [panel("a", "start = 1/3"), panel("b", "start = 1/3")];
        assert_eq!(coinciding_note(&agree), ["start = 1/3:", "the same population"]);
        let differ = [panel("a", "start = 1/3"), panel("b", ""), panel("c", "2/3 = end")];
        assert_eq!(
            coinciding_note(&differ),
            ["the same population:", "a: start = 1/3", "c: 2/3 = end"]
        );
        assert!(coinciding_note(&[panel("a", "")]).is_empty());
        let names = vec![
            "r-cppn-beam".to_string(),
            "r-direct-beam".into(),
            "r-direct-cave".into(),
        ];
        assert_eq!(encoding_pairs(&names), [(1, 0)]);
    }
}
