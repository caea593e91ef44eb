//! `vsrlab analyze`: figures and tables from the output folders of `vsrlab run`
//! (docs/analysis.md). Settings pool the runs of same-named experiments; the best robot of every
//! run is replayed for its features; with a labels file, the individuals of every snapshot are
//! classified into species and their diversity measured.

use crate::best_robots::{best_csv, best_robots};
use crate::classifiers::{classifier_table, train_classifiers};
use crate::error::AnalysisError;
use crate::figures::{
    boxplot, column_figure, column_figures, descriptor_figure, fitness_figure, isi_figure, pca_figure, species_figure,
};
use crate::output::{create_folder, write_output};
use crate::replay::{ReplaySetup, SetupReader};
use crate::settings::{fitness_label, per_setting, settings_of, with_unit, Setting};
use crate::species::{isi_csv, species_over_time};
use crate::summary_page::SummaryPage;
use crate::{read_setups, thread_pool};
use std::path::{Path, PathBuf};
use vsrlab_analysis::plot::{self, Figure};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::report::{SettingSummary, Summary};
use vsrlab_analysis::results::{self, ExperimentData, RunData};
use vsrlab_analysis::run_folder::{BEST_ROBOT_FILE, GENERATIONS_FILE, SUMMARY_FILE};

/// What to analyse and how (the options of `vsrlab analyze`).
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyzeOptions {
    /// Output folders of `vsrlab run`, or folders above them (searched 4 levels deep).
    pub results: Vec<PathBuf>,
    /// Labels CSV (made with `vsrlab label`): turns on species, ISI and the bubble plot.
    pub labels: Option<PathBuf>,
    /// Output folder for figures and tables.
    pub out: PathBuf,
    /// With labels: individuals replayed per snapshot, evenly spread (0 = all).
    pub sample: usize,
    /// Cross-validation folds of the classifiers.
    pub folds: usize,
    /// Seed of the random forests.
    pub seed: u64,
    /// Worker threads for replays (None: every core).
    pub threads: Option<usize>,
    /// Pool runs into settings by these keys of each experiment's resolved configuration
    /// (`task.terrain`, …) instead of by experiment name ([`results::group_by`]).
    pub group_by: Vec<String>,
}

impl AnalyzeOptions {
    /// Analyse `results` into `out` with the defaults of `vsrlab analyze` (no labels, every
    /// individual, 5 folds, seed 0, every core).
    pub fn new(results: Vec<PathBuf>, out: impl Into<PathBuf>) -> AnalyzeOptions {
        AnalyzeOptions {
            results,
            labels: None,
            out: out.into(),
            sample: 0,
            folds: 5,
            seed: 0,
            threads: None,
            group_by: Vec::new(),
        }
    }
}

/// One figure written (as `NAME.png` and `NAME.svg`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FigureNote {
    /// File stem (`fitness`).
    pub name: String,
    /// What it shows, one line.
    pub description: String,
}

/// What an analysis wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisReport {
    /// The output folder.
    pub out: PathBuf,
    /// The summary table (also in `summary.md`, `summary.csv` and `pvalues.csv`).
    pub summary: Summary,
    /// The figures, in the order they were written.
    pub figures: Vec<FigureNote>,
}

/// What `summary.md` says when no labels were given.
const NO_LABELS: &str = "No labels given (--labels): species, ISI and the species bubble plot are skipped. \
     Make a labels file with `vsrlab label` and pass it with --labels.\n";

/// Analyses the results of `options.results` into `options.out`: `fitness`, `descriptors`,
/// `pca-best` and `best-boxplot` figures, `best.csv`, `summary.csv`, `pvalues.csv` and
/// `summary.md`; with labels also `isi`, `isi-boxplot`, `species` and `isi.csv`. `setups`
/// reads how each experiment's robots are replayed; `progress` receives progress and warnings.
pub fn analyze(
    options: &AnalyzeOptions,
    setups: &dyn SetupReader,
    progress: &dyn Progress,
) -> Result<AnalysisReport, AnalysisError> {
    let mut experiments = results::discover(&options.results)?;
    results::group_by(&mut experiments, &options.group_by)?;
    let settings = settings_of(&experiments);
    create_folder(&options.out)?;
    let pool = thread_pool(options.threads)?;
    let runs: usize = experiments.iter().map(|e| e.runs.len()).sum();
    progress.note(&format!(
        "{} setting(s), {} experiment folder(s), {runs} run(s)",
        settings.len(),
        experiments.len()
    ));
    warn_missing_inputs(&experiments, &settings, progress);
    let mut a = Analysis {
        options,
        experiments: &experiments,
        settings: &settings,
        pool: &pool,
        progress,
        figures: Vec::new(),
    };
    let fitness = fitness_label(&experiments);
    a.figure(
        "fitness",
        &fitness_figure(&settings, &experiments, &with_unit(&fitness)),
        "best-so-far and population-median fitness vs evaluations, median ± sd across runs",
    )?;
    let (senses, members) = crate::pareto::members(&settings, &experiments);
    if !members.is_empty() {
        a.table("pareto.csv", &crate::pareto::pareto_csv(&settings, &senses, &members))?;
        a.figure(
            "pareto",
            &crate::pareto::pareto_figure(&settings, &senses, &members),
            "two objectives: every run's final population, its first front (large) and knee (largest)",
        )?;
        for (k, objective) in senses.iter().enumerate() {
            let metric = &objective.metric;
            for (role, name, what) in [
                (
                    format!("specialist-{metric}"),
                    format!("specialist-{metric}"),
                    "specialist (the front's best in it)",
                ),
                ("knee".to_string(), format!("knee-{metric}"), "knee"),
            ] {
                let values = crate::pareto::role_values(&settings, &members, &role, k);
                a.figure(
                    &name,
                    &boxplot(
                        format!("{metric} of each run's {what}"),
                        metric.clone(),
                        &settings,
                        &values,
                    ),
                    &format!("{metric} of each run's {what} per setting, with pairwise Mann–Whitney p-values"),
                )?;
            }
        }
    }
    // the figures of columns the genotype kinds log (the graph's size, a co-designed body's)
    let mut declared: Vec<_> = experiments.iter().flat_map(column_figures).collect();
    declared.sort_by_key(|f| f.file);
    declared.dedup();
    for declared in &declared {
        if let Some(figure) = column_figure(&settings, &experiments, declared) {
            a.figure(declared.file, &figure, declared.description)?;
        }
    }
    let best = per_setting(&settings, &experiments, RunData::final_best);
    progress.note("replaying the best robot of every run…");
    let setups = read_setups(&experiments, setups, progress);
    let saved = crate::pareto::save_role_robots(&a.path("pareto-robots"), &settings, &setups, &members, progress)?;
    if saved > 0 {
        progress.note(&format!(
            "saved {saved} knee and specialist robot files in {}",
            a.path("pareto-robots").display()
        ));
    }
    let best_table = a.best_robots(&setups)?;
    let (classifiers, final_isi) = match &options.labels {
        Some(labels) => a.species(labels, &setups)?,
        None => (NO_LABELS.to_string(), vec![Vec::new(); settings.len()]),
    };
    a.figure(
        "best-boxplot",
        &boxplot(
            format!("Best {fitness} of each run"),
            format!("best {}", with_unit(&fitness)),
            &settings,
            &best,
        ),
        "best fitness of each run per setting, with pairwise Mann–Whitney p-values",
    )?;
    let summary = Summary::new(&fitness, setting_summaries(&settings, &best, &final_isi));
    a.table("summary.csv", &summary.settings_csv())?;
    a.table("pvalues.csv", &summary.pvalues_csv())?;
    let page = SummaryPage {
        results: &options.results,
        settings: &settings,
        experiments: &experiments,
        summary: &summary,
        classifiers: &classifiers,
        figures: &a.figures,
        species: options.labels.is_some(),
        best_table,
    };
    a.table("summary.md", &page.to_markdown())?;
    Ok(AnalysisReport {
        out: options.out.clone(),
        summary,
        figures: a.figures,
    })
}

/// Fewest runs per setting for which boxplots and rank tests are drawn without a warning.
const FEW_RUNS: usize = 5;

/// Warns about every input that an analysis leaves out or that makes a figure weak: a run without
/// `generations.csv` (no fitness curve), without `best.robot.json` (not in `best.csv` nor the
/// descriptor figures), without `summary.json` (unfinished), and settings with few runs.
fn warn_missing_inputs(experiments: &[ExperimentData], settings: &[Setting], progress: &dyn Progress) {
    for experiment in experiments {
        for run in &experiment.runs {
            let files = run.files();
            let label = experiment.run_label(run);
            if !files.generations_csv().exists() {
                progress.note(&format!(
                    "warning: {label}: no {GENERATIONS_FILE}; the run is left out of the fitness figure"
                ));
            }
            if run.best_robot.is_none() {
                progress.note(&format!(
                    "warning: {label}: no {BEST_ROBOT_FILE}; the run is left out of best.csv and the descriptor figures"
                ));
            }
            if run.summary.is_none() {
                progress.note(&format!(
                    "warning: {label}: no {SUMMARY_FILE} (unfinished run); it is analysed where it stopped"
                ));
            }
        }
    }
    for setting in settings {
        let runs = setting.runs(experiments).count();
        if runs < FEW_RUNS {
            progress.note(&format!(
                "warning: setting {}: only {runs} run(s); its boxplot and p-values say little below {FEW_RUNS} runs",
                setting.name
            ));
        }
    }
}

/// The summary table's rows: per setting, the runs' best fitness and final ISI.
fn setting_summaries(settings: &[Setting], best: &[Vec<f64>], final_isi: &[Vec<f64>]) -> Vec<SettingSummary> {
    settings
        .iter()
        .map(|s| SettingSummary {
            name: s.name.clone(),
            best: best[s.color].clone(),
            final_isi: final_isi[s.color].clone(),
        })
        .collect()
}

/// One analysis under way: its inputs and the figures written so far.
struct Analysis<'a> {
    options: &'a AnalyzeOptions,
    experiments: &'a [ExperimentData],
    settings: &'a [Setting],
    pool: &'a rayon::ThreadPool,
    progress: &'a dyn Progress,
    figures: Vec<FigureNote>,
}

impl Analysis<'_> {
    /// A path in the output folder.
    fn path(&self, name: &str) -> PathBuf {
        self.options.out.join(name)
    }

    /// Writes `figure` as `name.png` and `name.svg`, and notes it for `summary.md`.
    fn figure(&mut self, name: &str, figure: &impl Figure, description: &str) -> Result<(), AnalysisError> {
        plot::save(figure, &self.path(name))?;
        self.figures.push(FigureNote {
            name: name.to_string(),
            description: description.to_string(),
        });
        Ok(())
    }

    /// Writes a table or text file `name`.
    fn table(&self, name: &str, text: &str) -> Result<(), AnalysisError> {
        write_output(&self.path(name), text.as_bytes())
    }

    /// The best robots: `best.csv`, the descriptor scatter and the PCA. Returns whether
    /// `best.csv` was written (not without a replayable best robot).
    fn best_robots(&mut self, setups: &[Option<ReplaySetup>]) -> Result<bool, AnalysisError> {
        let bests = best_robots(self.settings, self.experiments, setups, self.pool, self.progress);
        if bests.is_empty() {
            // a figure with no data is not written
            return Ok(false);
        }
        self.table("best.csv", &best_csv(self.settings, &bests))?;
        self.figure(
            "descriptors",
            &descriptor_figure(self.settings, &bests),
            "elongation vs compactness of each run's best robot (marker size: voxels)",
        )?;
        match pca_figure(self.settings, &bests) {
            Some(fig) => self.figure(
                "pca-best",
                &fig,
                "best robots on the first two principal components of their features",
            )?,
            None => self
                .progress
                .note("note: fewer than 3 replayable best robots: no PCA figure"),
        }
        Ok(true)
    }

    /// Species with the labels file: trains the classifiers, classifies every snapshot, writes
    /// `isi.csv` and the `isi`, `isi-boxplot` and `species` figures. Returns the classifiers'
    /// table for `summary.md` and the final ISI of each run per setting.
    fn species(
        &mut self,
        labels: &Path,
        setups: &[Option<ReplaySetup>],
    ) -> Result<(String, Vec<Vec<f64>>), AnalysisError> {
        let o = self.options;
        let cls = train_classifiers(labels, o.folds, o.seed, self.pool, self.progress)?;
        let table = classifier_table(&cls, o.folds, self.progress);
        let runs = species_over_time(
            self.experiments,
            self.settings,
            setups,
            &cls,
            o.sample,
            self.pool,
            self.progress,
        )?;
        self.table("isi.csv", &isi_csv(self.settings, &runs))?;
        self.figure(
            "isi",
            &isi_figure(self.settings, &runs),
            "Inverse Simpson Index of species, morphology and behaviour classes vs evaluations, median ± sd across runs",
        )?;
        let mut final_isi = vec![Vec::new(); self.settings.len()];
        for run in &runs {
            if let Some(last) = run.snapshots.last() {
                final_isi[run.setting].push(last.species);
            }
        }
        self.figure(
            "isi-boxplot",
            &boxplot(
                "Final species diversity per run (Inverse Simpson Index)".into(),
                "ISI of the final population".into(),
                self.settings,
                &final_isi,
            ),
            "ISI of the final population of each run, with pairwise Mann–Whitney p-values",
        )?;
        self.figure(
            "species",
            &species_figure(self.settings, &runs, &cls),
            "share of each species in the final populations (bubble area) and its best velocity (colour)",
        )?;
        Ok((table, final_isi))
    }
}
