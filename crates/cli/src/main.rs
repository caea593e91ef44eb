//! `vsrlab`: the command-line front end. It parses arguments, builds the pieces from the library
//! crates and hands over; it holds no domain logic.
// Doc comments here are clap help texts, with `<placeholders>` that are not HTML.
#![allow(rustdoc::invalid_html_tags)]

mod analyze;
mod bench;
mod campaign;
mod codesign;
mod evaluate;
mod fidelity;
mod inflate;
mod label;
mod modules;
mod monitor;
mod overrides;
mod plasticity;
mod python;
mod reassess;
mod run;
mod simulate;
mod stdout_errors;
mod validate;
mod view;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

/// Simulate, evolve, render and benchmark soft robots: voxel-based soft robots and pressure-based
/// soft agents.
#[derive(Parser)]
#[command(name = "vsrlab", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one episode and print its outcome (optionally render a video).
    Simulate(Box<simulate::SimulateArgs>),
    /// Measure simulation speed on the standard robots, single-threaded and on every core.
    Bench(bench::BenchArgs),
    /// Run an evolutionary experiment described in a TOML file (docs/experiments.md).
    Run(run::RunArgs),
    /// Run many experiment files (every setting, every run) side by side, locally or on a Ray
    /// cluster, each setting in its own folder (docs/cluster.md, "Campaigns").
    Campaign(campaign::CampaignArgs),
    /// Fitness of given genotypes (rows of genes) on an experiment's robot and task, for
    /// optimisers outside vsrlab; the same evaluations as `vsrlab run`.
    Evaluate(evaluate::EvaluateArgs),
    /// Check experiment files: print each resolved configuration, its sizes and a time estimate.
    Validate(validate::ValidateArgs),
    /// The 2D fidelity protocol: vsrlab's start-shift ensembles against the original
    /// simulator's, case by case, with the tests' verdicts (docs/fidelity.md, "The protocol").
    Fidelity(fidelity::FidelityArgs),
    /// Figures and a summary table from the output of `vsrlab run` (docs/analysis.md).
    Analyze(analyze::AnalyzeArgs),
    /// Render a stratified sample of evolved robots into an HTML page for labelling species.
    Label(label::LabelArgs),
    /// Replay the best robot of every run on unseen episodes (new terrains, damage) and compare
    /// the settings.
    Reassess(reassess::ReassessArgs),
    /// Frozen-weight test and weight histograms of evolved Hebbian robots (docs/ch5.3.md).
    Plasticity(plasticity::PlasticityArgs),
    /// Learning curves, learning radius and morphology over evolution of co-design runs
    /// (docs/ch5.2.md).
    Codesign(codesign::CodesignArgs),
    /// Discover the most compact module of every evolved graph brain (docs/ch4.1.md).
    Modules(modules::ModulesArgs),
    /// Reassemble evolved graph brains from two runs' robots and write their re-optimisation
    /// experiment (docs/ch4.1.md).
    Reassemble(modules::ReassembleArgs),
    /// Transferability ρ and edges cut η of re-optimised reassembled robots, per setting.
    Transferability(modules::TransferabilityArgs),
    /// The PSA inflation protocol: φ and pressure per step for each size (docs/psa.md).
    Inflate(inflate::InflateArgs),
    /// Watch replays in the browser: serves the viewer page on 127.0.0.1 (docs/viewer.md).
    View(view::ViewArgs),
    /// Print a shell completion script, e.g. `vsrlab completions bash > ~/.local/share/bash-completion/completions/vsrlab`.
    Completions {
        /// The shell: bash, zsh, fish, elvish or powershell.
        shell: clap_complete::Shell,
    },
}

fn main() -> ExitCode {
    stdout_errors::install();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Simulate(a) => simulate::run(*a),
        Command::Bench(a) => bench::run(a),
        Command::Run(a) => run::run(a),
        Command::Campaign(a) => campaign::run(a),
        Command::Evaluate(a) => evaluate::run(a),
        Command::Validate(a) => validate::run(a),
        Command::Fidelity(a) => fidelity::run(a),
        Command::Analyze(a) => analyze::run(a),
        Command::Label(a) => label::run(a),
        Command::Reassess(a) => reassess::run(a),
        Command::Plasticity(a) => plasticity::run(a),
        Command::Codesign(a) => codesign::run(a),
        Command::Modules(a) => modules::run_modules(a),
        Command::Reassemble(a) => modules::run_reassemble(a),
        Command::Transferability(a) => modules::run_transferability(a),
        Command::Inflate(a) => inflate::run(a),
        Command::View(a) => view::run(a),
        Command::Completions { shell } => {
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "vsrlab", &mut script);
            print!("{}", String::from_utf8_lossy(&script));
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
