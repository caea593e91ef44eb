//! The README's commands, run as written (parsed from README.md so they cannot drift): every
//! `vsrlab …` line and the quick start's `cargo run … --` line, in order, in a scratch folder
//! holding the repository's `examples/` and `experiments/quickstart.toml`. Only the quickstart's
//! evaluation budget is cut (8 000 → 80) to keep the suite short; the commands themselves are
//! untouched, so the run → replay pair is checked verbatim. `vsrlab view`, a server, is started,
//! must print its URL, and is stopped with Ctrl-C (SIGINT), which must end it with status 0.

use crate::common;

use std::path::Path;
use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");
/// How the quick start calls the binary before it is installed.
const CARGO_PREFIX: &str = "cargo run --release -p vsrlab-cli -- ";

/// Splits a shell command line into words: spaces separate, double quotes group.
fn words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut quoted = false;
    let mut started = false;
    for c in line.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                started = true;
            }
            ' ' if !quoted => {
                if started {
                    words.push(std::mem::take(&mut word));
                    started = false;
                }
            }
            c => {
                word.push(c);
                started = true;
            }
        }
    }
    if started {
        words.push(word);
    }
    words
}

/// The arguments of every vsrlab command in the README's `sh` blocks, in order (comments
/// after two or more spaces and a `#` dropped).
fn readme_commands(readme: &str) -> Vec<Vec<String>> {
    let mut commands = Vec::new();
    let mut in_sh = false;
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = line.trim() == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let code = line.split("  #").next().unwrap_or("").trim();
        let rest = code.strip_prefix(CARGO_PREFIX).or_else(|| code.strip_prefix("vsrlab "));
        if let Some(rest) = rest {
            commands.push(words(rest));
        }
    }
    commands
}

/// Starts a `vsrlab view` command, waits for its URL, stops it with SIGINT.
fn run_viewer(args: &[String], work: &Path) {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let viewer = common::start_viewer(&args, work);
    let line = viewer.first_line.clone();
    let (stopped, rest) = viewer.interrupt();
    assert!(
        stopped && line.contains("http://127.0.0.1:"),
        "vsrlab {} failed: {line}{rest}",
        args.join(" ")
    );
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

#[test]
fn the_readme_commands_run_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let commands = readme_commands(&readme);
    assert!(commands.len() >= 8, "{commands:?}");
    assert_eq!(commands[0][..2], ["simulate", "--robot"], "the first command");

    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path();
    copy_dir(&root.join("examples"), &work.join("examples"));
    let quickstart = std::fs::read_to_string(root.join("experiments/quickstart.toml")).unwrap();
    let short = quickstart.replace("evaluations = 8000", "evaluations = 80");
    assert_ne!(
        short, quickstart,
        "the quickstart's budget line changed: update this test"
    );
    std::fs::create_dir_all(work.join("experiments")).unwrap();
    std::fs::write(work.join("experiments/quickstart.toml"), short).unwrap();
    let ffmpeg = Command::new("ffmpeg").arg("-version").output().is_ok();

    for args in &commands {
        if args.iter().any(|a| a.ends_with(".mp4")) && !ffmpeg {
            eprintln!("skipped (no ffmpeg): vsrlab {}", args.join(" "));
            continue;
        }
        if args[0] == "view" {
            run_viewer(args, work);
            continue;
        }
        let args = &shortened(args);
        let out = Command::new(VSRLAB).args(args).current_dir(work).output().unwrap();
        assert!(
            out.status.success(),
            "vsrlab {} failed:\n{}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
        // every video a command asks for is written
        if let Some(i) = args.iter().position(|a| a == "--video") {
            let video = work.join(&args[i + 1]);
            assert!(video.metadata().is_ok_and(|m| m.len() > 0), "{}", video.display());
        }
    }
    assert!(work.join("biped.gif").is_file() && work.join("walk.gif").is_file());
    assert!(commands.iter().any(|c| c[0] == "view"), "the README shows the viewer");
}

/// `vsrlab bench` as written spends two CPU seconds on each of its rows (over a minute in all):
/// the test runs the same command with 0.2 s episodes and one episode per row.
fn shortened(args: &[String]) -> Vec<String> {
    let mut args = args.to_vec();
    if args == ["bench"] {
        args.extend(["--duration", "0.2", "--min-seconds", "0"].map(String::from));
    }
    args
}

#[test]
fn words_split_like_a_shell() {
    assert_eq!(
        words(r####"simulate --body "###/#.#/#.#"  --duration 5"####),
        ["simulate", "--body", "###/#.#/#.#", "--duration", "5"]
    );
    let readme = "```sh\n# a comment\nvsrlab bench   # speed\ncargo test\n```\nvsrlab not-code\n";
    assert_eq!(readme_commands(readme), vec![vec!["bench".to_string()]]);
}
