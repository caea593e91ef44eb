//! `vsrlab run` end to end: a run killed with SIGKILL and resumed ends with the same files as an
//! uninterrupted one; a bad experiment file is reported with its field and line.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

/// About 60 short generations: long enough to be killed in the middle.
const EXPERIMENT: &str = r#"
runs = 1
seed = 5

[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }

[task]
duration = 3.0

[optimizer]
kind = "ga"
population_size = 10
offspring_size = 10

[stop]
generations = 60

[output]
snapshot_every = 200
"#;

fn deterministic_files(out: &Path) -> Vec<(String, Vec<u8>)> {
    vsrlab_experiment::runner::deterministic_files(out).unwrap()
}

fn vsrlab(args: &[&str]) -> std::process::Output {
    Command::new(VSRLAB).args(args).output().unwrap()
}

/// Starts `vsrlab run FILE --out OUT --threads THREADS` in the background, to be killed.
fn spawn_run(file: &str, out: &Path, threads: &str) -> Child {
    Command::new(VSRLAB)
        .args(["run", file, "--out", out.to_str().unwrap(), "--threads", threads])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Polls `ready` until it holds; fails the test after a minute, naming `what` it waited for.
fn wait_for(what: &str, mut ready: impl FnMut() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(start.elapsed() < Duration::from_secs(60), "waited a minute for {what}");
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn killed_run_resumes_to_the_same_files() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("exp.toml");
    std::fs::write(&file, EXPERIMENT).unwrap();
    let file = file.to_str().unwrap();
    let straight = dir.path().join("straight");
    let killed = dir.path().join("killed");

    let out = vsrlab(&["run", file, "--out", straight.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));

    let mut child = spawn_run(file, &killed, "2");
    let csv = killed.join("run-00/generations.csv");
    wait_for("a checkpoint after 5 generations", || {
        let rows = std::fs::read_to_string(&csv).map_or(0, |t| t.lines().count());
        rows >= 6 && killed.join("run-00/checkpoint.json").exists()
    });
    // A second process on the same folder is refused while the first one runs.
    let second = vsrlab(&["run", file, "--out", killed.to_str().unwrap(), "--resume"]);
    assert!(!second.status.success());
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(err.contains("in use by another vsrlab process"), "{err}");
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    assert!(
        !killed.join("run-00/summary.json").exists(),
        "the run finished before it could be killed"
    );
    // Without --resume the folder is refused; with it the run goes on.
    let refused = vsrlab(&["run", file, "--out", killed.to_str().unwrap()]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--resume"));
    // A damaged checkpoint is refused, naming the file; the intact one resumes.
    let checkpoint = killed.join("run-00/checkpoint.json");
    let intact = std::fs::read(&checkpoint).unwrap();
    std::fs::write(&checkpoint, &intact[..intact.len() - 20]).unwrap();
    let damaged = vsrlab(&["run", file, "--out", killed.to_str().unwrap(), "--resume"]);
    assert!(!damaged.status.success());
    let err = String::from_utf8_lossy(&damaged.stderr);
    assert!(err.contains("checkpoint.json"), "{err}");
    std::fs::write(&checkpoint, &intact).unwrap();
    let resumed = vsrlab(&[
        "run",
        file,
        "--out",
        killed.to_str().unwrap(),
        "--resume",
        "--threads",
        "1",
    ]);
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));

    let (a, b) = (deterministic_files(&straight), deterministic_files(&killed));
    assert!(a.iter().any(|(n, _)| n == "run-00/best.robot.json"));
    let names = |v: &[(String, Vec<u8>)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&a), names(&b));
    for ((na, ca), (nb, cb)) in a.iter().zip(&b) {
        assert_eq!(na, nb);
        assert!(ca == cb, "{na} differs after kill -9 and --resume");
    }
}

/// [`EXPERIMENT`] with generations of about two seconds on one thread (six evaluations of a
/// quarter of a second each), so that a kill falls inside a generation.
fn long_generations() -> String {
    EXPERIMENT
        .replace("duration = 3.0", "duration = 300.0")
        .replace("population_size = 10", "population_size = 6")
        .replace("offspring_size = 10", "offspring_size = 6")
        .replace("generations = 60", "generations = 2")
}

#[test]
fn a_run_killed_inside_a_generation_keeps_that_generations_finished_evaluations() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("exp.toml");
    std::fs::write(&file, long_generations()).unwrap();
    let file = file.to_str().unwrap();
    let straight = dir.path().join("straight");
    let killed = dir.path().join("killed");

    let out = vsrlab(&["run", file, "--out", straight.to_str().unwrap(), "--threads", "2"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(
        !straight.join("run-00/unfinished-generation.jsonl").exists(),
        "gone at the end"
    );

    let mut child = spawn_run(file, &killed, "1");
    let saved = killed.join("run-00/unfinished-generation.jsonl");
    wait_for("a saved evaluation", || saved.exists());
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let lines = std::fs::read_to_string(&saved).unwrap().lines().count();
    assert!(
        (1..6).contains(&lines),
        "{lines} evaluations saved in the first generation of 6"
    );
    assert!(
        !killed.join("run-00/generations.csv").exists(),
        "killed inside the first generation"
    );
    // A copy whose first saved evaluation is edited shows that saved evaluations are used, not
    // recomputed: the edited fitness becomes the run's best.
    let edited = dir.path().join("edited");
    std::fs::create_dir_all(edited.join("run-00")).unwrap();
    std::fs::copy(killed.join("experiment.toml"), edited.join("experiment.toml")).unwrap();
    let text = std::fs::read_to_string(&saved).unwrap();
    let mut first: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    first["evaluated"]["objectives"] = serde_json::json!([123456.0]);
    let rest: String = text.lines().skip(1).map(|l| format!("{l}\n")).collect();
    std::fs::write(
        edited.join("run-00/unfinished-generation.jsonl"),
        format!("{first}\n{rest}"),
    )
    .unwrap();
    let out = vsrlab(&["run", file, "--out", edited.to_str().unwrap(), "--resume"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let csv = std::fs::read_to_string(edited.join("run-00/generations.csv")).unwrap();
    assert!(csv.contains("123456"), "{csv}");

    let resumed = vsrlab(&["run", file, "--out", killed.to_str().unwrap(), "--resume"]);
    let err = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{err}");
    assert!(
        err.contains(&format!(
            "run 1/1: {lines} evaluations of the generation under way when it stopped are reused"
        )),
        "{err}"
    );
    assert!(!saved.exists(), "a checkpoint or the run's end covers them");
    let (a, b) = (deterministic_files(&straight), deterministic_files(&killed));
    assert_eq!(a.len(), b.len());
    for ((na, ca), (nb, cb)) in a.iter().zip(&b) {
        assert_eq!(na, nb);
        assert!(ca == cb, "{na} differs after a kill inside a generation and --resume");
    }
}

#[test]
fn bad_experiment_files_name_the_field_and_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(
        &file,
        EXPERIMENT.replace("population_size = 10", "population_size = -3"),
    )
    .unwrap();
    let out = vsrlab(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("line 15") && err.contains("optimizer.population_size"),
        "{err}"
    );
}

#[test]
fn an_experiment_name_cannot_write_outside_the_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path().join("a/b");
    std::fs::create_dir_all(&work).unwrap();
    let file = work.join("exp.toml");
    std::fs::write(&file, format!("name = \"../../escaped\"\n{EXPERIMENT}")).unwrap();
    let out = Command::new(VSRLAB)
        .args(["run", "exp.toml"])
        .current_dir(&work)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("'name'") && stderr.contains("line 1"), "{stderr}");
    // nothing was written: no output folder below, no escaped folder above
    assert!(!work.join("out").exists());
    assert!(!dir.path().join("escaped").exists() && !dir.path().join("a/escaped").exists());
}

#[test]
fn without_a_terminal_progress_is_logged_at_the_interval_and_resume_says_where_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("exp.toml");
    std::fs::write(&file, EXPERIMENT.replace("generations = 60", "generations = 3")).unwrap();
    let out_dir = dir.path().join("o");
    let args = ["run", file.to_str().unwrap(), "--out", out_dir.to_str().unwrap()];
    // stderr is a pipe here, as in a batch job
    let out = vsrlab(&[&args[..], &["--log-every", "0"]].concat());
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let lines = err.lines().filter(|l| l.contains("· best")).count();
    assert_eq!(lines, 3, "one line per generation with --log-every 0:\n{err}");
    assert!(err.contains("run 1/1: generation 3 · 30 evaluations"), "{err}");
    // Resuming a finished experiment: nothing resumed, the finished run is reported.
    let again = vsrlab(&[&args[..], &["--resume"]].concat());
    assert!(again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("run 1/1: best"));
}

/// The `.toml` files directly in these folders of the workspace, as paths.
fn shipped_toml_files(dirs: &[&str]) -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    for dir in dirs {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                files.push(path.display().to_string());
            }
        }
    }
    files
}

#[test]
fn every_2d_voxel_chapter_file_names_its_solver_and_run_solver_replaces_it() {
    // the thesis files run the original's dynamics, the reduced ones vsrlab's fast solver
    let mut files = shipped_toml_files(&[
        "experiments/ch3",
        "experiments/ch4.1",
        "experiments/ch4.2",
        "experiments/ch5.3",
    ]);
    files.push(format!("{}/../../experiments/ch3.toml", env!("CARGO_MANIFEST_DIR")));
    assert!(files.len() > 90, "{}", files.len());
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let name = file.rsplit('/').next().unwrap();
        let solver = match name.starts_with("reduced") {
            true => "soft-substeps",
            false => "sequential-impulses",
        };
        assert!(
            text.contains(&format!("[task.physics]\nsolver = \"{solver}\"")),
            "{file}"
        );
    }
    // `--solver` replaces the file's (the resolved file says so, and the results differ)
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("e.toml");
    let text = EXPERIMENT
        .replace("generations = 60", "generations = 1")
        .replace("duration = 3.0", "duration = 2.0");
    std::fs::write(&file, text).unwrap();
    let mut best = Vec::new();
    for solver in [None, Some("sequential-impulses")] {
        let out = dir.path().join(solver.unwrap_or("default"));
        let mut args = vec!["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend(solver.map(|s| ["--solver", s]).into_iter().flatten());
        let run = vsrlab(&args);
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        let resolved = std::fs::read_to_string(out.join("experiment.toml")).unwrap();
        let expected = solver.unwrap_or("soft-substeps");
        assert!(resolved.contains(&format!("solver = \"{expected}\"")), "{resolved}");
        best.push(std::fs::read_to_string(out.join("run-00/best.robot.json")).unwrap());
    }
    assert_ne!(best[0], best[1], "the solver changes the results");
    // a bad solver, or a task without a 2D solver, is refused naming the option; nothing written
    let out = dir.path().join("bad");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let three_d = root.join("experiments/ch5.1/reduced.toml");
    let refused = [
        (file.clone(), "dyn4j", "--solver: expected soft-substeps"),
        (three_d, "soft-substeps", "--solver: the affordance task has no 2D"),
    ];
    for (experiment, solver, message) in refused {
        let args = [
            "run",
            experiment.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--solver",
            solver,
        ];
        let run = vsrlab(&args);
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success() && err.contains(message), "{err}");
    }
    assert!(!out.exists());
}

#[test]
fn the_chapter_experiments_validate_and_transfers_name_their_missing_source() {
    // transfer files read the best robots of runs not made yet
    let (transfers, mut files): (Vec<String>, Vec<String>) =
        shipped_toml_files(&["experiments/ch4.2", "experiments/ch5.3"])
            .into_iter()
            .partition(|f| f.rsplit('/').next().is_some_and(|name| name.contains("transfer")));
    let text = validated_briefly(&mut files);
    // 4 bodies × 3 brains, 2 × 2 variants, 6 reduced, 1 scratch; 4 × 6 apparatus × brain, 2
    // normalised, 3 variants, 2 + 2 reduced
    assert_eq!(
        text.matches(": ok; ").count(),
        12 + 4 + 6 + 1 + 24 + 2 + 3 + 4,
        "{text}"
    );
    assert_eq!(transfers.len(), 5);
    for file in &transfers {
        assert_needs_a_best_robot(file, "transfer.from");
    }
}

/// `vsrlab validate --brief` of these files (sorted), which must all pass: its output.
fn validated_briefly(files: &mut [String]) -> String {
    files.sort();
    let args: Vec<&str> = ["validate", "--brief", "--threads", "1"]
        .into_iter()
        .chain(files.iter().map(String::as_str))
        .collect();
    let out = vsrlab(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A file that reads the best robot of a run not made yet is refused, naming `field`.
fn assert_needs_a_best_robot(file: &str, field: &str) {
    let out = vsrlab(&["validate", "--brief", file]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains(field) && err.contains("best.robot.json"),
        "{err}"
    );
}

#[test]
fn validate_prints_the_resolved_configuration_of_every_shipped_experiment() {
    // ch3.toml is the sweep of the 72 ch3/ files, checked by the experiment crate's tests
    let mut files: Vec<String> = shipped_toml_files(&["experiments", "experiments/ch3", "examples"])
        .into_iter()
        .filter(|f| !f.ends_with("experiments/ch3.toml"))
        .collect();
    files.sort();
    assert!(files.len() > 70, "{} files", files.len());
    let args: Vec<&str> = ["validate", "--threads", "1"]
        .into_iter()
        .chain(files.iter().map(String::as_str))
        .collect();
    let out = vsrlab(&args);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for file in &files {
        assert!(text.contains(&format!("# {file} (resolved)")), "{file}");
        assert!(text.contains(&format!("{file}: ok; ")), "{file}");
    }
    assert!(text.contains("population_size = "));
    // a bad file fails naming the field
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, EXPERIMENT.replace("duration = 3.0", "duration = -1")).unwrap();
    let out = vsrlab(&["validate", bad.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("task.duration"));
    // what `run` would refuse for its memory estimate, validate refuses too
    let file = dir.path().join("fine.toml");
    std::fs::write(&file, EXPERIMENT).unwrap();
    let out = vsrlab(&["validate", "--max-memory-gib", "0.01", file.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("--max-memory-gib"), "{err}");
}

#[test]
fn completions_are_printed_for_bash() {
    let out = vsrlab(&["completions", "bash"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("_vsrlab") && text.contains("validate"), "{text}");
}

/// Output into a pipe whose reader is gone (`| head -c 1`) ends quietly with status 0; into a
/// full disk (`> /dev/full`) with status 1 and a line saying so; never with a panic.
#[test]
fn a_closed_pipe_or_a_full_disk_ends_without_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("tiny.toml");
    std::fs::write(&file, EXPERIMENT.replace("generations = 60", "generations = 1")).unwrap();
    let (file, out) = (file.to_str().unwrap(), dir.path().join("o"));
    let commands: [&[&str]; 6] = [
        &["completions", "bash"],
        &["simulate", "--body", "biped-4x3", "--duration", "0.2", "--json"],
        &[
            "simulate",
            "--body",
            "biped-4x3",
            "--duration",
            "0.2",
            "--ensemble",
            "4",
        ],
        &[
            "validate",
            concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml"),
        ],
        &[
            "bench",
            "--robots",
            "biped-4x3",
            "--duration",
            "0.2",
            "--min-seconds",
            "0",
            "--single-only",
        ],
        // --resume: each of the runs below goes on from (or finds finished) the one before
        &["run", file, "--out", out.to_str().unwrap(), "--resume"],
    ];
    for args in commands {
        // the command's status and standard error, its standard output going to `stdout`
        let run_into = |stdout: Stdio| {
            let out = Command::new(VSRLAB)
                .args(args)
                .stdout(stdout)
                .stderr(Stdio::piped())
                .output()
                .unwrap();
            (out.status, String::from_utf8_lossy(&out.stderr).into_owned())
        };
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let (status, err) = run_into(writer.into());
        assert!(
            status.success() && !err.contains("panicked"),
            "{args:?}: {status:?} {err}"
        );
        if std::path::Path::new("/dev/full").exists() {
            let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
            let (status, err) = run_into(full.into());
            assert_eq!(status.code(), Some(1), "{args:?}: {err}");
            assert!(
                err.contains("cannot write to standard output") && !err.contains("panicked"),
                "{err}"
            );
        }
    }
}

#[test]
fn a_sweep_runs_every_setting_into_its_folder_and_analyze_compares_them() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("grid.toml");
    let text = EXPERIMENT.replace("generations = 60", "generations = 2");
    std::fs::write(
        &file,
        format!("name = \"grid\"\n{text}\n[sweep]\n\"task.duration\" = [1.0, 2.0]\n"),
    )
    .unwrap();
    let out = dir.path().join("o");
    let run = vsrlab(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    for setting in ["grid-1.0", "grid-2.0"] {
        assert!(out.join(setting).join("run-00/best.robot.json").is_file(), "{setting}");
        let toml = std::fs::read_to_string(out.join(setting).join("experiment.toml")).unwrap();
        assert!(toml.contains(&format!("name = \"{setting}\"")), "{toml}");
    }
    let analysis = dir.path().join("a");
    let an = vsrlab(&["analyze", out.to_str().unwrap(), "--out", analysis.to_str().unwrap()]);
    assert!(an.status.success(), "{}", String::from_utf8_lossy(&an.stderr));
    let csv = std::fs::read_to_string(analysis.join("summary.csv")).unwrap();
    assert!(csv.contains("grid-1.0") && csv.contains("grid-2.0"), "{csv}");
}

#[test]
fn the_graph_chapter_experiments_validate_and_resume_names_its_missing_robot() {
    let (resume, mut files): (Vec<String>, Vec<String>) = shipped_toml_files(&["experiments/ch4.1"])
        .into_iter()
        .partition(|f| f.ends_with("resume.toml"));
    let text = validated_briefly(&mut files);
    // 3 bodies × 2 operator sets, 2 × 3 modularity biases, 2 reduced, 3 reduced donors
    assert_eq!(text.matches(": ok; ").count(), 6 + 6 + 2 + 3, "{text}");
    // the resume protocol reads a run's best robot, not made yet
    assert_needs_a_best_robot(&resume[0], "genotype.initial");
}

/// The end line of `vsrlab run` picks the best of the runs' bests by the objective's sense: the
/// smallest when it is minimised (issue 56, item 3: it printed the largest).
#[test]
fn the_summary_of_a_minimised_objective_reports_the_smallest_best() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("min.toml");
    let text = EXPERIMENT
        .replace("runs = 1", "runs = 3")
        .replace(
            "duration = 3.0",
            "duration = 1.0\nfitness = [{ metric = \"distance\", sense = \"minimize\" }]",
        )
        .replace("generations = 60", "generations = 2");
    std::fs::write(&config, text).unwrap();
    let out = vsrlab(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        dir.path().join("out").to_str().unwrap(),
    ]);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{text}");
    let number = |s: &str| {
        s.split_whitespace()
            .next()
            .unwrap()
            .trim_end_matches(';')
            .parse::<f64>()
            .unwrap()
    };
    let runs: Vec<f64> = text
        .lines()
        .filter_map(|l| l.split(": best ").nth(1))
        .map(number)
        .collect();
    let best = text
        .lines()
        .find_map(|l| l.split("best fitness ").nth(1))
        .map(number)
        .unwrap();
    assert_eq!(runs.len(), 3, "{text}");
    let smallest = runs.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(runs.iter().any(|&r| r > smallest), "the runs differ: {runs:?}");
    assert_eq!(best, smallest, "{text}");
}
