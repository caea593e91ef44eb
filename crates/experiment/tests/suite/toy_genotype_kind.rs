//! A third genotype kind, written entirely in this file, goes through the genotype-kind seam:
//! quantised phases (one small integer per cell of a biped, the phase of its voxel). It touches
//! no existing file: its `[genotype]` table is a `GenotypeKind`, set on an experiment read from
//! a file; GA, NSGA-II and MAP-Elites evolve it over its own operators; the runner writes its
//! snapshots, checkpoints and best robot; `vsrlab validate`'s estimate sizes and times it; and
//! the analyses replay its snapshot rows through the kind's stored-genotype reader. Registering
//! it for experiment files would be one line in `genotypes::GENOTYPES`.

use crate::common;

use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use vsrlab_evolution::rng::SeededRng;
use vsrlab_evolution::Representation as Variation;
use vsrlab_experiment::config::{self, Experiment};
use vsrlab_experiment::genotype::fnv1a;
use vsrlab_experiment::genotypes::{
    check_operators, run_with_operators, time_with_operators, GenotypeConfig, GenotypeKind, GenotypeSize,
};
use vsrlab_experiment::optimizers::FieldError;
use vsrlab_experiment::runner::{run_dir, Observer, RunError, RunOptions, RunSummary, Silent};
use vsrlab_experiment::{run_configured, Genotype};
use vsrlab_tasks::{EvaluationError, Mapper, Robot, Stored, StoredGenotypes, TraceLevel};

/// Cells of the biped-4x3 grid.
const CELLS: usize = 12;

/// One phase level per cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Phases(Vec<i8>);

impl Genotype for Phases {
    fn key(&self) -> u64 {
        fnv1a(self.0.iter().map(|&v| v as u8))
    }
}

/// Levels in `-levels..=levels`; mutation moves one cell one level; crossover takes each cell
/// from either parent.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct PhaseOps {
    levels: i8,
}

impl Variation for PhaseOps {
    type Genotype = Phases;

    fn random(&self, rng: &mut SeededRng) -> Phases {
        let span = 2 * self.levels as usize + 1;
        Phases((0..CELLS).map(|_| rng.below(span) as i8 - self.levels).collect())
    }

    fn mutate(&self, parent: &Phases, rng: &mut SeededRng) -> Phases {
        let mut child = parent.clone();
        let cell = rng.below(CELLS);
        let step = if rng.uniform() < 0.5 { -1 } else { 1 };
        child.0[cell] = (child.0[cell] + step).clamp(-self.levels, self.levels);
        child
    }

    fn crossover(&self, first: &Phases, second: &Phases, rng: &mut SeededRng) -> Phases {
        Phases(
            first
                .0
                .iter()
                .zip(&second.0)
                .map(|(&a, &b)| if rng.uniform() < 0.5 { a } else { b })
                .collect(),
        )
    }
}

/// Phases → a biped with a phase-grid brain.
#[derive(Debug, Clone)]
struct PhaseMapper {
    levels: i8,
}

impl Mapper<Phases> for PhaseMapper {
    fn robot(&self, g: &Phases) -> Result<Box<dyn Robot>, EvaluationError> {
        if g.0.len() != CELLS || g.0.iter().any(|v| v.abs() > self.levels) {
            return Err(EvaluationError::Genotype(vsrlab_field::FieldError::message(format!(
                "{CELLS} levels within ±{} expected",
                self.levels
            ))));
        }
        let phases: Vec<f64> = g.0.iter().map(|&v| f64::from(v) / f64::from(self.levels)).collect();
        common::phase_biped(&phases)
    }
}

/// The `kind` tag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum Tag {
    QuantisedPhases,
}

/// `[genotype] kind = "quantised-phases"` with its one setting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuantisedPhases {
    kind: Tag,
    levels: i8,
}

impl GenotypeKind for QuantisedPhases {
    fn name(&self) -> &'static str {
        "quantised-phases"
    }

    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError> {
        check_operators(experiment, true)?;
        if !(1..=16).contains(&self.levels) {
            return Err(FieldError::new(
                "genotype.levels",
                format!("must be in 1..=16, got {}", self.levels),
            ));
        }
        Ok(())
    }

    fn size(&self, _experiment: &Experiment) -> Result<GenotypeSize, FieldError> {
        Ok(GenotypeSize {
            genes: CELLS,
            text: format!("{CELLS} phase levels"),
        })
    }

    fn run(
        &self,
        experiment: &Experiment,
        out: &Path,
        options: &RunOptions,
        observer: &mut dyn Observer,
    ) -> Result<Vec<RunSummary>, RunError> {
        let (ops, mapper) = (PhaseOps { levels: self.levels }, PhaseMapper { levels: self.levels });
        run_with_operators(experiment, ops, mapper, CELLS, out, options, observer)
    }

    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError> {
        let ops = PhaseOps { levels: self.levels };
        time_with_operators(experiment, &ops, PhaseMapper { levels: self.levels }, count)
    }

    fn stored(&self, _experiment: &Experiment) -> Result<Arc<dyn StoredGenotypes>, FieldError> {
        Ok(Arc::new(Stored::<Phases, _>::new(PhaseMapper { levels: self.levels })))
    }
}

/// An experiment file (flat-vector genotypes as read) given the toy genotype kind.
pub(crate) fn experiment(optimizer: &str) -> Experiment {
    let text = format!(
        r#"
runs = 2
seed = 3

[representation]
body = "biped-4x3"
sensors = "empty"
brain = {{ kind = "phase-grid" }}

[task]
terrain = "flat"
duration = 1.0

[optimizer]
{optimizer}

[stop]
evaluations = 24

[output]
snapshot_every = 12
"#
    );
    let mut experiment = config::parse(&text, "phases.toml").unwrap();
    experiment.genotype = Some(GenotypeConfig::new(QuantisedPhases {
        kind: Tag::QuantisedPhases,
        levels: 4,
    }));
    experiment
}

fn run(experiment: &Experiment, out: &Path) -> Vec<RunSummary> {
    experiment.validate().unwrap();
    run_configured(experiment, out, &common::two_threads(false), &mut Silent).unwrap()
}

#[test]
fn a_toy_genotype_kind_runs_with_the_ga_and_its_snapshots_replay_in_the_analyses() {
    let experiment = experiment("kind = \"ga\"\npopulation_size = 6\noffspring_size = 6");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ga");
    let summaries = run(&experiment, &out);
    assert_eq!(summaries.len(), 2);
    assert!(summaries.iter().all(|s| s.failures == 0 && s.best_fitness.is_some()));

    // the resolved file names the kind and its setting
    let resolved = std::fs::read_to_string(out.join("experiment.toml")).unwrap();
    assert!(
        resolved.contains("[genotype]\nkind = \"quantised-phases\"\nlevels = 4"),
        "{resolved}"
    );

    // snapshots hold the genotypes as the kind stores them; the analyses read them and replay
    // them through the kind's stored-genotype reader (what `vsrlab-pipelines`' ReplaySetup holds)
    let rows =
        vsrlab_analysis::results::read_snapshot(&run_dir(&out, 0, 2).join("snapshots/evaluations-0000012.jsonl"))
            .unwrap();
    assert_eq!(rows.len(), 6);
    let levels: Vec<i8> = serde_json::from_value(rows[0].genotype.clone()).unwrap();
    assert_eq!(levels.len(), CELLS);
    let stored = experiment.genotype_kind().stored(&experiment).unwrap();
    let robot = stored.robot(&rows[0].genotype).unwrap();
    let outcome = vsrlab_tasks::episode::run(
        robot.as_ref(),
        experiment.task.spec.task(),
        rows[0].seed(),
        TraceLevel::Full,
    )
    .unwrap();
    assert!(outcome.trace.unwrap().times.len() > 10, "a whole episode is replayed");
    assert_eq!(
        outcome.fitness.first().copied(),
        rows[0].fitness(),
        "the replay gives the logged fitness"
    );
    // a stored genotype of another kind is refused, not dropped
    let err = stored
        .robot(&serde_json::json!({"neurons": []}))
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("not a genotype of this experiment"), "{err}");

    // the best robot is a robot file
    vsrlab_tasks::files::load_robot(&run_dir(&out, 1, 2).join("best.robot.json")).unwrap();

    // validate sizes and times it
    let v = vsrlab_experiment::validate::validate(&experiment, 1).unwrap();
    assert_eq!(v.genes, CELLS);
    assert!(v.seconds_per_evaluation > 0.0);
}

#[test]
fn nsga2_and_map_elites_evolve_it_and_flat_vector_optimizers_are_refused_by_field() {
    let dir = tempfile::tempdir().unwrap();
    for (name, optimizer) in [
        (
            "nsga2",
            "kind = \"nsga2\"\npopulation_size = 6\noffspring_size = 6\nmutation_probability = 0.5",
        ),
        (
            "map-elites",
            "kind = \"map-elites\"\ninitial_population = 6\nbatch_size = 6",
        ),
    ] {
        let summaries = run(&experiment(optimizer), &dir.path().join(name));
        assert!(
            summaries.iter().all(|s| s.failures == 0 && s.best_fitness.is_some()),
            "{name}: {summaries:?}"
        );
    }
    for optimizer in ["kind = \"cma-es\"", "kind = \"es\"", "kind = \"se\""] {
        let FieldError {
            path: field, message, ..
        } = experiment(optimizer).validate().unwrap_err();
        assert_eq!(field, "optimizer.kind", "{optimizer}");
        assert!(
            message.contains("a quantised-phases genotype evolves with"),
            "{message}"
        );
    }
    let mut bad = experiment("kind = \"ga\"");
    bad.genotype = Some(GenotypeConfig::new(QuantisedPhases {
        kind: Tag::QuantisedPhases,
        levels: 0,
    }));
    assert_eq!(bad.validate().unwrap_err().path, "genotype.levels");
}

#[test]
fn a_killed_toy_run_resumes_to_the_same_files() {
    let experiment = experiment("kind = \"ga\"\npopulation_size = 6\noffspring_size = 6");
    let dir = tempfile::tempdir().unwrap();
    let (straight, resumed) = (dir.path().join("straight"), dir.path().join("resumed"));
    run(&experiment, &straight);
    let done = run_configured(
        &experiment,
        &resumed,
        &common::two_threads(false),
        &mut common::Killer { run: 1, after: 2 },
    )
    .unwrap();
    assert_eq!(done.len(), 1);
    run_configured(&experiment, &resumed, &common::two_threads(true), &mut Silent).unwrap();
    let files = |out: &Path| vsrlab_experiment::runner::deterministic_files(out).unwrap();
    assert_eq!(files(&straight), files(&resumed));
}
