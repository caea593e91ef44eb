//! `vsrlab run`: runs an experiment file (docs/experiments.md) with progress bars.

use clap::Args;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::{Path, PathBuf};
use std::time::Instant;
use vsrlab_experiment::memory::{gib, MemoryEstimate};
use vsrlab_experiment::runner::{worker_threads, Flow, Observer, Progress, RunOptions, RunSummary};
use vsrlab_experiment::{config, run_configured, Experiment};

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
    /// When stderr is not a terminal (batch jobs, nohup, SLURM): seconds between progress lines.
    #[arg(long, default_value_t = 60.0, value_name = "SECONDS")]
    pub log_every: f64,
    /// Refuse a run whose estimated memory exceeds this many GiB (docs/experiments.md).
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory_gib: f64,
    /// Evaluate on a Ray cluster ('auto', 'local' or HOST:PORT) through vsrlab's Python package
    /// (the interpreter in $VSRLAB_PYTHON, or python3); a sweep goes as a campaign.
    #[arg(long, value_name = "ADDRESS")]
    pub ray: Option<String>,
    /// Physics solver of 2D voxel tasks, replacing the experiment file's: soft-substeps
    /// (vsrlab's, fast) or sequential-impulses (dyn4j's pipeline, the original's dynamics;
    /// docs/fidelity.md).
    #[arg(long)]
    pub solver: Option<String>,
}

/// Positions per run on the progress bars.
const TICKS: u64 = 1000;

/// Progress bars: one for the whole experiment, one for the current run. Hidden when stderr is
/// not a terminal; then a progress line is printed every `log_every` seconds and one line per
/// finished run.
struct Bars {
    multi: MultiProgress,
    overall: ProgressBar,
    current: Option<ProgressBar>,
    runs: usize,
    finished: usize,
    interactive: bool,
    log_every: f64,
    last_log: Instant,
}

impl Bars {
    fn new(runs: usize, log_every: f64) -> Bars {
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
            log_every,
            last_log: Instant::now(),
        }
    }

    /// A line above the bars on a terminal, a plain line on stderr otherwise.
    fn say(&self, line: String) {
        if self.interactive {
            let _ = self.multi.println(line);
        } else {
            eprintln!("{line}");
        }
    }
}

/// Seconds as `1 h 47 min`, `3 min 20 s` or `12 s`.
pub(crate) fn duration(seconds: f64) -> String {
    let s = if seconds.is_finite() {
        seconds.max(0.0).round() as u64
    } else {
        0
    };
    match s {
        0..=59 => format!("{s} s"),
        60..=3599 => format!("{} min {} s", s / 60, s % 60),
        _ => format!("{} h {} min", s / 3600, (s % 3600) / 60),
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
        if p.generation > 0 {
            self.say(format!(
                "run {}/{}: resumed from its checkpoint at generation {} ({} evaluations, best {})",
                p.run + 1,
                p.runs,
                p.generation,
                p.evaluations,
                fitness(p.best_fitness)
            ));
        }
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
        if !self.interactive && self.last_log.elapsed().as_secs_f64() >= self.log_every {
            self.last_log = Instant::now();
            let eta = if p.fraction > 0.0 {
                format!(", ETA {}", duration(p.elapsed * (1.0 - p.fraction) / p.fraction))
            } else {
                String::new()
            };
            eprintln!(
                "run {}/{}: generation {} · {} evaluations · best {} · {:.0}% of the run{eta}",
                p.run + 1,
                p.runs,
                p.generation,
                p.evaluations,
                fitness(p.best_fitness),
                100.0 * p.fraction
            );
        }
        Flow::Continue
    }

    fn notice(&mut self, message: &str) {
        self.say(format!("note: {message}"));
    }

    fn run_finished(&mut self, s: &RunSummary) {
        self.finished += 1;
        if let Some(bar) = self.current.take() {
            bar.finish_and_clear();
            self.multi.remove(&bar);
        }
        let line = if s.evaluations > 0 && s.failures >= s.evaluations {
            format!(
                "run {}/{}: every one of its {} evaluations failed, so it has no best robot \
                 (`vsrlab validate` on the experiment file shows why an evaluation fails), {:.1} s",
                s.run + 1,
                self.runs,
                s.evaluations,
                s.wall_seconds
            )
        } else {
            format!(
                "run {}/{}: best {} after {} evaluations ({}), {:.1} s, {:.1}% outside episodes",
                s.run + 1,
                self.runs,
                s.best_fitness.map_or("-".to_string(), fitness),
                s.evaluations,
                s.stop_reason,
                s.wall_seconds,
                100.0 * s.overhead_fraction
            )
        };
        self.say(line);
        self.overall.set_position(self.finished as u64 * TICKS);
        self.overall
            .set_message(format!("{}/{} runs", self.finished, self.runs));
    }
}

/// The bytes of `--max-memory-gib`, refusing a value that is not a positive number.
pub fn memory_limit(gib: f64) -> Result<u64, String> {
    if !(gib.is_finite() && gib > 0.0) {
        return Err(format!("--max-memory-gib must be a positive number, got {gib}"));
    }
    Ok((gib * (1u64 << 30) as f64).min(u64::MAX as f64) as u64)
}

/// Runs `vsrlab run`: one experiment, or every setting of a sweep one after the other (each in
/// its own folder under the output folder).
pub fn run(a: RunArgs) -> Result<(), String> {
    memory_limit(a.max_memory_gib)?;
    if !(a.log_every.is_finite() && a.log_every >= 0.0) {
        return Err(format!(
            "--log-every must be a number of seconds ≥ 0, got {}",
            a.log_every
        ));
    }
    let mut experiments = config::load_all(&a.experiment).map_err(|e| e.to_string())?;
    if let Some(solver) = &a.solver {
        for experiment in &mut experiments {
            experiment
                .task
                .set_solver(solver)
                .map_err(|e| e.at("--solver").to_string())?;
        }
    }
    if let [experiment] = experiments.as_slice() {
        let name = experiment.name.clone().unwrap_or_else(|| "experiment".to_string());
        let out = a.out.clone().unwrap_or_else(|| PathBuf::from("out").join(&name));
        if let Some(address) = &a.ray {
            return crate::python::hand_over(&ray_request("run", &a, &out, address).arguments());
        }
        return run_one(experiment, &out, &a);
    }
    let stem = a
        .experiment
        .file_stem()
        .map_or("sweep".to_string(), |s| s.to_string_lossy().into_owned());
    let base = a.out.clone().unwrap_or_else(|| PathBuf::from("out").join(stem));
    if let Some(address) = &a.ray {
        return crate::python::hand_over(&ray_request("campaign", &a, &base, address).arguments());
    }
    eprintln!(
        "{}: a sweep of {} settings, each in its own folder under {}",
        a.experiment.display(),
        experiments.len(),
        base.display()
    );
    for experiment in &experiments {
        let name = experiment.name.clone().unwrap_or_else(|| "experiment".to_string());
        run_one(experiment, &base.join(name), &a)?;
    }
    Ok(())
}

/// Runs one experiment into `out`.
fn run_one(experiment: &Experiment, out: &Path, a: &RunArgs) -> Result<(), String> {
    let name = experiment.name.clone().unwrap_or_else(|| "experiment".to_string());
    let options = RunOptions {
        threads: a.threads.unwrap_or(0),
        resume: a.resume,
        memory_limit: Some(memory_limit(a.max_memory_gib)?),
        ..RunOptions::default()
    };
    let threads = worker_threads(options.threads);
    let size = experiment.genotype_kind().size(experiment).map_err(|e| e.to_string())?;
    let (genes, genotype) = (size.genes, size.text);
    let estimate = MemoryEstimate::of(experiment, genes, threads);
    eprintln!(
        "{name}: {} run(s), {genotype}, about {} per run, output in {}",
        experiment.runs,
        gib(estimate.bytes),
        out.display()
    );
    let start = Instant::now();
    let mut bars = Bars::new(experiment.runs, a.log_every);
    let result = run_configured(experiment, out, &options, &mut bars);
    bars.overall.finish_and_clear();
    let summaries = result.map_err(|e| e.to_string())?;
    // the best of the runs' bests by the first objective's sense (smaller is better when minimised)
    let sense = experiment.senses().first().copied().unwrap_or_default();
    let best = summaries
        .iter()
        .filter_map(|s| s.best_fitness)
        .max_by(|a, b| sense.compare(*a, *b))
        .unwrap_or(f64::NAN);
    println!(
        "{name}: {} run(s) done in {:.1} s; best fitness {}; results in {}",
        summaries.len(),
        start.elapsed().as_secs_f64(),
        fitness(best),
        out.display()
    );
    Ok(())
}

/// `python -m vsrlab COMMAND FILE --out OUT --ray ADDRESS …` with this command's settings.
fn ray_request<'a>(
    command: &'static str,
    a: &'a RunArgs,
    out: &'a Path,
    address: &'a str,
) -> crate::python::RayRequest<'a> {
    crate::python::RayRequest {
        command,
        files: std::slice::from_ref(&a.experiment),
        out,
        address,
        resume: a.resume,
        threads: a.threads,
        solver: a.solver.as_deref(),
    }
}
