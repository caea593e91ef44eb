//! Helpers shared by the runner's integration tests.

use std::path::Path;

/// The deterministic files of a finished experiment (all but `timings.csv` and the
/// `summary.json` files, which hold wall-clock figures), as (relative path, content).
pub fn deterministic_files(out: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let mut stack = vec![out.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if name == "timings.csv" || name == "summary.json" {
                continue;
            }
            let rel = path.strip_prefix(out).unwrap().display().to_string();
            files.push((rel, std::fs::read_to_string(&path).unwrap()));
        }
    }
    files.sort();
    files
}
