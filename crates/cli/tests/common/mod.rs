//! Helpers shared by the CLI's end-to-end tests: run the `vsrlab` binary and collect its output.

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
