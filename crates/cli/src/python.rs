//! Handing a command over to vsrlab's Python package (`python -m vsrlab …`): the route to a Ray
//! cluster, which lives in Python. The interpreter is `$VSRLAB_PYTHON`, or `python3`.

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
