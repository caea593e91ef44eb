//! Campaigns: many experiment files × their runs in one go (`vsrlab campaign`, `vsrlab.campaign`).
//!
//! Every setting (a file, or each setting of a sweep file) gets its own output folder, written
//! exactly as `vsrlab run` writes it; all settings and all their runs go side by side, their
//! optimizers in this process and their batches on one shared pool of threads, or sent to one
//! cluster ([`Setting::evaluations`]). So many small runs keep many cores busy, and the results
//! are those of running each file alone: a run is a pure function of its seed. `resume`
//! continues every unfinished run from its checkpoint and keeps the finished ones.

use crate::config::{self, ConfigError, Experiment};
use crate::remote::Evaluations;
use crate::runner::{Flow, Observer, Progress, RunError, RunOptions, RunSummary};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// One setting of a campaign: an experiment and its output folder.
#[derive(Debug, Clone)]
pub struct Setting {
    /// Its name (the experiment's, or the sweep setting's): its folder under the campaign's.
    pub name: String,
    /// The file it comes from.
    pub file: PathBuf,
    /// The experiment.
    pub experiment: Experiment,
    /// Its output folder.
    pub out: PathBuf,
    /// Where its batches are evaluated (the campaign's shared pool by default).
    pub evaluations: Evaluations,
}

/// Why a campaign could not start or did not finish.
#[derive(Debug, thiserror::Error)]
pub enum CampaignError {
    /// No experiment file was given.
    #[error("no experiment files given")]
    Empty,
    /// A file could not be read or is not a valid experiment.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// Two settings would write the same folder.
    #[error("{name}: both {first} and {second} name a setting so; rename one (its `name`)")]
    SameName {
        /// The shared name.
        name: String,
        /// The first file.
        first: String,
        /// The second file.
        second: String,
    },
    /// Settings failed; the others stopped at their last checkpoints (or had finished).
    #[error("{}\nthe other settings stopped at their last checkpoints: run the campaign again with --resume (resume=True) to continue", failed_text(.0))]
    Settings(Vec<(String, RunError)>),
}

fn failed_text(failed: &[(String, RunError)]) -> String {
    let lines: Vec<String> = failed.iter().map(|(name, e)| format!("{name}: {e}")).collect();
    lines.join("\n")
}

/// The settings of `files` (a sweep file gives one per setting), each in `out/<name>`; two
/// settings of one name are refused.
pub fn settings(files: &[PathBuf], out: &Path) -> Result<Vec<Setting>, CampaignError> {
    if files.is_empty() {
        return Err(CampaignError::Empty);
    }
    let mut settings: Vec<Setting> = Vec::new();
    for file in files {
        let stem = file
            .file_stem()
            .map_or("experiment".into(), |s| s.to_string_lossy().into_owned());
        for experiment in config::load_all(file)? {
            let name = experiment.name.clone().unwrap_or_else(|| stem.clone());
            if let Some(other) = settings.iter().find(|s| s.name == name) {
                return Err(CampaignError::SameName {
                    name,
                    first: other.file.display().to_string(),
                    second: file.display().to_string(),
                });
            }
            settings.push(Setting {
                out: out.join(&name),
                name,
                file: file.clone(),
                experiment,
                evaluations: Evaluations::Local,
            });
        }
    }
    Ok(settings)
}

/// What a campaign reports: its settings' runs, each with the setting's index.
pub trait CampaignObserver: Send {
    /// A run of setting `setting` starts (or resumes, with `progress` where it left off).
    fn run_started(&mut self, _setting: usize, _progress: &Progress) {}
    /// A generation of a run of setting `setting` ended.
    fn generation(&mut self, _setting: usize, _progress: &Progress) -> Flow {
        Flow::Continue
    }
    /// A run of setting `setting` ended, or was found finished when resuming.
    fn run_finished(&mut self, _setting: usize, _summary: &RunSummary) {}
    /// Something the user should know about setting `setting`.
    fn notice(&mut self, _setting: usize, _message: &str) {}
}

/// What one setting of a campaign ended with.
#[derive(Debug, Clone)]
pub struct SettingResult {
    /// The setting's name.
    pub name: String,
    /// Its folder.
    pub out: PathBuf,
    /// Its finished runs' summaries (all of them when it finished).
    pub summaries: Vec<RunSummary>,
    /// Its number of runs.
    pub runs: usize,
}

/// Runs every setting's runs side by side: optimizers here, batches on one pool of `threads`
/// (`options.threads`) or where each setting's [`Setting::evaluations`] sends them. When a
/// setting fails (a batch that cannot finish, a full disk), every other run stops at its next
/// checkpoint, and the failures come back together, by name.
pub fn run_campaign(
    settings: &[Setting],
    options: &RunOptions,
    observer: &mut dyn CampaignObserver,
) -> Result<Vec<SettingResult>, CampaignError> {
    let pool = crate::runner::pool_of(options).map_err(|e| CampaignError::Settings(vec![("campaign".into(), e)]))?;
    let shared = Mutex::new(observer);
    let indexed: Vec<(usize, &Setting)> = settings.iter().enumerate().collect();
    let outcomes = crate::runner::side_by_side(&indexed, "setting", |&(index, setting), stop| {
        let options = RunOptions {
            evaluations: setting.evaluations.clone(),
            pool: Some(pool.clone()),
            concurrent_runs: true,
            ..options.clone()
        };
        let mut relay = SettingRelay {
            index,
            shared: &shared,
            stop,
        };
        crate::run_configured(&setting.experiment, &setting.out, &options, &mut relay)
    });
    let mut results = Vec::new();
    let mut failed = Vec::new();
    for (setting, outcome) in settings.iter().zip(outcomes) {
        match outcome {
            Ok(summaries) => results.push(SettingResult {
                name: setting.name.clone(),
                out: setting.out.clone(),
                summaries,
                runs: setting.experiment.runs,
            }),
            Err(e) => failed.push((setting.name.clone(), e)),
        }
    }
    if failed.is_empty() {
        Ok(results)
    } else {
        Err(CampaignError::Settings(failed))
    }
}

/// A setting's view of the campaign's observer: a runner [`Observer`] that adds its index.
struct SettingRelay<'a, 'b> {
    index: usize,
    shared: &'a Mutex<&'b mut dyn CampaignObserver>,
    /// Set when a setting failed: every run stops at its next checkpoint.
    stop: &'a AtomicBool,
}

impl<'a, 'b> SettingRelay<'a, 'b> {
    fn lock(&self) -> std::sync::MutexGuard<'a, &'b mut dyn CampaignObserver> {
        self.shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl Observer for SettingRelay<'_, '_> {
    fn run_started(&mut self, progress: &Progress) {
        self.lock().run_started(self.index, progress);
    }
    fn generation(&mut self, progress: &Progress) -> Flow {
        let flow = self.lock().generation(self.index, progress);
        if self.stop.load(Ordering::SeqCst) {
            Flow::Interrupt
        } else {
            flow
        }
    }
    fn run_finished(&mut self, summary: &RunSummary) {
        self.lock().run_finished(self.index, summary);
    }
    fn notice(&mut self, message: &str) {
        self.lock().notice(self.index, message);
    }
}

/// Where a campaign stands: every run's share done, for progress lines and an ETA.
#[derive(Debug, Clone, PartialEq)]
pub struct Standing {
    /// Per setting, per run: the fraction done (1 when finished).
    pub fractions: Vec<Vec<f64>>,
}

impl Standing {
    /// Nothing done yet, for settings of these run counts.
    pub fn new(runs: &[usize]) -> Standing {
        Standing {
            fractions: runs.iter().map(|&n| vec![0.0; n]).collect(),
        }
    }

    /// Records a run's progress (a finished run: 1).
    pub fn set(&mut self, setting: usize, run: usize, fraction: f64) {
        if let Some(f) = self.fractions.get_mut(setting).and_then(|s| s.get_mut(run)) {
            *f = fraction.clamp(0.0, 1.0);
        }
    }

    /// The campaign's share done: the mean over all runs.
    pub fn fraction(&self) -> f64 {
        let all: Vec<f64> = self.fractions.iter().flatten().copied().collect();
        if all.is_empty() {
            1.0
        } else {
            all.iter().sum::<f64>() / all.len() as f64
        }
    }

    /// Finished runs and all runs.
    pub fn runs_done(&self) -> (usize, usize) {
        let all = self.fractions.iter().flatten();
        let done = all.clone().filter(|&&f| f >= 1.0).count();
        (done, all.count())
    }

    /// Seconds left at this pace after `elapsed` seconds (`None` before any progress), counting
    /// from `start` (the share done when this session began, e.g. a resumed campaign's).
    pub fn eta(&self, start: f64, elapsed: f64) -> Option<f64> {
        let done = self.fraction() - start;
        (done > 1e-9).then(|| elapsed * (1.0 - self.fraction()) / done)
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 {
        f64::NAN
    } else {
        sum / n as f64
    }
}

/// The campaign's summary, one line per setting: runs finished, evaluations, the best of the
/// runs' bests and their median (by the first objective's sense: smaller is better when
/// minimised), and the mean wall-clock seconds of a run.
pub fn table(settings: &[Setting], results: &[SettingResult]) -> String {
    let width = settings.iter().map(|s| s.name.len()).max().unwrap_or(7).max(7);
    let mut text = format!(
        "{:<width$}  {:>5}  {:>11}  {:>12}  {:>12}  {:>9}\n",
        "setting", "runs", "evaluations", "best", "median best", "s per run"
    );
    for result in results {
        let Some(setting) = settings.iter().find(|s| s.name == result.name) else {
            continue;
        };
        let sense = setting.experiment.senses().first().copied().unwrap_or_default();
        let mut bests: Vec<f64> = result.summaries.iter().filter_map(|s| s.best_fitness).collect();
        bests.sort_by(|a, b| sense.compare(*a, *b));
        let best = bests.last().copied();
        let median = (!bests.is_empty()).then(|| {
            let n = bests.len();
            if n % 2 == 1 {
                bests[n / 2]
            } else {
                (bests[n / 2 - 1] + bests[n / 2]) / 2.0
            }
        });
        let number = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
        text.push_str(&format!(
            "{:<width$}  {:>5}  {:>11}  {:>12}  {:>12}  {:>9.1}\n",
            result.name,
            format!("{}/{}", result.summaries.len(), result.runs),
            result.summaries.iter().map(|s| s.evaluations).sum::<u64>(),
            number(best),
            number(median),
            mean(result.summaries.iter().map(|s| s.wall_seconds)),
        ));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_standing_is_the_mean_over_every_run_and_its_eta_counts_from_the_sessions_start() {
        let mut s = Standing::new(&[2, 1]);
        assert_eq!(s.fraction(), 0.0);
        assert_eq!(s.eta(0.0, 10.0), None);
        s.set(0, 0, 1.0);
        s.set(0, 1, 0.5);
        s.set(1, 0, 0.0);
        assert_eq!(s.fraction(), 0.5);
        assert_eq!(s.runs_done(), (1, 3));
        // half done in 10 s: 10 s more
        assert_eq!(s.eta(0.0, 10.0), Some(10.0));
        // a resumed campaign that started at a quarter did a quarter in 10 s: 20 s more
        assert_eq!(s.eta(0.25, 10.0), Some(20.0));
        s.set(5, 0, 1.0); // out of range: ignored
        s.set(1, 0, 7.0);
        assert_eq!(s.runs_done(), (2, 3));
    }
}
