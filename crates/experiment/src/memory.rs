//! An estimate of the memory one run of an experiment needs, checked before anything is written
//! so that a population or a brain too large for the machine is refused with a message instead
//! of an allocation failure an hour later.
//!
//! The estimate counts what grows with the settings: every genotype the optimizer holds at once
//! (population, offspring, the batch being evaluated, an archive), its matrices (CMA-ES), and the
//! per-thread copies of a genotype during evaluation, and each thread's episode (a generous
//! figure, plus the buffers a body's settings size, such as a PSA's sensor window). Each gene costs 8 bytes in memory and about
//! 24 bytes of JSON text in each of the checkpoint and the snapshot being written: 64 bytes per
//! gene in all. It is a rough upper figure, not a measurement.

use crate::config::Experiment;

/// Bytes per gene held: the f64 and its JSON text in a checkpoint and a snapshot.
const BYTES_PER_GENE: u128 = 64;
/// Simulation memory per worker thread besides the genotype (world, robot, trace): a generous
/// figure for the largest bodies.
const BYTES_PER_THREAD: u128 = 64 << 20;

/// The default limit on the estimate: 8 GiB (raise it with `vsrlab run --max-memory-gib`).
pub const DEFAULT_MEMORY_LIMIT: u64 = 8 << 30;

/// What one run is estimated to need.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Genes per genotype.
    pub genes: usize,
    /// Genotypes held at once.
    pub genotypes: u128,
    /// Estimated bytes.
    pub bytes: u128,
}

impl MemoryEstimate {
    /// The estimate for one run of `experiment` with genotypes of `genes` genes on `threads`
    /// worker threads.
    pub fn of(experiment: &Experiment, genes: usize, threads: usize) -> MemoryEstimate {
        let kind = experiment.optimizer.kind();
        let budget = experiment.stop.evaluations.or(experiment.stop.births);
        let genotypes = kind.held_genotypes(genes, budget);
        let floats = genotypes
            .saturating_mul(genes as u128)
            .saturating_add(kind.held_matrix_floats(genes))
            .saturating_add((threads.max(1) as u128).saturating_mul(2 * genes as u128));
        let dt = experiment.task.spec.task().step_seconds();
        let per_thread = BYTES_PER_THREAD.saturating_add(experiment.representation.body.episode_bytes(dt));
        let bytes = floats
            .saturating_mul(BYTES_PER_GENE)
            .saturating_add((threads.max(1) as u128).saturating_mul(per_thread));
        MemoryEstimate {
            genes,
            genotypes,
            bytes,
        }
    }

    /// Refuses an estimate above `limit` bytes, saying what to change.
    pub fn check(&self, limit: u64) -> Result<(), MemoryLimit> {
        if self.bytes <= u128::from(limit) {
            return Ok(());
        }
        Err(MemoryLimit { estimate: *self, limit })
    }
}

/// An experiment whose memory estimate is above the limit: the message says by how much and
/// what to change.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "this experiment needs about {} per run ({} genotypes of {} genes held at once), above the \
     memory limit of {}: lower the optimizer's population/offspring sizes or the brain's size, or raise \
     the limit with --max-memory-gib",
    gib(estimate.bytes), estimate.genotypes, estimate.genes, gib(u128::from(*limit))
)]
pub struct MemoryLimit {
    /// What one run was estimated to need.
    pub estimate: MemoryEstimate,
    /// The limit it is above, in bytes.
    pub limit: u64,
}

/// Bytes as GiB, for messages.
pub fn gib(bytes: u128) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config;

    fn experiment(optimizer: &str) -> Experiment {
        let text = format!(
            "[representation]\nbody = \"biped-4x3\"\nsensors = \"uniform-vxy+a+t-0\"\n\
             brain = {{ kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [] }}\n\
             [task]\nterrain = \"flat\"\n[optimizer]\n{optimizer}\n[stop]\nevaluations = 1000\n"
        );
        config::parse(&text, "test.toml").unwrap()
    }

    #[test]
    fn grows_with_the_population_and_the_genes() {
        let small = MemoryEstimate::of(&experiment("kind = \"ga\"\npopulation_size = 10"), 100, 1);
        let big = MemoryEstimate::of(&experiment("kind = \"ga\"\npopulation_size = 1000"), 100, 1);
        assert!(big.bytes > small.bytes);
        assert!(big.genotypes > small.genotypes);
        let more_genes = MemoryEstimate::of(&experiment("kind = \"ga\"\npopulation_size = 10"), 10_000, 1);
        assert!(more_genes.bytes > small.bytes);
    }

    #[test]
    fn a_default_run_fits_and_a_huge_one_is_refused_with_the_fix() {
        let quick = MemoryEstimate::of(&experiment("kind = \"ga\""), 45, 16);
        quick.check(DEFAULT_MEMORY_LIMIT).unwrap();
        let huge = MemoryEstimate::of(&experiment("kind = \"ga\"\npopulation_size = 1000000"), 50_000, 2);
        let message = huge.check(DEFAULT_MEMORY_LIMIT).unwrap_err().to_string();
        assert!(message.contains("--max-memory-gib"), "{message}");
        assert!(message.contains("50000 genes"), "{message}");
        // CMA-ES's matrices alone: 3·n² floats
        let cma = MemoryEstimate::of(&experiment("kind = \"cma-es\""), 100_000, 1);
        assert!(cma.bytes > 3 * 100_000u128 * 100_000 * 8);
        assert!(cma.check(DEFAULT_MEMORY_LIMIT).is_err());
    }

    #[test]
    fn a_psa_sensor_window_counts_in_each_thread() {
        let psa = |window: &str| {
            let text = format!(
                "[representation]\nbody = {{ kind = \"psa\", size = \"small\", sensor_window = {window} }}\n\
                 brain = {{ kind = \"heads\", linear_outputs = 1 }}\n\
                 [task]\nterrain = \"flat\"\n[optimizer]\nkind = \"cma-es\"\n[stop]\nevaluations = 100\n"
            );
            MemoryEstimate::of(&config::parse(&text, "psa.toml").unwrap(), 374, 4)
        };
        let (usual, long) = (psa("0.25"), psa("1e4"));
        // 1e4 s at 60 Hz: 6e5 steps of 33 readings, 8 bytes each, in each of 4 threads
        let window = 6e5 * 33.0 * 8.0 * 4.0;
        let grown = (long.bytes - usual.bytes) as f64;
        assert!((grown - window).abs() / window < 0.01, "{grown} vs {window}");
        assert!(long.check(512 << 20).is_err() && usual.check(512 << 20).is_ok());
    }
}
