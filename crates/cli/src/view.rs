//! `vsrlab view`: the browser replay viewer on 127.0.0.1 (docs/viewer.md). The server and the
//! page are `vsrlab_render::viewer`; this file finds the replays (files, robot files simulated on
//! demand, results and labelling folders) and runs the server until Ctrl-C.

use clap::Args;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use vsrlab_analysis::run_folder::{BEST_REPLAY_FILE, BEST_ROBOT_FILE, EXPERIMENT_FILE};
use vsrlab_pipelines::LABELLING_FILE;
use vsrlab_render::replay::{Replay, ReplayOptions};
use vsrlab_render::viewer::{self, ReplaySource, Viewer, ViewerEntry};
use vsrlab_tasks::files::load_any_robot;
use vsrlab_tasks::{episode, TaskSpec, TraceLevel};

/// Suffix of replay files.
const REPLAY_SUFFIX: &str = ".replay.json";
/// How deep folders are searched for replays and robots.
const MAX_DEPTH: usize = 4;
/// Replays shown when the page opens, at most.
const MAX_SHOWN: usize = 4;

/// Arguments of `vsrlab view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Replay files (`vsrlab simulate --replay`), robot files (simulated when first shown), or
    /// folders: a `vsrlab run` output (every run's best robot, and a live monitor of its runs'
    /// curves and best so far, also while it runs), a `vsrlab label` folder (its robots
    /// with the labelling choices and "Save labels.csv"), or any folder holding replay files.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 8765)]
    pub port: u16,
}

/// The task a robot file found under `dir` is shown on: the nearest experiment's, else 30 s on
/// flat ground.
fn task_near(path: &Path) -> Result<TaskSpec, String> {
    for dir in path.ancestors().skip(1) {
        if dir.join(EXPERIMENT_FILE).is_file() {
            return vsrlab_experiment::config::load_task(dir).map_err(|e| e.to_string());
        }
    }
    crate::simulate::task_from_args("locomotion:flat", Some(30.0), None, Default::default(), None)
}

/// A replay made by simulating a robot file (checked now, simulated when first shown).
fn robot_entry(path: &Path, name: String, shown: bool) -> Result<ViewerEntry, String> {
    let robot = load_any_robot(path).map_err(|e| e.to_string())?;
    let task = task_near(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let title = format!("{} on {}", path.display(), task.kind());
    let make = move || -> Result<Vec<u8>, String> {
        let outcome = episode::run(robot.as_robot(), task.task(), 0, TraceLevel::Full).map_err(|e| e.to_string())?;
        let trace = outcome.trace.ok_or("the episode recorded no trace")?;
        let options = ReplayOptions {
            title: title.clone(),
            ..ReplayOptions::default()
        };
        Ok(Replay::from_trace(&trace, &options)
            .map_err(|e| e.to_string())?
            .to_json()
            .into_bytes())
    };
    Ok(ViewerEntry {
        name,
        source: ReplaySource::Make(Box::new(move || make().map_err(Into::into))),
        shown,
    })
}

/// Replay files, and best robots without a replay, under `dir` (sorted, `depth` levels down).
/// Only regular files whose resolved path lies inside `root` (resolved) are listed, each as
/// (its path, its resolved path, which is what is served): a symbolic link out of the folder, a
/// FIFO or a device is skipped, so the viewer serves nothing else.
fn collect(root: &Path, dir: &Path, depth: usize, found: &mut Vec<(PathBuf, PathBuf)>) -> Result<(), String> {
    let mut items: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    items.sort();
    for path in items {
        let Some(resolved) = std::fs::canonicalize(&path).ok().filter(|r| r.starts_with(root)) else {
            continue;
        };
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if resolved.is_dir() {
            if depth > 0 && resolved == path {
                collect(root, &path, depth - 1, found)?;
            }
        } else if resolved.is_file()
            && (name.ends_with(REPLAY_SUFFIX)
                || (name == BEST_ROBOT_FILE && !path.with_file_name(BEST_REPLAY_FILE).is_file()))
        {
            found.push((path, resolved));
        }
    }
    Ok(())
}

/// The name a file under a given folder is listed by: its path inside the folder, without the
/// `best.*.json` or `.replay.json` ending.
fn short_name(root: &Path, path: &Path) -> String {
    let inside = path.strip_prefix(root).unwrap_or(path).to_string_lossy().to_string();
    let trimmed = [BEST_REPLAY_FILE, BEST_ROBOT_FILE, REPLAY_SUFFIX]
        .iter()
        .find_map(|end| inside.strip_suffix(end))
        .unwrap_or(&inside)
        .trim_end_matches('/');
    match (trimmed.is_empty(), root.as_os_str().is_empty()) {
        (false, _) => trimmed.to_string(),
        (true, false) => root.display().to_string(),
        (true, true) => path.display().to_string(),
    }
}

/// The labelling data of a `vsrlab label` folder, if `dir` is one.
fn labelling_of(dir: &Path) -> Option<Vec<u8>> {
    vsrlab_tasks::files::read_bytes(&dir.join(LABELLING_FILE)).ok()
}

/// A labelling folder's replays, in page order, named by the robots' ids (the page pairs them
/// with the labelling choices by that name).
fn labelling_entries(dir: &Path, data: &[u8]) -> Result<Vec<ViewerEntry>, String> {
    let file = dir.join(LABELLING_FILE);
    let data: serde_json::Value =
        serde_json::from_slice(data).map_err(|e| format!("{}: not JSON: {e}", file.display()))?;
    let items = data["items"]
        .as_array()
        .ok_or_else(|| format!("{}: no 'items' list", file.display()))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let id = item["id"]
                .as_str()
                .ok_or_else(|| format!("{}: items[{i}] has no 'id'", file.display()))?;
            Ok(ViewerEntry {
                name: id.to_string(),
                source: ReplaySource::File(dir.join("replays").join(format!("{id}{REPLAY_SUFFIX}"))),
                shown: i < MAX_SHOWN,
            })
        })
        .collect()
}

/// The viewer's entries for the command-line paths, and the labelling data when the paths are
/// one labelling folder.
fn entries(paths: &[PathBuf]) -> Result<(Vec<ViewerEntry>, Option<Vec<u8>>), String> {
    if let [one] = paths {
        if let Some(data) = one.is_dir().then(|| labelling_of(one)).flatten() {
            return Ok((labelling_entries(one, &data)?, Some(data)));
        }
    }
    let mut out = Vec::new();
    for path in paths {
        if path.is_dir() {
            let root = std::fs::canonicalize(path).map_err(|e| format!("{}: {e}", path.display()))?;
            let mut found = Vec::new();
            collect(&root, &root, MAX_DEPTH, &mut found)?;
            // an experiment that has no best robot yet is watched by the live monitor alone
            if found.is_empty() && crate::monitor::experiment_folders(path).is_empty() {
                return Err(format!(
                    "{}: no replay files ({REPLAY_SUFFIX}) or best robots ({BEST_ROBOT_FILE}) in this folder",
                    path.display()
                ));
            }
            for (i, (file, resolved)) in found.iter().enumerate() {
                let name = match short_name(&root, file) {
                    whole if whole == root.display().to_string() => path.display().to_string(),
                    inside => inside,
                };
                out.push(entry(resolved, name, i == 0)?);
            }
        } else if path.is_file() {
            let parent = path.parent().unwrap_or(Path::new(""));
            out.push(entry(path, short_name(parent, path), true)?);
        } else {
            return Err(format!("{}: no such file or folder", path.display()));
        }
    }
    let mut names = std::collections::BTreeMap::<String, usize>::new();
    for e in &mut out {
        let seen = names.entry(e.name.clone()).or_default();
        *seen += 1;
        if *seen > 1 {
            e.name = format!("{} ({seen})", e.name);
        }
    }
    let mut shown = 0;
    for e in &mut out {
        e.shown &= shown < MAX_SHOWN;
        shown += usize::from(e.shown);
    }
    Ok((out, None))
}

/// Whether `path` holds a replay: named `*.replay.json`, or whatever its name, a JSON object
/// whose first field is `"format": "vsrlab-replay"` (as `--replay` writes them).
fn is_replay(path: &Path) -> bool {
    if path.to_string_lossy().ends_with(REPLAY_SUFFIX) {
        return true;
    }
    if !path.is_file() {
        return false; // opening a FIFO to look would block; the robot reader refuses it by name
    }
    let mut head = [0u8; 64];
    let n = std::fs::File::open(path)
        .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
        .unwrap_or(0);
    let text = String::from_utf8_lossy(&head[..n]);
    let compact: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    compact.starts_with(&format!("{{\"format\":\"{}\"", vsrlab_render::replay::FORMAT))
}

fn entry(path: &Path, name: String, shown: bool) -> Result<ViewerEntry, String> {
    if is_replay(path) {
        Ok(ViewerEntry {
            name,
            source: ReplaySource::File(path.to_path_buf()),
            shown,
        })
    } else {
        robot_entry(path, name, shown)
    }
}

/// Runs `vsrlab view`.
pub fn run(args: ViewArgs) -> Result<(), String> {
    let (entries, labelling) = entries(&args.paths)?;
    let count = entries.len();
    let watched: Vec<PathBuf> = args
        .paths
        .iter()
        .filter(|p| p.is_dir())
        .flat_map(|p| crate::monitor::experiment_folders(p))
        .collect();
    let monitor = match watched.is_empty() {
        true => None,
        false => Some(crate::monitor::Monitor::new(&watched)?),
    };
    let listener = viewer::bind(args.port).map_err(|e| {
        if e.kind() == std::io::ErrorKind::AddrInUse {
            format!(
                "--port: port {} on 127.0.0.1 is in use; pass another, or --port 0 for any free one",
                args.port
            )
        } else {
            format!("--port: cannot listen on 127.0.0.1:{}: {e}", args.port)
        }
    })?;
    let address = listener.local_addr().map_err(|e| e.to_string())?;
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst)).map_err(|e| e.to_string())?;
    }
    println!("vsrlab viewer: http://{address}/ ({count} replays; Ctrl-C stops it)");
    use std::io::Write as _;
    let _ = std::io::stdout().flush();
    let mut viewer = Viewer::new(entries);
    if let Some(monitor) = monitor {
        println!(
            "live monitor: {} experiment(s); the page shows each run's curves and best so far, refreshed as generations land",
            watched.len()
        );
        viewer = viewer.with_live(Box::new(monitor));
    }
    if let Some(data) = labelling {
        println!("labelling: pick a morphology and a behaviour beside each robot, then \"Save labels.csv\" into the labelling folder");
        viewer = viewer.with_labelling(data);
    }
    viewer::serve(listener, Arc::new(viewer), &stop).map_err(|e| e.to_string())?;
    println!("viewer stopped");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn listed_names_drop_the_folder_and_the_file_ending() {
        let name = |root: &str, path: &str| short_name(Path::new(root), Path::new(path));
        assert_eq!(name("out", "out/run-03/best.replay.json"), "run-03");
        assert_eq!(name("out", "out/ch3/run-00/best.robot.json"), "ch3/run-00");
        assert_eq!(name("/tmp/x", "/tmp/x/walk.replay.json"), "walk");
        assert_eq!(name("out/run-00", "out/run-00/best.replay.json"), "out/run-00");
        assert_eq!(name("", "best.replay.json"), "best.replay.json");
        assert_eq!(name("examples", "examples/biped.robot.json"), "biped.robot.json");
    }

    #[test]
    fn a_replay_is_known_by_its_content_whatever_its_name() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, text: &str| {
            let path = dir.path().join(name);
            std::fs::write(&path, text).unwrap();
            path
        };
        assert!(is_replay(&write(
            "r.json",
            "{\"format\":\"vsrlab-replay\",\"version\":1}"
        )));
        assert!(is_replay(&write("r2.json", "{\n  \"format\": \"vsrlab-replay\"}")));
        assert!(is_replay(&write("x.replay.json", "{}")));
        assert!(!is_replay(&write(
            "robot.json",
            "{\"version\":1,\"body\":\"vsrlab-replay\"}"
        )));
        assert!(!is_replay(&dir.path().join("missing.json")));
    }

    #[cfg(unix)]
    #[test]
    fn links_out_of_the_folder_fifos_and_devices_are_not_listed() {
        let outside = tempfile::tempdir().unwrap();
        let secret = outside.path().join("secret.replay.json");
        std::fs::write(&secret, "{}").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let inside = dir.path().join("walk.replay.json");
        std::fs::write(&inside, "{}").unwrap();
        let link = |target: &Path, name: &str| std::os::unix::fs::symlink(target, dir.path().join(name)).unwrap();
        link(&secret, "leak.replay.json");
        link(Path::new("/etc/passwd"), "passwd.replay.json");
        link(Path::new("/dev/zero"), "zero.replay.json");
        link(outside.path(), "elsewhere");
        link(&inside, "alias.replay.json");
        let fifo = dir.path().join("hang.replay.json");
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let (listed, _) = entries(&[dir.path().to_path_buf()]).unwrap();
        let names: Vec<&str> = listed.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(
            names,
            ["alias", "walk"],
            "a link inside the folder is served as its target"
        );
        for e in &listed {
            match &e.source {
                ReplaySource::File(path) => assert_eq!(path, &std::fs::canonicalize(&inside).unwrap()),
                ReplaySource::Make(_) => panic!("{} is not a replay file", e.name),
            }
        }
    }
}
