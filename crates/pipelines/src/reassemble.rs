//! Disassembly–reassembly of evolved graph brains (thesis §4.1.5.2–4.1.5.6) and the
//! transferability measures.
//!
//! [`reassemble`] pairs the runs of one setting as the original code does: the hybrid of pair i
//! keeps the best robot of run i outside the cut region and takes the best robot of run i + 1
//! (wrapping) inside it ([`vsrlab_brain::graph_transfer::reassemble`]). It writes each hybrid as
//! a robot file, `transfer.csv` (donor fitnesses, η_num, η_weight) and `reoptimise.toml`: the
//! donors' experiment re-run from each hybrid (`[genotype] initial`, a sweep over the pairs), with
//! the thesis' re-optimisation: the hybrid and mutants of it made with the five operators, then
//! weights and biases only.
//!
//! [`transferability`] reads those folders once `reoptimise.toml` has run (into
//! `<folder>/reoptimised`) and computes ρ = v̄(r′) ÷ mean(v̄(r₁), v̄(r₂)) (thesis eq. 4.4) over
//! the re-optimisation, with v̄ the best fitness so far of each run; it compares the settings'
//! final ρ, η_num and η_weight with Mann–Whitney tests.

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use std::path::{Path, PathBuf};
use vsrlab_analysis::curves::{band, grid_for};
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries, BoxFigure, BoxGroup};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::{self, ExperimentData};
use vsrlab_analysis::stats::{mann_whitney_u, median};
use vsrlab_body::Morphology;
use vsrlab_brain::graph_modules::{discover, grid_rows, region, Cell};
use vsrlab_brain::graph_transfer::reassemble as hybrid_of;
use vsrlab_brain::{BrainSpec, GraphSpec};
use vsrlab_experiment::config::StopConfig;
use vsrlab_experiment::genotypes::graph::{GraphGenotypeConfig, OperatorMix};
use vsrlab_tasks::files::{load_robot, robot_to_json};
use vsrlab_tasks::RobotSpec;

/// The re-optimisation folder [`transferability`] reads inside a reassembly folder.
pub const REOPTIMISED_DIR: &str = "reoptimised";

/// Options of [`reassemble`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReassembleOptions {
    /// The output folders of one setting of `vsrlab run` (the donors).
    pub donors: Vec<PathBuf>,
    /// The region taken from the second donor: `legs`, `back-half`, `front-half`, rows of `#`
    /// and `.`, or `discovered` (the most compact module of the second donor).
    pub cut: String,
    /// Output folder.
    pub out: PathBuf,
    /// Generations of the re-optimisation (thesis: 510).
    pub generations: u64,
}

/// One reassembled robot.
#[derive(Debug, Clone, PartialEq)]
pub struct Pair {
    /// `pair-XX`.
    pub label: String,
    /// The donor kept outside the region.
    pub outside_run: String,
    /// The donor taken inside the region.
    pub inside_run: String,
    /// Their best fitness at the end of evolution.
    pub donor_fitness: [f64; 2],
    /// The region, as rows (`#` in it).
    pub region: String,
    /// The hybrid's robot file.
    pub hybrid: PathBuf,
    /// Hybrid neurons and edges.
    pub size: (usize, usize),
    /// η_num and η_weight over both modules.
    pub eta: (f64, f64),
    /// Inside edges without a counterpart in the kept graph.
    pub unmatched: usize,
}

/// What [`reassemble`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ReassembleReport {
    /// The donors' setting.
    pub setting: String,
    /// Every pair.
    pub pairs: Vec<Pair>,
    /// The re-optimisation experiment file.
    pub config: PathBuf,
}

fn option(option: &'static str, message: String) -> AnalysisError {
    AnalysisError::Option { option, message }
}

/// A region's cells as rows of `#` (in it) and `.`, top row first.
fn region_rows(body: &Morphology, cells: &[Cell]) -> String {
    grid_rows(body.width(), body.height(), |x, y| {
        if cells.contains(&(x, y)) {
            '#'
        } else {
            '.'
        }
    })
}

/// Builds the hybrids of one setting's runs and the experiment that re-optimises them.
pub fn reassemble(options: &ReassembleOptions, progress: &dyn Progress) -> Result<ReassembleReport, AnalysisError> {
    if options.generations == 0 {
        return Err(option("generations", "must be at least 1".into()));
    }
    let experiments = results::discover(&options.donors)?;
    let names: Vec<&str> = experiments.iter().map(|e| e.name.as_str()).collect();
    if names.iter().any(|n| *n != names[0]) {
        return Err(option(
            "donors",
            format!("give the runs of one setting, not of several ({})", names.join(", ")),
        ));
    }
    let setting = names[0].to_string();
    let mut donors: Vec<(String, f64, RobotSpec)> = Vec::new();
    for e in &experiments {
        for run in &e.runs {
            let Some(path) = &run.best_robot else {
                progress.note(&format!("warning: {}: no best robot file, skipped", run.dir.display()));
                continue;
            };
            let robot = load_robot(path)?;
            if !matches!(&robot.brain, BrainSpec::Graph(g) if !g.neurons.is_empty()) {
                return Err(option(
                    "donors",
                    format!("{}: its brain is not an evolved graph", path.display()),
                ));
            }
            donors.push((e.run_label(run), run.final_best(), robot));
        }
    }
    if donors.len() < 2 {
        return Err(option(
            "donors",
            format!("need at least 2 runs with a best robot, found {}", donors.len()),
        ));
    }
    create_folder(&options.out)?;
    let mut pairs = Vec::new();
    for i in 0..donors.len() {
        let (outside, inside) = (&donors[i], &donors[(i + 1) % donors.len()]);
        let (BrainSpec::Graph(a), BrainSpec::Graph(b)) = (&outside.2.brain, &inside.2.brain) else {
            unreachable!("checked above")
        };
        if outside.2.body != inside.2.body {
            return Err(option(
                "donors",
                format!("{} and {} have different bodies", outside.0, inside.0),
            ));
        }
        let body = &outside.2.body;
        let cells = if options.cut == "discovered" {
            discover(b, body, 2..=5)
                .ok_or_else(|| option("cut", "the body is too small to hold a module of 2 to 5 voxels".into()))?
                .module
        } else {
            region(&options.cut, body).map_err(|e| option("cut", e.to_string()))?
        };
        let r = hybrid_of(a, b, &cells);
        let label = format!("pair-{i:02}");
        let hybrid = options.out.join(format!("hybrid-{i:02}.robot.json"));
        let robot = RobotSpec {
            brain: BrainSpec::Graph(r.graph.clone()),
            ..outside.2.clone()
        };
        let note = format!("{label}: {} outside the region, {} inside it", outside.0, inside.0);
        write_output(&hybrid, robot_to_json(&robot, Some(&note)).as_bytes())?;
        let total = r.total();
        pairs.push(Pair {
            label,
            outside_run: outside.0.clone(),
            inside_run: inside.0.clone(),
            donor_fitness: [outside.1, inside.1],
            region: region_rows(body, &cells),
            hybrid,
            size: (r.graph.neurons.len(), r.graph.edges.len()),
            eta: (total.eta_num(), total.eta_weight()),
            unmatched: r.unmatched,
        });
    }
    write_output(
        &options.out.join("transfer.csv"),
        transfer_csv(&setting, &pairs).as_bytes(),
    )?;
    let config = options.out.join("reoptimise.toml");
    let text = reoptimise_toml(&experiments[0], &setting, &pairs, options.generations)?;
    write_output(&config, text.as_bytes())?;
    Ok(ReassembleReport { setting, pairs, config })
}

fn transfer_csv(setting: &str, pairs: &[Pair]) -> String {
    let mut s = String::from(
        "setting,pair,outside_run,inside_run,outside_fitness,inside_fitness,donor_mean,region,hybrid_neurons,\
         hybrid_edges,eta_num,eta_weight,unmatched,hybrid\n",
    );
    for p in pairs {
        s += &format!(
            "{setting},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            p.label,
            p.outside_run,
            p.inside_run,
            p.donor_fitness[0],
            p.donor_fitness[1],
            (p.donor_fitness[0] + p.donor_fitness[1]) / 2.0,
            p.region,
            p.size.0,
            p.size.1,
            p.eta.0,
            p.eta.1,
            p.unmatched,
            p.hybrid.display()
        );
    }
    s
}

/// The donors' resolved experiment, re-run from each hybrid: one run per pair, the thesis'
/// re-optimisation operators, `generations` generations; written through the experiment's typed
/// configuration, with a `[sweep]` over the hybrids.
fn reoptimise_toml(
    donors: &ExperimentData,
    setting: &str,
    pairs: &[Pair],
    generations: u64,
) -> Result<String, AnalysisError> {
    let path = donors.folder().experiment_toml();
    let mut e = vsrlab_experiment::config::load(&path).map_err(|err| option("donors", err.to_string()))?;
    let graph = e
        .genotype
        .as_mut()
        .and_then(|g| g.downcast_mut::<GraphGenotypeConfig>())
        .ok_or_else(|| {
            option(
                "donors",
                format!("{}: not a graph-genotype experiment", donors.dir.display()),
            )
        })?;
    graph.seeded = false;
    graph.initial = None;
    graph.operators = OperatorMix::Named("weights-only".into());
    graph.initial_operators = OperatorMix::Named("thesis".into());
    e.representation.brain = BrainSpec::Graph(GraphSpec::default());
    e.description = None;
    e.name = Some(format!("{setting}-reassembled"));
    e.setting = e.name.clone();
    e.runs = 1;
    e.stop = StopConfig {
        generations: Some(generations),
        ..StopConfig::default()
    };
    let initial: toml::Table = pairs
        .iter()
        .map(|p| (p.label.clone(), p.hybrid.display().to_string().into()))
        .collect();
    let sweep = toml::Table::from_iter([(
        "sweep".to_string(),
        toml::Value::Table(toml::Table::from_iter([(
            "genotype.initial".to_string(),
            initial.into(),
        )])),
    )]);
    let sweep =
        toml::to_string(&sweep).map_err(|err| option("donors", format!("cannot write the experiment: {err}")))?;
    Ok(format!(
        "# Re-optimisation of the reassembled robots of {setting} (written by vsrlab reassemble):\n\
         # one run from each hybrid; the hybrid and mutants of it made with the five operators, then\n\
         # weights and biases only (thesis §4.1.5.3). Run it into the folder `transferability` reads:\n\
         #   vsrlab run <this file> --out <this folder>/{REOPTIMISED_DIR}\n{}\n{sweep}",
        e.to_toml()
    ))
}

/// Options of [`transferability`].
#[derive(Debug, Clone, PartialEq)]
pub struct TransferabilityOptions {
    /// Folders written by [`reassemble`], each re-optimised into `<folder>/reoptimised`.
    pub reassemblies: Vec<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
}

/// One pair's transferability.
#[derive(Debug, Clone, PartialEq)]
pub struct PairTransfer {
    /// The donors' setting.
    pub setting: String,
    /// `pair-XX`.
    pub pair: String,
    /// ρ over the re-optimisation: (evaluations, ρ).
    pub rho: Vec<(f64, f64)>,
    /// η_num and η_weight.
    pub eta: (f64, f64),
}

impl PairTransfer {
    /// ρ at the end of the re-optimisation.
    pub fn final_rho(&self) -> f64 {
        self.rho.last().map_or(f64::NAN, |p| p.1)
    }
}

/// One setting's medians.
#[derive(Debug, Clone, PartialEq)]
pub struct SettingTransfer {
    /// The donors' setting.
    pub setting: String,
    /// Pairs.
    pub pairs: usize,
    /// Median ρ at the start (the hybrids' first generation) and at the end.
    pub rho: (f64, f64),
    /// Median η_num and η_weight.
    pub eta: (f64, f64),
}

/// What [`transferability`] measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct TransferabilityReport {
    /// Every pair.
    pub pairs: Vec<PairTransfer>,
    /// Every setting.
    pub settings: Vec<SettingTransfer>,
    /// Mann–Whitney p-values between settings: (a, b, measure, p).
    pub pvalues: Vec<(String, String, &'static str, f64)>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

impl TransferabilityReport {
    /// The medians as a Markdown table, then the p-values.
    pub fn to_markdown(&self) -> String {
        let mut s = String::from(
            "| setting | pairs | ρ first generation | ρ final | η_num | η_weight |\n|---|---|---|---|---|---|\n",
        );
        for r in &self.settings {
            s += &format!(
                "| {} | {} | {:.3} | {:.3} | {:.3} | {:.3} |\n",
                r.setting, r.pairs, r.rho.0, r.rho.1, r.eta.0, r.eta.1
            );
        }
        for (a, b, what, p) in &self.pvalues {
            s += &format!("\nMann–Whitney {what}, {a} vs {b}: {}", plot::format_p(*p));
        }
        s
    }
}

/// A per-pair measure compared between settings.
type Measure = fn(&PairTransfer) -> f64;

/// The measures compared between settings: (figure stem, title, value).
const MEASURES: [(&str, &str, Measure); 3] = [
    ("rho-boxplot", "final ρ", |p| p.final_rho()),
    ("eta-num-boxplot", "η_num: share of edges cut", |p| p.eta.0),
    ("eta-weight-boxplot", "η_weight: share of |w| + |b| cut", |p| p.eta.1),
];

/// One row of `transfer.csv`.
#[derive(Debug, Clone, serde::Deserialize)]
struct TransferRow {
    setting: String,
    pair: String,
    donor_mean: f64,
    eta_num: f64,
    eta_weight: f64,
}

fn read_transfer_csv(dir: &Path) -> Result<Vec<TransferRow>, AnalysisError> {
    let path = dir.join("transfer.csv");
    let fail = |m: String| option("reassemblies", format!("{}: {m}", path.display()));
    let mut reader = csv::Reader::from_path(&path).map_err(|e| fail(format!("{e} (run vsrlab reassemble first)")))?;
    reader
        .deserialize()
        .map(|r| r.map_err(|e| fail(e.to_string())))
        .collect()
}

/// ρ and η of every pair of every reassembly folder, compared between settings.
pub fn transferability(
    options: &TransferabilityOptions,
    progress: &dyn Progress,
) -> Result<TransferabilityReport, AnalysisError> {
    let mut pairs = Vec::new();
    for dir in &options.reassemblies {
        let rows = read_transfer_csv(dir)?;
        let reoptimised = dir.join(REOPTIMISED_DIR);
        let experiments = results::discover(std::slice::from_ref(&reoptimised)).map_err(|e| {
            option(
                "reassemblies",
                format!(
                    "{e} (run {}/reoptimise.toml with --out {})",
                    dir.display(),
                    reoptimised.display()
                ),
            )
        })?;
        for row in rows {
            let suffix = format!("-{}", row.pair);
            let Some(run) = experiments
                .iter()
                .find(|e| {
                    e.dir
                        .file_name()
                        .is_some_and(|n| n.to_string_lossy().ends_with(&suffix))
                })
                .and_then(|e| e.runs.first())
            else {
                progress.note(&format!(
                    "warning: {}: {} was not re-optimised, skipped",
                    dir.display(),
                    row.pair
                ));
                continue;
            };
            let rho = run
                .generations
                .iter()
                .filter(|g| g.best_fitness.is_finite())
                .map(|g| (g.evaluations as f64, g.best_fitness / row.donor_mean))
                .collect();
            pairs.push(PairTransfer {
                setting: row.setting,
                pair: row.pair,
                rho,
                eta: (row.eta_num, row.eta_weight),
            });
        }
    }
    if pairs.is_empty() {
        return Err(option("reassemblies", "no re-optimised pair found".into()));
    }
    let mut names: Vec<String> = pairs.iter().map(|p| p.setting.clone()).collect();
    names.sort();
    names.dedup();
    let of = |name: &str, f: &dyn Fn(&PairTransfer) -> f64| -> Vec<f64> {
        pairs.iter().filter(|p| p.setting == name).map(f).collect()
    };
    let first_rho = |p: &PairTransfer| p.rho.first().map_or(f64::NAN, |x| x.1);
    let settings: Vec<SettingTransfer> = names
        .iter()
        .map(|n| SettingTransfer {
            setting: n.clone(),
            pairs: pairs.iter().filter(|p| &p.setting == n).count(),
            rho: (median(&of(n, &first_rho)), median(&of(n, &|p| p.final_rho()))),
            eta: (median(&of(n, &|p| p.eta.0)), median(&of(n, &|p| p.eta.1))),
        })
        .collect();
    let mut pvalues = Vec::new();
    for &(_, what, f) in &MEASURES {
        for i in 0..names.len() {
            for j in i + 1..names.len() {
                if let Some(mw) = mann_whitney_u(&of(&names[i], &f), &of(&names[j], &f)) {
                    let what = what.split(':').next().unwrap_or(what);
                    pvalues.push((names[i].clone(), names[j].clone(), what, mw.p));
                }
            }
        }
    }
    create_folder(&options.out)?;
    let mut files = Vec::new();
    let mut csv = String::from("setting,pair,final_rho,eta_num,eta_weight\n");
    for p in &pairs {
        csv += &format!("{},{},{},{},{}\n", p.setting, p.pair, p.final_rho(), p.eta.0, p.eta.1);
    }
    let path = options.out.join("transferability.csv");
    write_output(&path, csv.as_bytes())?;
    files.push(path);
    let series: Vec<BandSeries> = names
        .iter()
        .enumerate()
        .map(|(color, n)| {
            let curves: Vec<Vec<(f64, f64)>> = pairs
                .iter()
                .filter(|p| &p.setting == n)
                .map(|p| p.rho.clone())
                .collect();
            let grid = grid_for(&curves, 100);
            let b = band(&curves, &grid, true);
            BandSeries {
                label: n.clone(),
                color,
                x: b.x,
                center: b.median,
                spread: b.sd,
            }
        })
        .collect();
    let rho_figure = BandFigure {
        title: "Transferability ρ during re-optimisation (1 = the donors' mean velocity)".into(),
        legend_title: "donors".into(),
        note: vsrlab_analysis::plot::band::median_sd_note(),
        panels: vec![BandChart {
            title: "reassembled robots".into(),
            x_label: "fitness evaluations".into(),
            y_label: "ρ".into(),
            series,
        }],
    };
    files.extend(plot::save(&rho_figure, &options.out.join("rho"))?);
    for &(stem, what, f) in &MEASURES {
        let values: Vec<Vec<f64>> = names.iter().map(|n| of(n, &f)).collect();
        let mut brackets = Vec::new();
        for i in 0..names.len() {
            for j in i + 1..names.len() {
                if let Some(mw) = mann_whitney_u(&values[i], &values[j]) {
                    brackets.push((i, j, mw.p));
                }
            }
        }
        let figure = BoxFigure {
            title: format!("{what}, per setting of the donors"),
            y_label: what.split(':').next().unwrap_or(what).to_string(),
            groups: names
                .iter()
                .zip(values)
                .enumerate()
                .map(|(color, (n, v))| BoxGroup {
                    label: n.clone(),
                    color,
                    values: v,
                })
                .collect(),
            pvalues: brackets,
            max_brackets: 6,
        };
        files.extend(plot::save(&figure, &options.out.join(stem))?);
    }
    Ok(TransferabilityReport {
        pairs,
        settings,
        pvalues,
        files,
    })
}
