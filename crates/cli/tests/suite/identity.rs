//! The identity harness (bench/identity) on this build, in its reduced set (`check.sh --quick`:
//! every simulate case and the experiment lines marked `quick`, about 30 s in the test profile):
//! every case's result must equal bench/identity/reference.txt bit for bit, so a change that
//! alters a result fails here unless it updates the references and CHANGELOG.md together
//! (docs/architecture.md, "Rules").

use std::path::Path;
use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

#[test]
fn every_identity_case_gives_the_reference_bits() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = Command::new("bash")
        .arg(root.join("bench/identity/check.sh"))
        .arg("--quick")
        .arg(VSRLAB)
        .output()
        .expect("bash runs bench/identity/check.sh");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{text}");
    // the harness ran its cases (a missing case list would pass on nothing)
    let cases: usize = text
        .lines()
        .filter(|line| line.contains(" cases identical"))
        .find_map(|line| line.strip_prefix("identity: ")?.split(' ').next()?.parse().ok())
        .unwrap_or(0);
    assert!(cases >= 60, "{text}");
}
