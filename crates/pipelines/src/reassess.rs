//! `vsrlab reassess`: the best robot of every run, replayed on unseen episodes (new random
//! terrains, optionally with damage), compared between settings (thesis §5.3.4.1, §4.2).
//!
//! Each run scores the mean of its best robot's fitness over `episodes` episodes with the seeds
//! `first_seed`, `first_seed + 1`, …; evolution never uses these seeds when they are above the
//! run's evaluation seeds (the default, 1 000 000, is). Settings are compared by the median of
//! their runs' scores and pairwise two-sided Mann–Whitney U tests. The task is each experiment's
//! own, with `overrides` applied (`duration`, `terrain`, `damage`, …).
//!
//! Files: `reassess.csv` (setting, experiment, run, seed, fitness), `reassess-boxplot.png/.svg`,
//! and `reassess-velocity-over-time.png/.svg` (the centre's velocity over sliding windows, mean
//! over episodes, median ± sd across runs: what happens around a damage).

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use crate::replay::{ReplayError, SetupReader};
use crate::settings::{settings_of, with_unit};
use crate::{read_setups, thread_pool};
use rayon::prelude::*;
use std::path::PathBuf;
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries, BoxFigure, BoxGroup};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::{self, ExperimentData};
use vsrlab_analysis::stats::{mann_whitney_u, mean, median, quantile, std_dev};
use vsrlab_tasks::files::load_robot;
use vsrlab_tasks::{episode, RobotSpec, TaskSpec, TraceLevel};

/// Options of [`reassess`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReassessOptions {
    /// Output folders of `vsrlab run` (experiments with the same name form one setting).
    pub results: Vec<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// Episodes per robot.
    pub episodes: usize,
    /// Seed of the first episode.
    pub first_seed: u64,
    /// Task settings replacing the experiments' (dotted path, value), e.g. `("damage", {…})`.
    pub overrides: Vec<(String, serde_json::Value)>,
    /// Width of the velocity windows (s) of the velocity-over-time figure.
    pub window: f64,
    /// Worker threads (None: every core).
    pub threads: Option<usize>,
}

/// One run's best robot, ready to replay.
#[derive(Debug, Clone)]
pub struct BestRobot {
    /// Its setting (experiment name).
    pub setting: String,
    /// The setting's colour index.
    pub color: usize,
    /// `<experiment folder>/run-XX`.
    pub run: String,
    /// The robot.
    pub robot: RobotSpec,
    /// The task, with the overrides.
    pub task: TaskSpec,
}

/// One run's scores.
#[derive(Debug, Clone, PartialEq)]
pub struct RunScore {
    /// Its setting.
    pub setting: String,
    /// `<experiment folder>/run-XX`.
    pub run: String,
    /// Fitness of each episode, in seed order.
    pub fitness: Vec<f64>,
    /// Their mean.
    pub score: f64,
}

/// One setting's summary.
#[derive(Debug, Clone, PartialEq)]
pub struct SettingScore {
    /// The setting.
    pub setting: String,
    /// Runs.
    pub runs: usize,
    /// Median, first and third quartile of the runs' scores.
    pub median: f64,
    /// First quartile.
    pub q1: f64,
    /// Third quartile.
    pub q3: f64,
}

/// What [`reassess`] measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ReassessReport {
    /// Every run.
    pub runs: Vec<RunScore>,
    /// Every setting, by name.
    pub settings: Vec<SettingScore>,
    /// Pairwise Mann–Whitney p-values (setting a, setting b, p).
    pub pvalues: Vec<(String, String, f64)>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

impl ReassessReport {
    /// The summary as a Markdown table, then the p-values.
    pub fn to_markdown(&self) -> String {
        let mut s = String::from("| setting | runs | median | IQR |\n|---|---|---|---|\n");
        for r in &self.settings {
            s += &format!(
                "| {} | {} | {:.4} | [{:.4}, {:.4}] |\n",
                r.setting, r.runs, r.median, r.q1, r.q3
            );
        }
        for (a, b, p) in &self.pvalues {
            s += &format!("\nMann–Whitney {a} vs {b}: {}", plot::format_p(*p));
        }
        s
    }
}

/// The best robot of every run of `results`, with each experiment's task and the overrides.
pub fn best_robots(
    results: &[PathBuf],
    overrides: &[(String, serde_json::Value)],
    setups: &dyn SetupReader,
    progress: &dyn Progress,
) -> Result<(Vec<ExperimentData>, Vec<BestRobot>), AnalysisError> {
    let experiments = results::discover(results)?;
    let settings = settings_of(&experiments);
    let readers = read_setups(&experiments, setups, progress);
    let overrides: Vec<(&str, serde_json::Value)> = overrides.iter().map(|(k, v)| (k.as_str(), v.clone())).collect();
    let mut robots = Vec::new();
    for setting in &settings {
        for (experiment, run) in setting.runs(&experiments) {
            let index = experiments
                .iter()
                .position(|e| e.dir == experiment.dir)
                .expect("listed");
            let Some(setup) = &readers[index] else { continue };
            let Some(path) = &run.best_robot else {
                progress.note(&format!("warning: {}: no best robot file, skipped", run.dir.display()));
                continue;
            };
            let task = setup
                .task
                .with_settings(&overrides)
                .map_err(|e| AnalysisError::Option {
                    option: "task",
                    message: format!("{}: {e}", experiment.dir.display()),
                })?;
            task.task().validate().map_err(|e| AnalysisError::Option {
                option: "task",
                message: e.to_string(),
            })?;
            robots.push(BestRobot {
                setting: setting.name.clone(),
                color: setting.color,
                run: experiment.run_label(run),
                robot: load_robot(path)?,
                task,
            });
        }
    }
    Ok((experiments, robots))
}

/// Replays every run's best robot on the unseen episodes and compares the settings.
pub fn reassess(
    options: &ReassessOptions,
    setups: &dyn SetupReader,
    progress: &dyn Progress,
) -> Result<ReassessReport, AnalysisError> {
    if options.episodes == 0 {
        return Err(AnalysisError::Option {
            option: "episodes",
            message: "must be at least 1".into(),
        });
    }
    if !(options.window.is_finite() && options.window > 0.0) {
        return Err(AnalysisError::Option {
            option: "window",
            message: format!("must be > 0 seconds, got {}", options.window),
        });
    }
    let (experiments, robots) = best_robots(&options.results, &options.overrides, setups, progress)?;
    create_folder(&options.out)?;
    let pool = thread_pool(options.threads)?;
    progress.note(&format!(
        "{} best robots × {} episodes (seeds {}…)",
        robots.len(),
        options.episodes,
        options.first_seed
    ));
    let seeds: Vec<u64> = (0..options.episodes as u64).map(|k| options.first_seed + k).collect();
    let jobs: Vec<(usize, u64)> = (0..robots.len())
        .flat_map(|r| seeds.iter().map(move |&s| (r, s)))
        .collect();
    let episodes: Vec<(f64, Vec<(f64, f64)>)> = pool.install(|| {
        jobs.par_iter()
            .map(|&(r, seed)| {
                let b = &robots[r];
                let out = episode::run(&b.robot, b.task.task(), seed, TraceLevel::Center).map_err(|e| {
                    AnalysisError::Replay {
                        robot: b.run.clone(),
                        source: ReplayError::Episode(e),
                    }
                })?;
                let trace = out.trace.unwrap_or_default();
                let path = trace.times.iter().zip(&trace.centers).map(|(t, c)| (*t, c.x)).collect();
                Ok((out.fitness.first().copied().unwrap_or(f64::NAN), path))
            })
            .collect::<Result<_, AnalysisError>>()
    })?;
    let runs: Vec<RunScore> = robots
        .iter()
        .enumerate()
        .map(|(r, b)| {
            let fitness: Vec<f64> = episodes[r * seeds.len()..(r + 1) * seeds.len()]
                .iter()
                .map(|e| e.0)
                .collect();
            RunScore {
                setting: b.setting.clone(),
                run: b.run.clone(),
                score: mean(&fitness),
                fitness,
            }
        })
        .collect();
    let settings = settings_of(&experiments);
    let scores: Vec<Vec<f64>> = settings
        .iter()
        .map(|s| runs.iter().filter(|r| r.setting == s.name).map(|r| r.score).collect())
        .collect();
    let summary: Vec<SettingScore> = settings
        .iter()
        .zip(&scores)
        .filter(|(_, v)| !v.is_empty())
        .map(|(s, v)| SettingScore {
            setting: s.name.clone(),
            runs: v.len(),
            median: median(v),
            q1: quantile(v, 0.25),
            q3: quantile(v, 0.75),
        })
        .collect();
    let mut pvalues = Vec::new();
    let mut pairs = Vec::new();
    for i in 0..settings.len() {
        for j in i + 1..settings.len() {
            if let Some(mw) = mann_whitney_u(&scores[i], &scores[j]) {
                pvalues.push((settings[i].name.clone(), settings[j].name.clone(), mw.p));
                pairs.push((i, j, mw.p));
            }
        }
    }
    let mut files = Vec::new();
    let csv_path = options.out.join("reassess.csv");
    write_output(&csv_path, scores_csv(&runs, &seeds).as_bytes())?;
    files.push(csv_path);
    let metric = with_unit("velocity");
    let boxes = BoxFigure {
        title: format!("best robots on {} unseen episodes (mean per run)", options.episodes),
        y_label: metric.clone(),
        groups: settings
            .iter()
            .zip(&scores)
            .map(|(s, v)| BoxGroup {
                label: s.name.clone(),
                color: s.color,
                values: v.clone(),
            })
            .collect(),
        pvalues: pairs,
        max_brackets: 6,
    };
    files.extend(plot::save(&boxes, &options.out.join("reassess-boxplot"))?);
    let series = settings
        .iter()
        .map(|s| {
            let per_run: Vec<Vec<(f64, f64)>> = robots
                .iter()
                .enumerate()
                .filter(|(_, b)| b.setting == s.name)
                .map(|(r, _)| {
                    let paths: Vec<&[(f64, f64)]> = episodes[r * seeds.len()..(r + 1) * seeds.len()]
                        .iter()
                        .map(|e| e.1.as_slice())
                        .collect();
                    mean_windowed_velocity(&paths, options.window)
                })
                .collect();
            band_series(&s.name, s.color, &per_run)
        })
        .collect();
    let over_time = BandFigure {
        title: format!("velocity over {} s windows, median ± sd across runs", options.window),
        panels: vec![BandChart {
            title: "best robots on the unseen episodes".into(),
            x_label: "time [s]".into(),
            y_label: metric,
            series,
        }],
        legend_title: "setting".into(),
        note: vsrlab_analysis::plot::band::median_sd_note(),
    };
    files.extend(plot::save(
        &over_time,
        &options.out.join("reassess-velocity-over-time"),
    )?);
    Ok(ReassessReport {
        runs,
        settings: summary,
        pvalues,
        files,
    })
}

/// The CSV of every episode: setting, run, seed, fitness.
fn scores_csv(runs: &[RunScore], seeds: &[u64]) -> String {
    let mut s = String::from("setting,run,seed,fitness\n");
    for r in runs {
        for (seed, f) in seeds.iter().zip(&r.fitness) {
            s += &format!("{},{},{seed},{f}\n", r.setting, r.run);
        }
    }
    s
}

/// Velocity of the centre over consecutive windows of `window` seconds, (window end, velocity),
/// averaged over the episodes (which share their times).
pub fn mean_windowed_velocity(paths: &[&[(f64, f64)]], window: f64) -> Vec<(f64, f64)> {
    let Some(first) = paths.first() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut start = 0;
    for (k, &(t, _)) in first.iter().enumerate() {
        if t - first[start].0 >= window - 1e-9 {
            let v: Vec<f64> = paths
                .iter()
                .filter(|p| p.len() > k)
                .map(|p| (p[k].1 - p[start].1) / (p[k].0 - p[start].0))
                .collect();
            out.push((t, mean(&v)));
            start = k;
        }
    }
    out
}

/// Median ± sd across runs of per-run curves that share their x values.
fn band_series(label: &str, color: usize, per_run: &[Vec<(f64, f64)>]) -> BandSeries {
    let len = per_run.iter().map(Vec::len).min().unwrap_or(0);
    let x = per_run
        .first()
        .map_or(Vec::new(), |c| c[..len].iter().map(|p| p.0).collect());
    let column = |k: usize| -> Vec<f64> { per_run.iter().map(|c| c[k].1).collect() };
    BandSeries {
        label: label.to_string(),
        color,
        x,
        center: (0..len).map(|k| median(&column(k))).collect(),
        spread: (0..len).map(|k| std_dev(&column(k))).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windowed_velocity_is_the_slope_over_each_window() {
        // x = 2t, sampled every 0.5 s: every 1 s window has velocity 2; a second path with x = 4t
        // averages to 3
        let a: Vec<(f64, f64)> = (1..=6).map(|k| (k as f64 * 0.5, k as f64)).collect();
        let b: Vec<(f64, f64)> = (1..=6).map(|k| (k as f64 * 0.5, 2.0 * k as f64)).collect();
        let v = mean_windowed_velocity(&[&a, &b], 1.0);
        assert_eq!(v, vec![(1.5, 3.0), (2.5, 3.0)]);
        assert!(mean_windowed_velocity(&[], 1.0).is_empty());
    }

    #[test]
    fn the_csv_has_one_row_per_episode() {
        let runs = vec![RunScore {
            setting: "s".into(),
            run: "e/run-00".into(),
            fitness: vec![1.0, 2.0],
            score: 1.5,
        }];
        assert_eq!(
            scores_csv(&runs, &[7, 8]),
            "setting,run,seed,fitness\ns,e/run-00,7,1\ns,e/run-00,8,2\n"
        );
    }
}
