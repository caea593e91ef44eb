//! `vsrlab plasticity`: does a Hebbian robot truly learn (thesis §5.3.4.2), and what do its
//! weights do (§5.3.4.3)?
//!
//! For the best robot of every run: one *learning episode* (seed `learning_seed`) records the
//! plastic weights at every freeze time. Then, for each freeze time t:
//! - **restart** (the thesis' protocol): new episodes on the unseen seeds `first_seed`, … start
//!   from the weights of time t with learning off;
//! - **continue**: the same unseen episodes, learning until t, frozen from then on;
//!
//! and, as the reference, **unfrozen** episodes on the same seeds. Each run scores the mean
//! fitness over its episodes; the figure shows median ± sd across runs per setting.
//!
//! The weight histograms pool the best robots' weights of a setting at each of `weights_at`
//! (seconds of the learning episode), over the 1st–99th percentile range of all of them; values
//! beyond it count in the edge bins, so diverging weights show as edge peaks.
//!
//! Files: `frozen.csv` (setting, run, protocol, time, seed, fitness), `frozen.png/.svg`,
//! `weights.csv` (setting, time, bin centre, relative frequency) and `weights.png/.svg`.

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use crate::reassess::{best_robots, BestRobot};
use crate::replay::{ReplayError, SetupReader};
use crate::thread_pool;
use rayon::prelude::*;
use std::path::PathBuf;
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::stats::{mean, median, quantile, std_dev};
use vsrlab_tasks::episode::{self, run_observed};
use vsrlab_tasks::{EpisodeError, RobotSpec, Task, TraceLevel};

/// Options of [`plasticity`].
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticityOptions {
    /// Output folders of `vsrlab run` whose robots have Hebbian brains.
    pub results: Vec<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// Freeze times (s).
    pub freeze_at: Vec<f64>,
    /// Times (s) of the weight histograms.
    pub weights_at: Vec<f64>,
    /// Seed of the learning episode.
    pub learning_seed: u64,
    /// Unseen episodes per robot and freeze time.
    pub episodes: usize,
    /// Seed of the first unseen episode.
    pub first_seed: u64,
    /// Task settings replacing the experiments' (dotted path, value).
    pub overrides: Vec<(String, serde_json::Value)>,
    /// Bins of the weight histograms.
    pub bins: usize,
    /// Worker threads (None: every core).
    pub threads: Option<usize>,
}

/// How the weights were frozen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Protocol {
    /// New episode from the snapshot, learning off (the thesis).
    Restart,
    /// Same episode, learning stops at the freeze time.
    Continue,
    /// Learning all along (the reference).
    Unfrozen,
}

impl Protocol {
    /// Lower-case name, as in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Protocol::Restart => "restart",
            Protocol::Continue => "continue",
            Protocol::Unfrozen => "unfrozen",
        }
    }
}

/// One run's mean fitness at one freeze time with one protocol.
#[derive(Debug, Clone, PartialEq)]
pub struct FrozenScore {
    /// Its setting.
    pub setting: String,
    /// `<experiment folder>/run-XX`.
    pub run: String,
    /// The protocol.
    pub protocol: Protocol,
    /// Freeze time (s); for `unfrozen`, the episode's end.
    pub time: f64,
    /// Fitness per unseen episode.
    pub fitness: Vec<f64>,
}

/// Statistics of one setting's weights at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct WeightStats {
    /// The setting.
    pub setting: String,
    /// Time (s).
    pub time: f64,
    /// Median |w|.
    pub median_abs: f64,
    /// Largest |w|.
    pub max_abs: f64,
    /// Fraction of weights with |w| > 1.
    pub beyond_one: f64,
}

/// What [`plasticity`] measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticityReport {
    /// Every (run, protocol, time).
    pub frozen: Vec<FrozenScore>,
    /// Weight statistics per setting and time.
    pub weights: Vec<WeightStats>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

impl PlasticityReport {
    /// Per setting, protocol and time: the median across runs of the mean fitness; then the
    /// weight statistics.
    pub fn to_markdown(&self) -> String {
        let mut s = String::from("| setting | protocol | freeze at [s] | median | sd |\n|---|---|---|---|---|\n");
        let mut keys: Vec<(String, Protocol, u64)> = self
            .frozen
            .iter()
            .map(|f| (f.setting.clone(), f.protocol, f.time.to_bits()))
            .collect();
        keys.sort_by(|a, b| {
            (&a.0, a.1.name(), f64::from_bits(a.2))
                .partial_cmp(&(&b.0, b.1.name(), f64::from_bits(b.2)))
                .expect("finite times")
        });
        keys.dedup();
        for (setting, protocol, time) in keys {
            let v: Vec<f64> = self
                .frozen
                .iter()
                .filter(|f| f.setting == setting && f.protocol == protocol && f.time.to_bits() == time)
                .map(|f| mean(&f.fitness))
                .collect();
            s += &format!(
                "| {setting} | {} | {} | {:.4} | {:.4} |\n",
                protocol.name(),
                f64::from_bits(time),
                median(&v),
                std_dev(&v)
            );
        }
        s += "\n| setting | t [s] | median abs(w) | max abs(w) | share abs(w) > 1 |\n|---|---|---|---|---|\n";
        for w in &self.weights {
            s += &format!(
                "| {} | {} | {:.4} | {:.3} | {:.3} |\n",
                w.setting, w.time, w.median_abs, w.max_abs, w.beyond_one
            );
        }
        s
    }
}

/// The plastic weights of `robot` at each of `times` (s) during one episode; errors when the
/// brain has no plastic weights.
pub fn weight_snapshots(
    robot: &RobotSpec,
    task: &dyn Task,
    seed: u64,
    times: &[f64],
) -> Result<Vec<Vec<f64>>, ReplayError> {
    let dt = task.rigid().map_or(f64::NAN, |rigid| rigid.physics().dt);
    let mut snapshots: Vec<Option<Vec<f64>>> = vec![None; times.len()];
    let mut last: Option<Vec<f64>> = None;
    let mut plastic = false;
    let mut capture = vsrlab_body::Capture::new();
    run_observed(robot, task, seed, TraceLevel::None, &mut |t, agent| {
        let Some(brain) = agent.brain() else {
            return;
        };
        brain.publish(&mut capture);
        let Some(w) = capture.get(vsrlab_brain::PLASTIC_WEIGHTS.name) else {
            return;
        };
        plastic = true;
        for (slot, &at) in snapshots.iter_mut().zip(times) {
            // the weights after the step ending at `at` (at = 0: after the first step, one
            // update away from the initial weights)
            if slot.is_none() && t >= at - 0.5 * dt {
                *slot = Some(w.to_vec());
            }
        }
        // the latest weights, for times beyond the episode: kept only while some are unfilled
        if snapshots.iter().any(Option::is_none) {
            match &mut last {
                Some(l) => l.copy_from_slice(w),
                None => last = Some(w.to_vec()),
            }
        }
    })?;
    if !plastic {
        return Err(ReplayError::Episode(EpisodeError::Invalid(format!(
            "robot.brain: a {} brain has no plastic weights (use a hebbian brain)",
            robot.brain.kind()
        ))));
    }
    // times beyond the episode take the final weights
    Ok(snapshots
        .into_iter()
        .map(|s| s.or_else(|| last.clone()).unwrap_or_default())
        .collect())
}

/// Freeze tests and weight histograms for the best robot of every run.
pub fn plasticity(
    options: &PlasticityOptions,
    setups: &dyn SetupReader,
    progress: &dyn Progress,
) -> Result<PlasticityReport, AnalysisError> {
    check_options(options)?;
    let (_, robots) = best_robots(&options.results, &options.overrides, setups, progress)?;
    create_folder(&options.out)?;
    let pool = thread_pool(options.threads)?;
    let mut times: Vec<f64> = options.freeze_at.clone();
    times.extend(&options.weights_at);
    progress.note(&format!(
        "{} best robots: learning episodes, then {} freeze times × {} episodes × 2 protocols",
        robots.len(),
        options.freeze_at.len(),
        options.episodes
    ));
    let snapshots: Vec<Vec<Vec<f64>>> = pool.install(|| {
        robots
            .par_iter()
            .map(|b| {
                weight_snapshots(&b.robot, b.task.task(), options.learning_seed, &times).map_err(|e| replay_error(b, e))
            })
            .collect::<Result<_, _>>()
    })?;
    let seeds: Vec<u64> = (0..options.episodes as u64).map(|k| options.first_seed + k).collect();
    let mut jobs = Vec::new();
    for (r, robot) in robots.iter().enumerate() {
        for (k, &t) in options.freeze_at.iter().enumerate() {
            jobs.push((r, Protocol::Restart, k, t));
            jobs.push((r, Protocol::Continue, k, t));
        }
        jobs.push((r, Protocol::Unfrozen, 0, robot.task.task().duration()));
    }
    let frozen: Vec<FrozenScore> = pool.install(|| {
        jobs.par_iter()
            .map(|&(r, protocol, k, t)| {
                let b = &robots[r];
                let mut robot = b.robot.clone();
                let changed = match protocol {
                    Protocol::Restart => robot.brain.as_kind_mut().freeze_with(&snapshots[r][k]),
                    Protocol::Continue => robot.brain.as_kind_mut().stop_learning_at(t),
                    Protocol::Unfrozen => Ok(()),
                };
                changed.map_err(|e| AnalysisError::Option {
                    option: "results",
                    message: format!("{}: {e}", b.run),
                })?;
                let fitness = seeds
                    .iter()
                    .map(|&seed| {
                        let out = episode::run(&robot, b.task.task(), seed, TraceLevel::None)
                            .map_err(|e| replay_error(b, ReplayError::Episode(e)))?;
                        Ok(out.fitness.first().copied().unwrap_or(f64::NAN))
                    })
                    .collect::<Result<Vec<f64>, AnalysisError>>()?;
                Ok(FrozenScore {
                    setting: b.setting.clone(),
                    run: b.run.clone(),
                    protocol,
                    time: t,
                    fitness,
                })
            })
            .collect::<Result<_, AnalysisError>>()
    })?;
    let mut files = Vec::new();
    let csv = options.out.join("frozen.csv");
    write_output(&csv, frozen_csv(&frozen, &seeds).as_bytes())?;
    files.push(csv);
    files.extend(plot::save(
        &frozen_figure(&robots, &frozen, options),
        &options.out.join("frozen"),
    )?);
    let n_freeze = options.freeze_at.len();
    let (weights_csv, figure, weights) = weight_histograms(&robots, &snapshots, n_freeze, options);
    let path = options.out.join("weights.csv");
    write_output(&path, weights_csv.as_bytes())?;
    files.push(path);
    files.extend(plot::save(&figure, &options.out.join("weights"))?);
    Ok(PlasticityReport { frozen, weights, files })
}

fn check_options(options: &PlasticityOptions) -> Result<(), AnalysisError> {
    let bad = |option, message: String| Err(AnalysisError::Option { option, message });
    if options.episodes == 0 {
        return bad("episodes", "must be at least 1".into());
    }
    if options.bins < 2 {
        return bad("bins", format!("must be at least 2, got {}", options.bins));
    }
    for (option, times) in [("freeze-at", &options.freeze_at), ("weights-at", &options.weights_at)] {
        if let Some(t) = times.iter().find(|t| !(t.is_finite() && **t >= 0.0)) {
            return bad(option, format!("times must be ≥ 0 seconds, got {t}"));
        }
    }
    Ok(())
}

fn replay_error(b: &BestRobot, source: ReplayError) -> AnalysisError {
    AnalysisError::Replay {
        robot: b.run.clone(),
        source,
    }
}

fn frozen_csv(frozen: &[FrozenScore], seeds: &[u64]) -> String {
    let mut s = String::from("setting,run,protocol,time,seed,fitness\n");
    for f in frozen {
        for (seed, v) in seeds.iter().zip(&f.fitness) {
            s += &format!("{},{},{},{},{seed},{v}\n", f.setting, f.run, f.protocol.name(), f.time);
        }
    }
    s
}

/// One panel per setting: median ± sd across runs vs freeze time, per protocol.
fn frozen_figure(robots: &[BestRobot], frozen: &[FrozenScore], options: &PlasticityOptions) -> BandFigure {
    let mut names: Vec<&str> = robots.iter().map(|b| b.setting.as_str()).collect();
    names.dedup();
    let panels = names
        .iter()
        .map(|&setting| {
            let series = [Protocol::Restart, Protocol::Continue, Protocol::Unfrozen]
                .iter()
                .enumerate()
                .map(|(color, &protocol)| {
                    let column = |t: f64| -> Vec<f64> {
                        frozen
                            .iter()
                            .filter(|f| f.setting == setting && f.protocol == protocol)
                            .filter(|f| protocol == Protocol::Unfrozen || f.time == t)
                            .map(|f| mean(&f.fitness))
                            .collect()
                    };
                    BandSeries {
                        label: match protocol {
                            Protocol::Restart => "frozen from the snapshot, new episode (thesis)".into(),
                            Protocol::Continue => "learning until t, frozen after".into(),
                            Protocol::Unfrozen => "never frozen".into(),
                        },
                        color,
                        x: options.freeze_at.clone(),
                        center: options.freeze_at.iter().map(|&t| median(&column(t))).collect(),
                        spread: options.freeze_at.iter().map(|&t| std_dev(&column(t))).collect(),
                    }
                })
                .collect();
            BandChart {
                title: setting.to_string(),
                x_label: "weights frozen at [s]".into(),
                y_label: "velocity [length units/s]".into(),
                series,
            }
        })
        .collect();
    BandFigure {
        title: format!(
            "frozen weights or attention: mean over {} unseen episodes, median ± sd across runs",
            options.episodes
        ),
        panels,
        legend_title: "protocol".into(),
        note: vsrlab_analysis::plot::band::median_sd_note(),
    }
}

/// The weight histograms (CSV, figure, statistics) of the snapshots at `weights_at`, which
/// follow the `n_freeze` freeze-time snapshots of every robot.
fn weight_histograms(
    robots: &[BestRobot],
    snapshots: &[Vec<Vec<f64>>],
    n_freeze: usize,
    options: &PlasticityOptions,
) -> (String, BandFigure, Vec<WeightStats>) {
    let mut names: Vec<&str> = robots.iter().map(|b| b.setting.as_str()).collect();
    names.dedup();
    let mut csv = String::from("setting,time,bin_center,relative_frequency\n");
    let mut stats = Vec::new();
    let mut panels = Vec::new();
    for &setting in &names {
        let pooled = |k: usize| -> Vec<f64> {
            robots
                .iter()
                .zip(snapshots)
                .filter(|(b, _)| b.setting == setting)
                .flat_map(|(_, s)| s[n_freeze + k].iter().copied())
                .collect()
        };
        let all: Vec<f64> = (0..options.weights_at.len()).flat_map(pooled).collect();
        let (lo, hi) = (quantile(&all, 0.01), quantile(&all, 0.99));
        let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 1.0, lo + 1.0) };
        let mut series = Vec::new();
        for (k, &t) in options.weights_at.iter().enumerate() {
            let w = pooled(k);
            let (centers, freq) = histogram(&w, lo, hi, options.bins);
            for (c, f) in centers.iter().zip(&freq) {
                csv += &format!("{setting},{t},{c},{f}\n");
            }
            let abs: Vec<f64> = w.iter().map(|x| x.abs()).collect();
            stats.push(WeightStats {
                setting: setting.to_string(),
                time: t,
                median_abs: median(&abs),
                max_abs: abs.iter().copied().fold(0.0, f64::max),
                beyond_one: abs.iter().filter(|&&a| a > 1.0).count() as f64 / abs.len().max(1) as f64,
            });
            series.push(BandSeries {
                label: format!("t = {t} s"),
                color: k,
                spread: vec![0.0; freq.len()],
                x: centers,
                center: freq,
            });
        }
        panels.push(BandChart {
            title: setting.to_string(),
            x_label: "weight (edge bins hold everything beyond)".into(),
            y_label: "relative frequency".into(),
            series,
        });
    }
    let figure = BandFigure {
        title: "weights of the best robots during the learning episode".into(),
        panels,
        legend_title: "time".into(),
        note: vec!["pooled over the runs'".into(), "best robots".into()],
    };
    (csv, figure, stats)
}

/// Relative frequencies of `values` in `bins` equal bins over [lo, hi]; values outside count in
/// the edge bins. Returns (bin centres, frequencies).
pub fn histogram(values: &[f64], lo: f64, hi: f64, bins: usize) -> (Vec<f64>, Vec<f64>) {
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for &v in values.iter().filter(|v| v.is_finite()) {
        let b = ((v - lo) / width).floor().clamp(0.0, (bins - 1) as f64) as usize;
        counts[b] += 1;
    }
    let n = counts.iter().sum::<usize>().max(1) as f64;
    let centers = (0..bins).map(|b| lo + (b as f64 + 0.5) * width).collect();
    (centers, counts.iter().map(|&c| c as f64 / n).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_tasks::Locomotion;

    #[test]
    fn histogram_counts_outliers_in_the_edge_bins() {
        let (centers, freq) = histogram(&[-5.0, 0.1, 0.2, 0.6, 9.0, f64::NAN], 0.0, 1.0, 2);
        assert_eq!(centers, vec![0.25, 0.75]);
        assert_eq!(freq, vec![0.6, 0.4]);
    }

    #[test]
    fn snapshots_start_at_zero_and_move() {
        let robot = RobotSpec::from_short_forms("biped-4x3", "2021", "low_biped-0-f", "hebbian").unwrap();
        let task = Locomotion {
            duration: 2.0,
            ..Locomotion::default()
        };
        let s = weight_snapshots(&robot, &task, 0, &[0.0, 1.0, 5.0]).unwrap();
        assert_eq!(s.len(), 3);
        assert_eq!(s[0].len(), 162);
        // the first snapshot is taken after the first step's update, so only one update away from 0
        assert!(s[0].iter().all(|w| w.abs() < 0.1), "{:?}", &s[0][..4]);
        assert_ne!(s[1], s[0]);
        // past the end: the final weights, those after the last step
        let steps = vsrlab_tasks::episode::run(&robot, &task, 0, TraceLevel::None)
            .unwrap()
            .steps;
        let last_t = steps as f64 / 60.0;
        assert_eq!(s[2], weight_snapshots(&robot, &task, 0, &[last_t]).unwrap()[0]);
        assert_ne!(
            s[2],
            weight_snapshots(&robot, &task, 0, &[last_t - 1.0 / 60.0]).unwrap()[0]
        );
        let mlp = RobotSpec::from_short_forms("biped-4x3", "2021", "low_biped-0-f", "mlp").unwrap();
        let err = weight_snapshots(&mlp, &task, 0, &[1.0]).unwrap_err();
        assert!(err.to_string().contains("no plastic weights"), "{err}");
    }
}
