//! The rows of a run folder, one type each for the runner that writes them and the analyses
//! that read them back: a line of `generations.csv` ([`GenerationRow`]) and a population member
//! of a snapshot ([`SnapshotRow`], with its evaluation [`Record`]).

use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use vsrlab_body::Morphology;

/// The summary of one evaluation that snapshots and checkpoints carry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The episode seed used.
    pub seed: u64,
    /// The (first) fitness value (`None` when the evaluation failed).
    pub fitness: Option<f64>,
    /// Distance travelled.
    pub distance: Option<f64>,
    /// Average velocity.
    pub velocity: Option<f64>,
    /// Number of voxels.
    pub voxels: Option<usize>,
    /// The body as rows of `#` and `.`, top row first, joined by `/`.
    pub body: Option<String>,
    /// Why the evaluation failed.
    pub error: Option<String>,
    /// Every fitness value, for multi-objective tasks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objectives: Option<Vec<f64>>,
    /// Sequences an evaluation recorded, by name: a named channel for what a kind of evaluation
    /// measures over its course (the co-design loop's `learning_curve`: the off-line reward per
    /// step after each PPO iteration). Finite values only.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub series: std::collections::BTreeMap<String, Vec<f64>>,
}

impl Record {
    /// The record of an evaluation with episode seed `seed` that measured nothing yet: every
    /// other field empty, for evaluators to fill.
    pub fn new(seed: u64) -> Record {
        Record {
            seed,
            fitness: None,
            distance: None,
            velocity: None,
            voxels: None,
            body: None,
            error: None,
            objectives: None,
            series: Default::default(),
        }
    }
}

/// One population member of a snapshot (a JSON line): where it stands in the run, its
/// evaluation record (absent when none was kept), its MAP-Elites descriptor and its genotype in
/// its kind's own form. The runner writes `SnapshotRow<&G, &Record>`; analyses read
/// `SnapshotRow` (the genotype as stored JSON).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SnapshotRow<G = serde_json::Value, R = Record> {
    /// Generation of the snapshot.
    pub generation: u64,
    /// Evaluations at the snapshot.
    pub evaluations: u64,
    /// Index in the population.
    pub index: usize,
    /// Generation in which it was born.
    pub birth_generation: u64,
    /// Its evaluation.
    #[serde(flatten)]
    pub record: Option<R>,
    /// MAP-Elites descriptor (empty for other optimizers).
    pub descriptor: Vec<f64>,
    /// The genotype.
    pub genotype: G,
}

impl SnapshotRow {
    /// The body, when the row has one that parses.
    pub fn morphology(&self) -> Option<Morphology> {
        self.body().and_then(|b| Morphology::parse(b).ok())
    }

    /// The episode seed of its evaluation (0 without a record).
    pub fn seed(&self) -> u64 {
        self.record.as_ref().map_or(0, |r| r.seed)
    }

    /// Its (first) fitness, when it was evaluated successfully.
    pub fn fitness(&self) -> Option<f64> {
        self.record.as_ref().and_then(|r| r.fitness)
    }

    /// Its average velocity.
    pub fn velocity(&self) -> Option<f64> {
        self.record.as_ref().and_then(|r| r.velocity)
    }

    /// Its body as rows joined by `/`.
    pub fn body(&self) -> Option<&str> {
        self.record.as_ref().and_then(|r| r.body.as_deref())
    }

    /// Why its evaluation failed.
    pub fn error(&self) -> Option<&str> {
        self.record.as_ref().and_then(|r| r.error.as_deref())
    }
}

/// The columns of `generations.csv` before the genotype kind's own (`best_<stat>`).
pub const GENERATIONS_HEADER: &str = "generation,evaluations,births,failures,best_fitness,batch_best,batch_median,\
population_best,population_median,population_size,distinct_bodies,mean_voxels,species,archive_cells";

/// One row of `generations.csv`: a generation's deterministic figures.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationRow {
    /// Generation number.
    pub generation: u64,
    /// Fitness evaluations so far.
    pub evaluations: u64,
    /// New genotypes evaluated so far.
    pub births: u64,
    /// Failed evaluations in this generation.
    pub failures: u64,
    /// Best fitness so far.
    pub best_fitness: f64,
    /// Best fitness of this generation's batch.
    pub batch_best: f64,
    /// Median fitness of this generation's batch.
    pub batch_median: f64,
    /// Best fitness of the population after the generation.
    pub population_best: f64,
    /// Median fitness of the population after the generation.
    pub population_median: f64,
    /// Members of the population.
    pub population_size: u64,
    /// Distinct bodies in the population.
    pub distinct_bodies: u64,
    /// Mean voxels per body of the population (NaN without bodies).
    pub mean_voxels: f64,
    /// Species (speciated evolvers only).
    pub species: Option<u64>,
    /// Filled archive cells (archive-based optimizers only).
    pub archive_cells: Option<u64>,
    /// The best genotype's own statistics (`best_<name>` columns: a graph's neurons, edges,
    /// size, …), in column order.
    pub best_stats: Vec<(String, f64)>,
}

impl GenerationRow {
    /// The header line (without newline) of a run whose genotype kind logs `stats`.
    pub fn header(stats: &[&str]) -> String {
        let mut header = GENERATIONS_HEADER.to_string();
        for name in stats {
            let _ = write!(header, ",best_{name}");
        }
        header
    }

    /// The row as a CSV line (without newline): floats in their shortest round-trip form, `NaN`
    /// for failures, empty cells for the optimizer's absent counts.
    pub fn to_csv(&self) -> String {
        let count = |v: Option<u64>| v.map_or(String::new(), |v| v.to_string());
        let mut line = format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            self.generation,
            self.evaluations,
            self.births,
            self.failures,
            self.best_fitness,
            self.batch_best,
            self.batch_median,
            self.population_best,
            self.population_median,
            self.population_size,
            self.distinct_bodies,
            self.mean_voxels,
            count(self.species),
            count(self.archive_cells),
        );
        for (_, value) in &self.best_stats {
            let _ = write!(line, ",{value}");
        }
        line
    }

    /// One of the best genotype's statistics by name (`size` for `best_size`), NaN when the run
    /// logs none of that name.
    pub fn best_stat(&self, name: &str) -> f64 {
        self.best_stats
            .iter()
            .find(|(n, _)| n == name)
            .map_or(f64::NAN, |(_, v)| *v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row() -> GenerationRow {
        GenerationRow {
            generation: 3,
            evaluations: 120,
            births: 100,
            failures: 1,
            best_fitness: 0.5,
            batch_best: 0.25,
            batch_median: f64::NAN,
            population_best: 0.5,
            population_median: 0.125,
            population_size: 40,
            distinct_bodies: 1,
            mean_voxels: 10.0,
            species: None,
            archive_cells: Some(7),
            best_stats: vec![("neurons".into(), 24.0), ("size".into(), 80.0)],
        }
    }

    #[test]
    fn a_generation_row_is_written_as_its_header_says() {
        let header = GenerationRow::header(&["neurons", "size"]);
        assert!(
            header.ends_with(",species,archive_cells,best_neurons,best_size"),
            "{header}"
        );
        let line = row().to_csv();
        assert_eq!(line, "3,120,100,1,0.5,0.25,NaN,0.5,0.125,40,1,10,,7,24,80");
        assert_eq!(header.split(',').count(), line.split(',').count());
        assert_eq!(row().best_stat("size"), 80.0);
        assert!(row().best_stat("edges").is_nan());
    }

    #[test]
    fn a_snapshot_row_reads_back_what_the_runner_writes() {
        let record = Record {
            seed: 9,
            fitness: Some(1.5),
            distance: Some(3.0),
            velocity: Some(1.5),
            voxels: Some(4),
            body: Some("##/##".into()),
            error: None,
            objectives: None,
            series: Default::default(),
        };
        let genotype = vec![0.5, -0.25];
        let written = SnapshotRow {
            generation: 2,
            evaluations: 80,
            index: 1,
            birth_generation: 1,
            record: Some(&record),
            descriptor: vec![],
            genotype: &genotype,
        };
        let line = serde_json::to_string(&written).unwrap();
        assert_eq!(
            line,
            r###"{"generation":2,"evaluations":80,"index":1,"birth_generation":1,"seed":9,"fitness":1.5,"distance":3.0,"velocity":1.5,"voxels":4,"body":"##/##","error":null,"descriptor":[],"genotype":[0.5,-0.25]}"###
        );
        let read: SnapshotRow = serde_json::from_str(&line).unwrap();
        assert_eq!(read.record.as_ref(), Some(&record));
        assert_eq!(
            (read.seed(), read.fitness(), read.body()),
            (9, Some(1.5), Some("##/##"))
        );
        assert_eq!(read.genotype, serde_json::json!([0.5, -0.25]));
        assert_eq!(read.morphology().unwrap().voxel_count(), 4);
    }
}
