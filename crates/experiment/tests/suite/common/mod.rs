//! Helpers shared by the experiment crate's integration tests.

use vsrlab_experiment::runner::{Flow, Observer, Progress, RunOptions};

/// Interrupts the run after `after` generations of run `run`, as a kill would.
pub struct Killer {
    /// The run to interrupt.
    pub run: usize,
    /// After how many of its generations.
    pub after: u64,
}

impl Observer for Killer {
    fn generation(&mut self, progress: &Progress) -> Flow {
        if progress.run == self.run && progress.generation >= self.after {
            Flow::Interrupt
        } else {
            Flow::Continue
        }
    }
}

/// Two worker threads, resuming or not.
pub fn two_threads(resume: bool) -> RunOptions {
    RunOptions {
        threads: 2,
        resume,
        ..RunOptions::default()
    }
}

/// A 2021 biped-4x3 without sensors whose phase-grid brain has these per-cell phases: the robot
/// the test genotypes (graphs of phase neurons, quantised phases) map to. Not every test binary
/// that includes this module uses it.
#[allow(dead_code)]
pub fn phase_biped(phases: &[f64]) -> Result<Box<dyn vsrlab_tasks::Robot>, vsrlab_tasks::EvaluationError> {
    let brain = vsrlab_brain::BrainSpec::parse("phase-grid")
        .and_then(|b| b.with_parameters(phases))
        .map_err(|e| vsrlab_tasks::EvaluationError::Genotype(vsrlab_field::FieldError::new("brain", e.to_string())))?;
    Ok(Box::new(vsrlab_tasks::RobotSpec {
        body: vsrlab_body::Morphology::parse("biped-4x3").unwrap(),
        preset: vsrlab_body::Preset::Y2021,
        voxel: None,
        sensors: vsrlab_body::sensors::SensorConfig::parse("empty").unwrap(),
        brain,
    }))
}

/// Runs the experiment's vector-genotype runs into `out` on `threads` threads, from scratch,
/// silently.
pub fn run_on_threads(experiment: &vsrlab_experiment::config::Experiment, out: &std::path::Path, threads: usize) {
    let evaluator = vsrlab_experiment::evaluator::RobotEvaluator::new(experiment).unwrap();
    let options = RunOptions {
        threads,
        resume: false,
        ..RunOptions::default()
    };
    vsrlab_experiment::genotypes::vector::run_vectors(
        experiment,
        &evaluator,
        out,
        &options,
        &mut vsrlab_experiment::runner::Silent,
    )
    .unwrap();
}
