//! Handing a command over to vsrlab's Python package (`python -m vsrlab …`): the route to a Ray
//! cluster, which lives in Python. The interpreter is `$VSRLAB_PYTHON`, or `python3`.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The interpreter that has (or should have) vsrlab's Python package and Ray.
fn interpreter() -> String {
    std::env::var("VSRLAB_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Runs `python -m vsrlab ARGS` with this terminal, after checking in one line that the
/// interpreter has vsrlab and Ray (or saying how to install them).
pub fn hand_over(args: &[String]) -> Result<(), String> {
    let python = interpreter();
    let install = format!(
        "--ray needs Python with vsrlab's package and Ray: `pip install './python[ray]'` from the \
         repository (in a venv), then run again with VSRLAB_PYTHON=<that venv>/bin/python (now: {python})"
    );
    let check = Command::new(&python)
        .args(["-c", "import vsrlab, ray"])
        .output()
        .map_err(|e| format!("{install}; {python}: {e}"))?;
    if !check.status.success() {
        let why = String::from_utf8_lossy(&check.stderr);
        let last = why.lines().last().unwrap_or("").trim();
        return Err(format!("{install}; {python}: {last}"));
    }
    let status = Command::new(&python)
        .args(["-m", "vsrlab"])
        .args(args)
        .status()
        .map_err(|e| format!("{python}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("python -m vsrlab {} ended with {status}", args.join(" ")))
    }
}

/// A command for `python -m vsrlab` that sends evaluations to a Ray cluster.
pub struct RayRequest<'a> {
    /// `run` or `campaign`.
    pub command: &'static str,
    /// The experiment files.
    pub files: &'a [PathBuf],
    /// The output folder.
    pub out: &'a Path,
    /// The cluster's address.
    pub address: &'a str,
    /// Continue from the checkpoints.
    pub resume: bool,
    /// Local worker threads, if given.
    pub threads: Option<usize>,
    /// The 2D physics solver replacing the files', if given (`--solver`).
    pub solver: Option<&'a str>,
}

impl RayRequest<'_> {
    /// Its command line after `python -m vsrlab`.
    pub fn arguments(&self) -> Vec<String> {
        let mut args = vec![self.command.to_string()];
        args.extend(self.files.iter().map(|p| p.display().to_string()));
        args.extend([
            "--out".into(),
            self.out.display().to_string(),
            "--ray".into(),
            self.address.into(),
        ]);
        if self.resume {
            args.push("--resume".into());
        }
        if let Some(threads) = self.threads {
            args.extend(["--threads".into(), threads.to_string()]);
        }
        if let Some(solver) = self.solver {
            args.extend(["--solver".into(), solver.into()]);
        }
        args
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_request_becomes_python_s_command_line() {
        let files = [PathBuf::from("a.toml"), PathBuf::from("b.toml")];
        let request = RayRequest {
            command: "campaign",
            files: &files,
            out: Path::new("out/ab"),
            address: "10.0.0.1:6379",
            resume: true,
            threads: Some(3),
            solver: Some("sequential-impulses"),
        };
        assert_eq!(
            request.arguments().join(" "),
            "campaign a.toml b.toml --out out/ab --ray 10.0.0.1:6379 --resume --threads 3 \
             --solver sequential-impulses"
        );
        let plain = RayRequest {
            resume: false,
            threads: None,
            solver: None,
            ..request
        };
        assert_eq!(plain.arguments().len(), 7);
    }
}
