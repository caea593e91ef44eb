//! Helpers shared by the CLI's end-to-end tests: run the `vsrlab` binary and collect its output.
#![allow(dead_code)] // each test file uses some of these helpers

use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

/// Runs `vsrlab args…`: whether it succeeded, and stdout then stderr.
pub fn vsrlab(args: &[&str]) -> (bool, String) {
    let out = Command::new(VSRLAB).args(args).output().expect("vsrlab runs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// Runs `vsrlab args…`, which must succeed; its output.
pub fn ok(args: &[&str]) -> String {
    let (success, text) = vsrlab(args);
    assert!(success, "vsrlab {args:?} failed:\n{text}");
    text
}

/// A running `vsrlab view`: the process and its stdout after the first line.
pub struct RunningViewer {
    child: std::process::Child,
    stdout: std::io::BufReader<std::process::ChildStdout>,
    /// The first line it printed (with the URL).
    pub first_line: String,
}

/// Starts `vsrlab args…` (a `view` command) in `dir` and waits for its first line.
pub fn start_viewer(args: &[&str], dir: &std::path::Path) -> RunningViewer {
    use std::io::BufRead;
    let mut child = Command::new(VSRLAB)
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("vsrlab runs");
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut first_line = String::new();
    stdout.read_line(&mut first_line).unwrap();
    RunningViewer {
        child,
        stdout,
        first_line,
    }
}

impl RunningViewer {
    /// The `127.0.0.1:PORT` of the URL it printed.
    pub fn address(&self) -> String {
        self.first_line
            .split("http://")
            .nth(1)
            .and_then(|rest| rest.split('/').next())
            .unwrap_or_else(|| panic!("no URL in {:?}", self.first_line))
            .to_string()
    }

    /// Sends Ctrl-C (SIGINT) and waits: whether it exited with status 0, and the rest of its
    /// stdout and its stderr.
    pub fn interrupt(mut self) -> (bool, String) {
        use std::io::Read;
        let pid = self.child.id().to_string();
        assert!(Command::new("kill").args(["-INT", &pid]).status().unwrap().success());
        let status = self.child.wait().unwrap();
        let mut rest = String::new();
        self.stdout.read_to_string(&mut rest).unwrap();
        if let Some(mut err) = self.child.stderr.take() {
            err.read_to_string(&mut rest).unwrap();
        }
        (status.success(), rest)
    }
}
