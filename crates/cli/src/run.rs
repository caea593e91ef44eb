//! `vsrlab run`: runs an experiment file (docs/experiments.md) with progress bars.

use clap::Args;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::PathBuf;
use std::time::Instant;
use vsrlab_experiment::memory::{gib, MemoryEstimate};
use vsrlab_experiment::runner::{run_experiment, Flow, Observer, Progress, RunOptions, RunSummary, MAX_THREADS};
use vsrlab_experiment::{config, RobotEvaluator};

/// Arguments of `vsrlab run`.
#[derive(Args, Debug)]
pub struct RunArgs {
    /// The experiment file (TOML).
    pub experiment: PathBuf,
    /// Output folder (default: out/<experiment name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads for evaluations (default: every core). Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Continue an interrupted experiment from its checkpoints (finished runs are kept).
    #[arg(long)]
    pub resume: bool,
    /// Refuse a run whose estimated memory exceeds this many GiB (docs/experiments.md).
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory_gib: f64,
}

/// Positions per run on the progress bars.
const TICKS: u64 = 1000;

/// Progress bars: one for the whole experiment, one for the current run. Hidden when stderr is
/// not a terminal; then one line per finished run is printed instead.
struct Bars {
    multi: MultiProgress,
    overall: ProgressBar,
    current: Option<ProgressBar>,
    runs: usize,
    finished: usize,
    interactive: bool,
}

impl Bars {
    fn new(runs: usize) -> Bars {
        let multi = MultiProgress::with_draw_target(ProgressDrawTarget::stderr());
        let interactive = !multi.is_hidden();
        let overall = multi.add(ProgressBar::new(runs as u64 * TICKS));
        overall.set_style(
            ProgressStyle::with_template(
                "experiment [{bar:40.cyan/blue}] {percent:>3}% {elapsed_precise} ETA {eta_precise} {msg}",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        overall.set_message(format!("0/{runs} runs"));
        Bars {
            multi,
            overall,
            current: None,
            runs,
            finished: 0,
            interactive,
        }
    }
}

fn fitness(v: f64) -> String {
    if v.is_nan() {
        "-".to_string()
    } else {
        format!("{v:.4}")
    }
}

impl Observer for Bars {
    fn run_started(&mut self, p: &Progress) {
        let bar = self.multi.add(ProgressBar::new(TICKS));
        bar.set_style(
            ProgressStyle::with_template(
                "run {prefix:>6} [{bar:40.green/white}] {percent:>3}% ETA {eta_precise} {msg}",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        bar.set_prefix(format!("{}/{}", p.run + 1, p.runs));
        bar.set_position((p.fraction * TICKS as f64) as u64);
        bar.reset_eta();
        self.current = Some(bar);
    }

    fn generation(&mut self, p: &Progress) -> Flow {
        if let Some(bar) = &self.current {
            bar.set_position((p.fraction * TICKS as f64) as u64);
            bar.set_message(format!(
                "gen {} · {} evals · best {}",
                p.generation,
                p.evaluations,
                fitness(p.best_fitness)
            ));
        }
        self.overall
            .set_position(self.finished as u64 * TICKS + (p.fraction * TICKS as f64) as u64);
        Flow::Continue
    }

    fn notice(&mut self, message: &str) {
        if self.interactive {
            let _ = self.multi.println(format!("note: {message}"));
        } else {
            eprintln!("note: {message}");
        }
    }

    fn run_finished(&mut self, s: &RunSummary) {
        self.finished += 1;
        if let Some(bar) = self.current.take() {
            bar.finish_and_clear();
            self.multi.remove(&bar);
        }
        let line = format!(
            "run {}/{}: best {} after {} evaluations ({}), {:.1} s, {:.1}% outside episodes",
            s.run + 1,
            self.runs,
            s.best_fitness.map_or("-".to_string(), fitness),
            s.evaluations,
            s.stop_reason,
            s.wall_seconds,
            100.0 * s.overhead_fraction
        );
        if self.interactive {
            let _ = self.multi.println(line);
        } else {
            eprintln!("{line}");
        }
        self.overall.set_position(self.finished as u64 * TICKS);
        self.overall
            .set_message(format!("{}/{} runs", self.finished, self.runs));
    }
}

/// Runs `vsrlab run`.
pub fn run(a: RunArgs) -> Result<(), String> {
    let experiment = config::load(&a.experiment).map_err(|e| e.to_string())?;
    let name = experiment.name.clone().unwrap_or_else(|| "experiment".to_string());
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from("out").join(&name));
    let evaluator = RobotEvaluator::new(&experiment).map_err(|e| e.to_string())?;
    if !(a.max_memory_gib.is_finite() && a.max_memory_gib > 0.0) {
        return Err(format!(
            "--max-memory-gib must be a positive number, got {}",
            a.max_memory_gib
        ));
    }
    let options = RunOptions {
        threads: a.threads.unwrap_or(0),
        resume: a.resume,
        memory_limit: Some((a.max_memory_gib * (1u64 << 30) as f64).min(u64::MAX as f64) as u64),
    };
    let threads = match options.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n.min(MAX_THREADS),
    };
    let estimate = MemoryEstimate::of(&experiment, evaluator.genotype_length(), threads);
    eprintln!(
        "{name}: {} run(s), {} genes per genotype, about {} per run, output in {}",
        experiment.runs,
        evaluator.genotype_length(),
        gib(estimate.bytes),
        out.display()
    );
    let start = Instant::now();
    let mut bars = Bars::new(experiment.runs);
    let result = run_experiment(&experiment, &evaluator, &out, &options, &mut bars);
    bars.overall.finish_and_clear();
    let summaries = result.map_err(|e| e.to_string())?;
    let best = summaries.iter().filter_map(|s| s.best_fitness).fold(f64::NAN, f64::max);
    println!(
        "{name}: {} run(s) done in {:.1} s; best fitness {}; results in {}",
        summaries.len(),
        start.elapsed().as_secs_f64(),
        fitness(best),
        out.display()
    );
    Ok(())
}
