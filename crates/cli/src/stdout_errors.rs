//! What happens when standard output goes away: `vsrlab … | head -c 10` closes the pipe, and
//! `> /dev/full` fails every write. Rust's `println!` panics then (exit 101 and a backtrace); this
//! hook turns that panic into what a command-line tool is expected to do: end quietly with
//! status 0 on a closed pipe (as ripgrep does), or say that the output could not be written and
//! end with status 1.

/// How the `println!` of the standard library words a failed write.
const FAILED_PRINT: &str = "failed printing to stdout";

/// What to do about a panic with this message: `Some(status)` to exit with, after printing the
/// returned line (if any) on standard error; `None` for a panic that is not a failed print.
pub fn outcome(message: &str) -> Option<(i32, Option<String>)> {
    let cause = message.strip_prefix(FAILED_PRINT)?.trim_start_matches(':').trim();
    if cause.contains("Broken pipe") || cause.contains("os error 32") {
        return Some((0, None));
    }
    Some((1, Some(format!("error: cannot write to standard output: {cause}"))))
}

/// Installs the hook; other panics keep the default report.
pub fn install() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        match outcome(message) {
            Some((status, line)) => {
                if let Some(line) = line {
                    eprintln!("{line}");
                }
                std::process::exit(status);
            }
            None => default(info),
        }
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closed_pipe_ends_quietly_and_a_full_disk_says_so() {
        assert_eq!(
            outcome("failed printing to stdout: Broken pipe (os error 32)"),
            Some((0, None))
        );
        let (status, line) = outcome("failed printing to stdout: No space left on device (os error 28)").unwrap();
        assert_eq!(status, 1);
        assert!(line.unwrap().contains("No space left on device"));
        assert_eq!(outcome("index out of bounds"), None);
    }
}
