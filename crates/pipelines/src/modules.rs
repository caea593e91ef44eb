//! `vsrlab modules`: automatic module discovery (thesis §4.1.5.7) on the best robot of every run
//! whose brain is a graph: the most compact 4-connected set of `sizes` voxels, and the pieces the
//! rest of the body falls into ([`vsrlab_brain::graph_modules::discover`]).
//!
//! Files: `modules.csv` (setting, run, module size, compactness, pieces, the partition as rows of
//! digits: 0 = the module, 1… = the other pieces, `.` = no voxel).

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use crate::settings::settings_of;
use std::path::PathBuf;
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results;
use vsrlab_body::Morphology;
use vsrlab_brain::graph_modules::{digit, discover, grid_rows, Cell, Partition, MAX_MODULE_SIZE};
use vsrlab_brain::BrainSpec;
use vsrlab_tasks::files::load_robot;

/// Options of [`modules`].
#[derive(Debug, Clone, PartialEq)]
pub struct ModulesOptions {
    /// Output folders of `vsrlab run`.
    pub results: Vec<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// Smallest and largest module, in voxels (thesis: 2 and 5).
    pub sizes: (usize, usize),
}

/// One robot's discovered module.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotModules {
    /// Its setting.
    pub setting: String,
    /// `<experiment folder>/run-XX`.
    pub run: String,
    /// The partition.
    pub partition: Partition,
    /// The partition as rows of digits (module 0 first), top row first, `/`-separated.
    pub rows: String,
}

/// What [`modules`] found and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ModulesReport {
    /// Every robot with a graph brain.
    pub robots: Vec<RobotModules>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

impl ModulesReport {
    /// One line per robot.
    pub fn to_text(&self) -> String {
        self.robots
            .iter()
            .map(|r| {
                format!(
                    "{}: module of {} voxels, compactness {:.3}, {} other piece(s): {}\n",
                    r.run,
                    r.partition.module.len(),
                    r.partition.compactness,
                    r.partition.rest.len(),
                    r.rows
                )
            })
            .collect()
    }
}

/// The partition drawn as rows of digits: the module 0, the other pieces 1, 2, …
pub fn partition_rows(body: &Morphology, p: &Partition) -> String {
    let piece_of = |c: Cell| {
        if p.module.contains(&c) {
            Some(0)
        } else {
            p.rest.iter().position(|r| r.contains(&c)).map(|k| k + 1)
        }
    };
    grid_rows(body.width(), body.height(), |x, y| piece_of((x, y)).map_or('.', digit))
}

/// Discovers a module in the best robot of every run of `results` whose brain is a graph.
pub fn modules(options: &ModulesOptions, progress: &dyn Progress) -> Result<ModulesReport, AnalysisError> {
    let (lo, hi) = options.sizes;
    if lo == 0 || lo > hi || hi > MAX_MODULE_SIZE {
        return Err(AnalysisError::Option {
            option: "sizes",
            message: format!("need 1 ≤ smallest ≤ largest ≤ {MAX_MODULE_SIZE}, got {lo}..{hi}"),
        });
    }
    let experiments = results::discover(&options.results)?;
    let mut robots = Vec::new();
    for setting in settings_of(&experiments) {
        for (experiment, run) in setting.runs(&experiments) {
            let Some(path) = &run.best_robot else {
                progress.note(&format!("warning: {}: no best robot file, skipped", run.dir.display()));
                continue;
            };
            let robot = load_robot(path)?;
            let BrainSpec::Graph(graph) = &robot.brain else {
                progress.note(&format!("{}: its brain is not a graph, skipped", path.display()));
                continue;
            };
            let Some(partition) = discover(graph, &robot.body, lo..=hi) else {
                progress.note(&format!(
                    "{}: the body has no connected set of {lo} to {hi} voxels smaller than itself, skipped",
                    path.display()
                ));
                continue;
            };
            robots.push(RobotModules {
                setting: setting.name.clone(),
                run: experiment.run_label(run),
                rows: partition_rows(&robot.body, &partition),
                partition,
            });
        }
    }
    create_folder(&options.out)?;
    let mut csv = String::from("setting,run,module_voxels,compactness,other_pieces,partition\n");
    for r in &robots {
        csv += &format!(
            "{},{},{},{},{},{}\n",
            r.setting,
            r.run,
            r.partition.module.len(),
            r.partition.compactness,
            r.partition.rest.len(),
            r.rows
        );
    }
    let path = options.out.join("modules.csv");
    write_output(&path, csv.as_bytes())?;
    Ok(ModulesReport {
        robots,
        files: vec![path],
    })
}
