//! `vsrlab campaign`: many experiment files × their runs side by side, each setting in its own
//! folder, with progress lines, an ETA and a summary table (docs/cluster.md, "Campaigns"). With
//! `--ray` it hands over to vsrlab's Python package, which sends the batches to a Ray cluster.

use crate::run::{duration, memory_limit};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use vsrlab_experiment::campaign::{self, CampaignObserver, Setting, Standing};
use vsrlab_experiment::runner::{Flow, Progress, RunOptions, RunSummary};

/// Arguments of `vsrlab campaign`.
#[derive(Args, Debug)]
pub struct CampaignArgs {
    /// Experiment files (TOML); a sweep file gives each of its settings.
    #[arg(required = true)]
    pub experiments: Vec<PathBuf>,
    /// Output folder: each setting in <OUT>/<setting name>, as `vsrlab run` writes it.
    #[arg(long)]
    pub out: PathBuf,
    /// Worker threads shared by every run (default: every core). Results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Continue every unfinished run from its checkpoint (finished runs are kept).
    #[arg(long)]
    pub resume: bool,
    /// Seconds between progress lines.
    #[arg(long, default_value_t = 30.0, value_name = "SECONDS")]
    pub log_every: f64,
    /// Refuse a run whose estimated memory exceeds this many GiB (docs/experiments.md).
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory_gib: f64,
    /// Evaluate on a Ray cluster ('auto', 'local' or HOST:PORT) through vsrlab's Python package
    /// (the interpreter in $VSRLAB_PYTHON, or python3).
    #[arg(long, value_name = "ADDRESS")]
    pub ray: Option<String>,
    /// Physics solver of 2D voxel tasks, replacing every file's (as `vsrlab run --solver`).
    #[arg(long)]
    pub solver: Option<String>,
}

/// Progress lines: each finished run, and the campaign's share done with an ETA every
/// `log_every` seconds.
struct Lines {
    names: Vec<String>,
    runs: Vec<usize>,
    standing: Standing,
    /// The share done when this session began (a resumed campaign's finished part).
    start_fraction: Option<f64>,
    start: Instant,
    last_log: Instant,
    log_every: f64,
    /// The last line's share done (per mille) and finished runs, not printed twice.
    last_line: Option<(u64, usize)>,
}

impl Lines {
    fn log(&mut self, always: bool) {
        if !always && self.last_log.elapsed().as_secs_f64() < self.log_every {
            return;
        }
        let now = ((1000.0 * self.standing.fraction()) as u64, self.standing.runs_done().0);
        if self.last_line == Some(now) {
            return;
        }
        self.last_line = Some(now);
        self.last_log = Instant::now();
        let elapsed = self.start.elapsed().as_secs_f64();
        let start = *self.start_fraction.get_or_insert(self.standing.fraction());
        let (done, all) = self.standing.runs_done();
        let eta = (self.standing.eta(start, elapsed)).map_or(String::new(), |s| format!(", ETA {}", duration(s)));
        eprintln!(
            "campaign: {:.0}% · {done}/{all} runs done · {} elapsed{eta}",
            100.0 * self.standing.fraction(),
            duration(elapsed)
        );
    }
}

impl CampaignObserver for Lines {
    fn run_started(&mut self, setting: usize, p: &Progress) {
        self.standing.set(setting, p.run, p.fraction);
        if p.generation > 0 {
            eprintln!(
                "{} run {}/{}: resumed at generation {} ({} evaluations)",
                self.names[setting],
                p.run + 1,
                p.runs,
                p.generation,
                p.evaluations
            );
        }
    }

    fn generation(&mut self, setting: usize, p: &Progress) -> Flow {
        self.standing.set(setting, p.run, p.fraction);
        self.log(false);
        Flow::Continue
    }

    fn run_finished(&mut self, setting: usize, s: &RunSummary) {
        self.standing.set(setting, s.run, 1.0);
        eprintln!(
            "{} run {}/{}: best {} after {} evaluations ({}), {:.1} s",
            self.names[setting],
            s.run + 1,
            self.runs[setting],
            s.best_fitness.map_or("-".to_string(), |v| format!("{v:.4}")),
            s.evaluations,
            s.stop_reason,
            s.wall_seconds
        );
        self.log(false);
    }

    fn notice(&mut self, setting: usize, message: &str) {
        eprintln!("{}: note: {message}", self.names[setting]);
    }
}

/// Runs `vsrlab campaign`.
pub fn run(a: CampaignArgs) -> Result<(), String> {
    let memory_limit = memory_limit(a.max_memory_gib)?;
    if !(a.log_every.is_finite() && a.log_every >= 0.0) {
        return Err(format!(
            "--log-every must be a number of seconds ≥ 0, got {}",
            a.log_every
        ));
    }
    let mut settings = campaign::settings(&a.experiments, &a.out).map_err(|e| e.to_string())?;
    if let Some(solver) = &a.solver {
        for setting in &mut settings {
            setting
                .experiment
                .task
                .set_solver(solver)
                .map_err(|e| e.at("--solver").to_string())?;
        }
    }
    if let Some(address) = &a.ray {
        let request = crate::python::RayRequest {
            command: "campaign",
            files: &a.experiments,
            out: &a.out,
            address,
            resume: a.resume,
            threads: a.threads,
            solver: a.solver.as_deref(),
        };
        return crate::python::hand_over(&request.arguments());
    }
    let runs: Vec<usize> = settings.iter().map(|s| s.experiment.runs).collect();
    eprintln!(
        "campaign: {} settings, {} runs side by side, output in {}",
        settings.len(),
        runs.iter().sum::<usize>(),
        a.out.display()
    );
    let mut lines = Lines {
        names: settings.iter().map(|s: &Setting| s.name.clone()).collect(),
        runs,
        standing: Standing::new(&settings.iter().map(|s| s.experiment.runs).collect::<Vec<_>>()),
        start_fraction: None,
        start: Instant::now(),
        last_log: Instant::now(),
        log_every: a.log_every,
        last_line: None,
    };
    let options = RunOptions {
        threads: a.threads.unwrap_or(0),
        resume: a.resume,
        memory_limit: Some(memory_limit),
        ..RunOptions::default()
    };
    let results = campaign::run_campaign(&settings, &options, &mut lines).map_err(|e| e.to_string())?;
    lines.log(true);
    print!("{}", campaign::table(&settings, &results));
    Ok(())
}
