//! Malformed inputs thrown at the binary: generated experiment files, robot files (vsrlab's and
//! EvoGym's world-file format), command-line
//! values, PSA bodies, sweeps, files read by `transfer.from` and `genotype.initial`, and requests
//! to the viewer (seeded, so every run of the suite throws the same ones). For each: no panic, no abort,
//! no timeout; a failure exits non-zero and names the field (or the line) it is about; nothing is
//! written outside the case's own folder.

use rand::seq::IndexedRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

/// A small valid experiment (a few evaluations of 0.2 s episodes), one setting per line.
const EXPERIMENT: &str = r####"name = "fuzz"
runs = 1
seed = 3

[representation]
body = "###/#.#"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }
preset = "2021"

[task]
kind = "locomotion"
terrain = "flat"
duration = 0.2
fitness = "velocity"

[optimizer]
kind = "ga"
population_size = 2
offspring_size = 2
tournament_size = 2

[stop]
evaluations = 4
wall_seconds = 5

[output]
snapshot_every = 2
checkpoint_interval = 0
save_best = true
"####;

/// Values that are wrong for most fields (and right for a few: the case then must succeed).
const BAD_VALUES: &[&str] = &[
    "-1",
    "0",
    "-0.0",
    "1e12",
    "1000000000000",
    "18446744073709551616",
    "nan",
    "inf",
    "-inf",
    "1.5",
    "true",
    "\"\"",
    "\"x\"",
    "\"../../escaped\"",
    "\"a/b\"",
    "\"🤖\"",
    "[]",
    "[1000000000]",
    "[-1]",
    "{}",
    "{ kind = \"nosuch\" }",
    "\"hilly-1e9-10\"",
    "\"mlp:100000000\"",
    "\"distributed-mlp:1000000000\"",
];

/// What one case did.
#[derive(Debug)]
struct Case {
    what: String,
    code: Option<i32>,
    stderr: String,
    timed_out: bool,
}

/// Runs the binary with a deadline.
fn run(args: &[&str], cwd: &Path) -> (Option<i32>, String, bool) {
    let mut child = Command::new(VSRLAB)
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vsrlab starts");
    let start = Instant::now();
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = std::io::Read::read_to_string(&mut stderr, &mut text);
        text
    });
    let timed_out = loop {
        if child.try_wait().unwrap().is_some() {
            break false;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            break true;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let status = child.wait().unwrap();
    (status.code(), reader.join().unwrap(), timed_out)
}

/// The outcome counts, and the list of cases that broke a rule.
#[derive(Default)]
struct Tally {
    cases: usize,
    by_code: BTreeMap<String, usize>,
    broken: Vec<String>,
}

impl Tally {
    /// Checks one case: `names` are the words one of which the error must contain.
    fn check(&mut self, case: &Case, names: &[&str]) {
        self.cases += 1;
        let code = case.code.map_or("signal".to_string(), |c| c.to_string());
        *self.by_code.entry(code).or_default() += 1;
        let mut problem = None;
        if case.timed_out {
            problem = Some("timed out".to_string());
        } else if case.stderr.contains("panicked") || case.stderr.contains("RUST_BACKTRACE") {
            problem = Some("panicked".to_string());
        } else if !matches!(case.code, Some(0..=2)) {
            problem = Some(format!("exit {:?}", case.code));
        } else if case.code != Some(0) && !names.iter().any(|n| case.stderr.contains(n)) {
            problem = Some(format!("error names none of {names:?}"));
        }
        if case.code == Some(0) && std::env::var_os("VSRLAB_FUZZ_LIST").is_some() {
            eprintln!("accepted: {}", case.what);
        }
        if let Some(p) = problem {
            self.broken.push(format!("{}: {p}\n{}", case.what, case.stderr.trim()));
        }
    }
}

/// Everything directly inside `dir`, by name.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A fresh case folder under `root/cases`; checks afterwards that nothing appeared elsewhere.
struct Sandbox {
    root: PathBuf,
    next: usize,
}

impl Sandbox {
    fn case(&mut self) -> PathBuf {
        self.next += 1;
        let dir = self.root.join("cases").join(format!("{:04}", self.next));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Nothing outside the case folders: the root holds only `cases`, `cases` only case folders.
    fn outside_writes(&self) -> Vec<String> {
        let mut found = Vec::new();
        for name in entries(&self.root) {
            if name != "cases" {
                found.push(name);
            }
        }
        for name in entries(&self.root.join("cases")) {
            if name.len() != 4 || !name.chars().all(|c| c.is_ascii_digit()) {
                found.push(format!("cases/{name}"));
            }
        }
        found
    }
}

/// `key = value` lines of the experiment: (line index, key).
fn setting_lines() -> Vec<(usize, String)> {
    EXPERIMENT
        .lines()
        .enumerate()
        .filter_map(|(i, line)| line.split_once(" = ").map(|(k, _)| (i, k.trim().to_string())))
        .collect()
}

/// One malformed experiment file and the names its error may give.
fn malformed_experiment(rng: &mut ChaCha8Rng) -> (String, Vec<u8>, Vec<String>) {
    let lines: Vec<&str> = EXPERIMENT.lines().collect();
    let settings = setting_lines();
    let join = |lines: &[String]| (lines.join("\n") + "\n").into_bytes();
    let mut owned: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    match rng.random_range(0..10) {
        // a bad value for a top-level key (most cases)
        0..=4 => {
            let (i, key) = settings.choose(rng).unwrap().clone();
            let value = BAD_VALUES.choose(rng).unwrap();
            owned[i] = format!("{key} = {value}");
            (format!("{key} = {value}"), join(&owned), vec![key])
        }
        // a bad value inside the brain table
        5 => {
            let key = ["kind", "layout", "signals", "hidden"].choose(rng).unwrap();
            let value = BAD_VALUES.choose(rng).unwrap();
            let mut brain: BTreeMap<&str, String> = [
                ("kind", "\"distributed-mlp\"".to_string()),
                ("layout", "\"homogeneous\"".to_string()),
                ("signals", "1".to_string()),
                ("hidden", "[]".to_string()),
            ]
            .into();
            brain.insert(key, value.to_string());
            let inner: Vec<String> = brain.iter().map(|(k, v)| format!("{k} = {v}")).collect();
            let i = lines.iter().position(|l| l.starts_with("brain")).unwrap();
            owned[i] = format!("brain = {{ {} }}", inner.join(", "));
            (format!("brain.{key} = {value}"), join(&owned), vec![key.to_string()])
        }
        // a setting removed
        6 => {
            let (i, key) = settings.choose(rng).unwrap().clone();
            owned.remove(i);
            (format!("without {key}"), join(&owned), vec![key])
        }
        // an unknown setting
        7 => {
            let (i, _) = settings.choose(rng).unwrap().clone();
            let key = format!("unknown_{}", rng.random_range(0..1000));
            owned.insert(i + 1, format!("{key} = 1"));
            (format!("extra {key}"), join(&owned), vec![key])
        }
        // the file cut short
        8 => {
            let cut = rng.random_range(0..EXPERIMENT.len());
            let bytes = EXPERIMENT.as_bytes()[..cut].to_vec();
            (
                format!("cut at byte {cut}"),
                bytes,
                vec!["line".into(), "missing".into()],
            )
        }
        // random bytes inserted
        _ => {
            let at = rng.random_range(0..EXPERIMENT.len());
            let mut bytes = EXPERIMENT.as_bytes().to_vec();
            let junk: Vec<u8> = (0..rng.random_range(1..8)).map(|_| rng.random()).collect();
            bytes.splice(at..at, junk.iter().copied());
            (
                format!("junk {junk:?} at byte {at}"),
                bytes,
                vec!["line".into(), "UTF-8".into(), "utf-8".into()],
            )
        }
    }
}

/// Every path to a value of a JSON document (`["robot", "brain", "weights", "3"]`).
fn json_paths(value: &serde_json::Value, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    out.push(prefix.clone());
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                prefix.push(k.clone());
                json_paths(v, prefix, out);
                prefix.pop();
            }
        }
        serde_json::Value::Array(items) => {
            for (i, v) in items.iter().enumerate().take(3) {
                prefix.push(i.to_string());
                json_paths(v, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn at_path<'a>(value: &'a mut serde_json::Value, path: &[String]) -> &'a mut serde_json::Value {
    path.iter().fold(value, |v, p| match v {
        serde_json::Value::Array(items) => &mut items[p.parse::<usize>().unwrap()],
        other => &mut other[p.as_str()],
    })
}

/// One malformed robot file and the names its error may give.
fn malformed_robot(rng: &mut ChaCha8Rng, robot: &serde_json::Value) -> (String, Vec<u8>, Vec<String>) {
    let mut paths = Vec::new();
    json_paths(robot, &mut Vec::new(), &mut paths);
    paths.retain(|p| !p.is_empty() && p.last().is_some_and(|k| k != "note"));
    let path = paths.choose(rng).unwrap().clone();
    // the innermost key (an array index names its array)
    let key = path
        .iter()
        .rev()
        .find(|p| p.parse::<usize>().is_err())
        .cloned()
        .unwrap_or_default();
    let mut doc = robot.clone();
    let text = match rng.random_range(0..6) {
        0..=2 => {
            let bad = [
                serde_json::json!(-1),
                serde_json::json!(1e300),
                serde_json::json!("x"),
                serde_json::json!(""),
                serde_json::json!(null),
                serde_json::json!([]),
                serde_json::json!({}),
                serde_json::json!(true),
                serde_json::json!(["#".repeat(2000)]),
                serde_json::json!(1_000_000_000_000u64),
            ];
            let value = bad.choose(rng).unwrap().clone();
            *at_path(&mut doc, &path) = value.clone();
            return (
                format!("{} = {value}", path.join(".")),
                serde_json::to_vec_pretty(&doc).unwrap(),
                vec![key, "line".into()],
            );
        }
        3 => {
            let (last, parent) = path.split_last().unwrap();
            if let serde_json::Value::Object(map) = at_path(&mut doc, parent) {
                map.remove(last);
            } else if let serde_json::Value::Array(items) = at_path(&mut doc, parent) {
                items.remove(last.parse::<usize>().unwrap());
            }
            return (
                format!("without {}", path.join(".")),
                serde_json::to_vec_pretty(&doc).unwrap(),
                vec![key, "line".into(), "expected".into()],
            );
        }
        4 => serde_json::to_string_pretty(&doc).unwrap(),
        _ => {
            let text = serde_json::to_string_pretty(&doc).unwrap();
            let mut bytes = text.into_bytes();
            let at = rng.random_range(0..bytes.len());
            bytes.insert(at, rng.random());
            return (
                format!("junk at byte {at}"),
                bytes,
                vec!["line".into(), key, "UTF-8".into(), "utf-8".into()],
            );
        }
    };
    let cut = rng.random_range(0..text.len());
    let cut = (0..=cut).rev().find(|&c| text.is_char_boundary(c)).unwrap();
    (
        format!("cut at byte {cut}"),
        text.as_bytes()[..cut].to_vec(),
        vec!["line".into(), "EOF".into()],
    )
}

/// A valid robot in EvoGym's own file format (a world file of one object): 2 × 2 horizontal
/// actuators, every pair of neighbours connected.
const EVOGYM_ROBOT: &str = r#"{"grid_width": 2, "grid_height": 2, "objects": {"robot": {
    "indices": [0, 1, 2, 3], "types": [3, 3, 3, 3],
    "neighbors": {"0": [1, 2], "1": [0, 3], "2": [0, 3], "3": [1, 2]}}}}"#;

/// One malformed EvoGym world file (a robot file in EvoGym's format is one) and the names its
/// error may give: the world file's own faults (unknown types, bad neighbours, repeated or
/// overlapping cells, missing parts), or any of [`malformed_robot`]'s.
fn malformed_evogym_file(rng: &mut ChaCha8Rng) -> (String, Vec<u8>, Vec<String>) {
    let mut doc: serde_json::Value = serde_json::from_str(EVOGYM_ROBOT).unwrap();
    let names = |list: &[&str]| list.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let (what, names) = match rng.random_range(0..8) {
        0 => {
            let (k, code) = (rng.random_range(0..4), *[0, 6, 7, 255].choose(rng).unwrap());
            doc["objects"]["robot"]["types"][k] = code.into();
            (format!("types[{k}] = {code}"), names(&["types"]))
        }
        1 => {
            // a neighbour that is not next to the cell (3 is diagonal to 0), or not in the object
            let (cell, neighbour) = *[("0", 3), ("1", 2), ("2", 9), ("3", 0)].choose(rng).unwrap();
            doc["objects"]["robot"]["neighbors"][cell] = serde_json::json!([neighbour]);
            (format!("neighbors.{cell} = [{neighbour}]"), names(&["neighbors"]))
        }
        2 => {
            doc["objects"]["robot"]["indices"][3] = 1.into();
            ("a cell listed twice".into(), names(&["indices"]))
        }
        3 => {
            let other = serde_json::json!({"indices": [1], "types": [5], "neighbors": {"1": []}});
            doc["objects"]["peg"] = other;
            (
                "a second object on the robot's cell".into(),
                names(&["overlap", "objects"]),
            )
        }
        4 => {
            let part = *["objects", "grid_width", "grid_height"].choose(rng).unwrap();
            doc.as_object_mut().unwrap().remove(part);
            (format!("without {part}"), names(&[part, "format"]))
        }
        5 => {
            let part = *["indices", "types", "neighbors"].choose(rng).unwrap();
            doc["objects"]["robot"].as_object_mut().unwrap().remove(part);
            (format!("without objects.robot.{part}"), names(&[part]))
        }
        _ => return malformed_robot(rng, &doc),
    };
    (what, serde_json::to_vec_pretty(&doc).unwrap(), names)
}

/// A random string of printable and odd characters.
fn random_text(rng: &mut ChaCha8Rng) -> String {
    const CHARS: &[char] = &[
        'a', 'z', '0', '9', '-', ':', ',', '.', '/', '#', ' ', 'e', 'é', '🤖', '\u{7f}', '%', '+', '*',
    ];
    (0..rng.random_range(0..12))
        .map(|_| *CHARS.choose(rng).unwrap())
        .collect()
}

/// One malformed command line: the arguments and the option it is about.
fn malformed_command(rng: &mut ChaCha8Rng, results: &Path) -> (Vec<String>, Vec<String>) {
    let value = if rng.random_bool(0.5) {
        BAD_VALUES.choose(rng).unwrap().trim_matches('"').to_string()
    } else {
        random_text(rng)
    };
    let simulate = |option: &str, value: String| {
        let mut args: Vec<String> = ["simulate", "--duration", "0.1"].map(String::from).to_vec();
        if option == "--duration" {
            args.truncate(1);
        }
        args.push(format!("{option}={value}"));
        args
    };
    let option = *[
        "--body",
        "--brain",
        "--task",
        "--sensors",
        "--duration",
        "--transient",
        "--preset",
        "--substeps",
        "--solver",
        "--robot",
        "run --threads",
        "run --max-memory-gib",
        "bench --robots",
        "bench --min-seconds",
        "bench --threads",
        "bench --solver",
        "label --bins",
    ]
    .choose(rng)
    .unwrap();
    let args = match option.split_once(' ') {
        None => simulate(option, value.clone()),
        Some(("run", flag)) => vec!["run".into(), "exp.toml".into(), format!("{flag}={value}")],
        Some(("bench", flag)) => {
            let mut args: Vec<String> = ["bench", "--min-seconds", "0.01", "--robots", "biped-4x3"]
                .map(String::from)
                .to_vec();
            let at = args.iter().position(|a| a == flag).map_or(args.len(), |i| i);
            if at < args.len() {
                args.drain(at..at + 2);
            }
            args.push(format!("{flag}={value}"));
            args
        }
        Some((command, flag)) => vec![command.into(), results.display().to_string(), format!("{flag}={value}")],
    };
    let flag = option.rsplit(' ').next().unwrap().to_string();
    let mut names = vec![flag.clone(), flag.trim_start_matches('-').to_string()];
    if !value.is_empty() {
        names.push(value);
    }
    (args, names)
}

/// The PSA constants a `[representation] body` table may set.
const PSA_KEYS: &[&str] = &[
    "masses",
    "radius",
    "mass_side",
    "density",
    "friction",
    "spring_frequency",
    "spring_damping",
    "min_length",
    "max_length",
    "gas_mass",
    "molar_mass",
    "temperature",
    "gas_constant",
    "max_pressure_factor",
    "min_pressure_fraction",
    "sensor_window",
    "position_scale",
    "displacement_scale",
    "spring_control",
    "pressure_control",
    "gas_amount",
    "pressure_length",
];

/// Extreme numbers, besides [`BAD_VALUES`], for physical constants.
const EXTREMES: &[&str] = &[
    "1e300",
    "1e-300",
    "1e150",
    "1e7",
    "1e-7",
    "5e-324",
    "1.7976931348623157e308",
    "3",
    "1000",
    "0.5",
];

/// One PSA experiment with a constant set to a bad or extreme value: (what, file, names).
fn malformed_psa(rng: &mut ChaCha8Rng) -> (String, String, Vec<String>) {
    let key = *PSA_KEYS.choose(rng).unwrap();
    let value = if rng.random_bool(0.5) {
        BAD_VALUES.choose(rng).unwrap()
    } else {
        EXTREMES.choose(rng).unwrap()
    };
    let text = format!(
        "name = \"fuzz-psa\"\nruns = 1\nseed = 3\n[representation]\n\
         body = {{ kind = \"psa\", size = \"small\", {key} = {value} }}\n\
         brain = {{ kind = \"heads\", linear_outputs = 1 }}\n\
         [task]\nkind = \"locomotion\"\nterrain = \"flat\"\nduration = 0.2\n\
         [optimizer]\nkind = \"cma-es\"\npopulation_size = 2\n[stop]\nevaluations = 2\n"
    );
    (format!("psa {key} = {value}"), text, vec![key.to_string()])
}

/// One sweep over a setting, with colliding, bad or unknown values: (what, file, names).
fn malformed_sweep(rng: &mut ChaCha8Rng) -> (String, String, Vec<String>) {
    let key = *[
        "seed",
        "runs",
        "name",
        "task.duration",
        "task.terrain",
        "optimizer.population_size",
        "representation.body",
        "stop.evaluations",
        "nosuch.key",
        "task",
        "",
    ]
    .choose(rng)
    .unwrap();
    let a = BAD_VALUES.choose(rng).unwrap();
    let values = match rng.random_range(0..4) {
        0 => format!("[{a}, {a}]"),
        1 => format!("[{a}, {}]", BAD_VALUES.choose(rng).unwrap()),
        2 => (*a).to_string(),
        _ => "[]".to_string(),
    };
    let text = format!("{EXPERIMENT}\n[sweep]\n\"{key}\" = {values}\n");
    let mut names = vec!["sweep".to_string(), "line".to_string()];
    names.extend(key.rsplit('.').next().map(str::to_string));
    (format!("sweep \"{key}\" = {values}"), text, names)
}

/// Files a `transfer.from` or `genotype.initial` may name: (what, path relative to the case
/// folder, after making it there).
fn odd_file(rng: &mut ChaCha8Rng, dir: &Path, robot: &serde_json::Value) -> (String, String) {
    match rng.random_range(0..7) {
        0 => ("/dev/zero".into(), "/dev/zero".into()),
        1 => {
            let made = Command::new("mkfifo").arg(dir.join("fifo.json")).status();
            assert!(made.is_ok_and(|s| s.success()), "mkfifo");
            ("a FIFO".into(), "fifo.json".into())
        }
        2 => ("a folder".into(), ".".into()),
        3 => ("a missing file".into(), "missing.json".into()),
        4 => {
            let (what, bytes, _) = malformed_robot(rng, robot);
            std::fs::write(dir.join("bad.json"), bytes).unwrap();
            (format!("a robot file: {what}"), "bad.json".into())
        }
        5 => {
            std::fs::write(dir.join("empty.json"), b"").unwrap();
            ("an empty file".into(), "empty.json".into())
        }
        _ => {
            std::fs::write(dir.join("good.json"), serde_json::to_vec(robot).unwrap()).unwrap();
            ("a robot file of another brain".into(), "good.json".into())
        }
    }
}

/// One experiment that reads a file when it is read: a `[transfer]` or a graph genotype's
/// `initial`, naming an odd file: (what, file, names).
fn file_reading_experiment(
    rng: &mut ChaCha8Rng,
    dir: &Path,
    robot: &serde_json::Value,
) -> (String, String, Vec<String>) {
    let (what, path) = odd_file(rng, dir, robot);
    if rng.random_bool(0.5) {
        let text = format!("{EXPERIMENT}\n[transfer]\nfrom = \"{path}\"\n");
        (format!("transfer.from = {what}"), text, vec!["transfer".into()])
    } else {
        let text = EXPERIMENT.replace(
            "brain = { kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [] }",
            "brain = { kind = \"graph\" }",
        ) + &format!("\n[genotype]\nkind = \"graph\"\ninitial = \"{path}\"\n");
        (
            format!("genotype.initial = {what}"),
            text,
            vec!["genotype.initial".into()],
        )
    }
}

/// What the viewer answered to one request: its status code, `None` when it closed the
/// connection without one (a request it could not read), or `Err` for a hung connection.
fn viewer_request(address: &str, request: &[u8]) -> Result<(Option<u16>, Vec<u8>), String> {
    use std::io::{Read, Write};
    let mut stream = std::net::TcpStream::connect(address).map_err(|e| e.to_string())?;
    stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let _ = stream.write_all(request);
    let _ = stream.shutdown(std::net::Shutdown::Write);
    let mut answer = Vec::new();
    if let Err(e) = stream.read_to_end(&mut answer) {
        if e.kind() == std::io::ErrorKind::WouldBlock || e.kind() == std::io::ErrorKind::TimedOut {
            return Err("no answer within 20 s".into());
        }
    }
    let head = String::from_utf8_lossy(&answer[..answer.len().min(64)]).into_owned();
    let code = head
        .strip_prefix("HTTP/1.1 ")
        .and_then(|rest| rest.get(..3))
        .and_then(|c| c.parse().ok());
    Ok((code, answer))
}

/// One random request to the viewer.
fn random_request(rng: &mut ChaCha8Rng) -> (String, Vec<u8>) {
    let method = *["GET", "GET", "GET", "HEAD", "POST", "DELETE", "get", ""]
        .choose(rng)
        .unwrap();
    let path = match rng.random_range(0..12) {
        0 => "/".to_string(),
        1 => "/api/replays".to_string(),
        2 => "/api/monitor".to_string(),
        3 => format!("/replay/{}", rng.random_range(0..6)),
        4 => format!("/live/{}/{}", rng.random_range(0..3), rng.random_range(0..3)),
        5 => "/../../../../etc/passwd".to_string(),
        6 => "/%2e%2e/%2e%2e/etc/passwd".to_string(),
        7 => format!("/replay/{}", u64::MAX),
        8 => format!("/{}", "a".repeat(rng.random_range(1..20_000))),
        9 => format!("/{}", random_text(rng)),
        10 => "/live/0/0/0".to_string(),
        _ => "/viewer.js?x=../../etc/passwd".to_string(),
    };
    let host = *[
        "localhost:1",
        "127.0.0.1",
        "[::1]:80",
        "evil.example",
        "localhost.evil.example",
        "",
    ]
    .choose(rng)
    .unwrap();
    match rng.random_range(0..10) {
        0 => {
            let junk: Vec<u8> = (0..rng.random_range(0..64)).map(|_| rng.random()).collect();
            (format!("{} junk bytes", junk.len()), junk)
        }
        1 => (
            format!("{method} {path} cut short"),
            format!("{method} {path}").into_bytes(),
        ),
        _ => {
            let host_line = if host.is_empty() {
                String::new()
            } else {
                format!("Host: {host}\r\n")
            };
            (
                format!("{method} {} Host {host:?}", &path[..path.len().min(60)]),
                format!("{method} {path} HTTP/1.1\r\n{host_line}\r\n").into_bytes(),
            )
        }
    }
}

/// Throws `count` random requests at `vsrlab view` on a folder holding a replay, a run's output,
/// a FIFO named like a replay and links to a secret file outside and to `/etc/passwd`; checks
/// each answer (a known status, or a closed connection for an unreadable request, never a hang,
/// never a byte of the files outside), that the server is still serving at the end and that it
/// never panicked. Returns the tally.
fn fuzz_viewer(rng: &mut ChaCha8Rng, sandbox: &mut Sandbox, results: &Path, count: usize) -> Tally {
    let dir = sandbox.case();
    let served = dir.join("served");
    std::fs::create_dir_all(&served).unwrap();
    let secret = dir.join("secret.replay.json");
    std::fs::write(&secret, "{\"format\":\"vsrlab-replay\",\"title\":\"SECRET-OUTSIDE\"}").unwrap();
    let (code, stderr, _) = run(
        &["simulate", "--duration", "0.2", "--replay", "served/walk.replay.json"],
        &dir,
    );
    assert_eq!(code, Some(0), "{stderr}");
    std::os::unix::fs::symlink(&secret, served.join("leak.replay.json")).unwrap();
    std::os::unix::fs::symlink("/etc/passwd", served.join("passwd.replay.json")).unwrap();
    assert!(Command::new("mkfifo")
        .arg(served.join("hang.replay.json"))
        .status()
        .unwrap()
        .success());
    let mut child = Command::new(VSRLAB)
        .args(["view", "served", results.to_str().unwrap(), "--port", "0"])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    std::io::BufRead::read_line(&mut stdout, &mut first).unwrap();
    let address = first
        .split("http://")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .unwrap_or_else(|| panic!("no URL: {first}"))
        .to_string();
    let mut tally = Tally::default();
    let mut statuses = BTreeMap::<String, usize>::new();
    for _ in 0..count {
        let (what, request) = random_request(rng);
        let (code, stderr, timed_out) = match viewer_request(&address, &request) {
            Ok((code, answer)) => {
                *statuses
                    .entry(code.map_or("closed".into(), |c| c.to_string()))
                    .or_default() += 1;
                let text = String::from_utf8_lossy(&answer);
                let leaked = text.contains("SECRET-OUTSIDE") || text.contains("root:");
                let known = matches!(code, None | Some(200 | 403 | 404 | 405 | 500));
                // a status the server may give: 0 for the right answers, 1 otherwise
                let verdict = if leaked || !known { 1 } else { 0 };
                (
                    Some(verdict),
                    format!("status {code:?}{}", if leaked { ", served a file outside" } else { "" }),
                    false,
                )
            }
            Err(e) => (None, e, true),
        };
        tally.check(
            &Case {
                what: format!("viewer: {what}"),
                code,
                stderr,
                timed_out,
            },
            &["status"],
        );
    }
    let (still, answer) = viewer_request(&address, b"GET / HTTP/1.1\r\nHost: localhost\r\n\r\n").unwrap();
    let _ = child.kill();
    let mut err = String::new();
    let _ = std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err);
    let _ = child.wait();
    eprintln!("viewer requests: HTTP statuses {statuses:?}");
    assert_eq!(still, Some(200), "still serving: {}", String::from_utf8_lossy(&answer));
    assert!(!err.contains("panicked"), "{err}");
    tally
}

/// Runs `vsrlab args…` in `dir` and checks the case under `kind`: `names` are the words one of
/// which its error must contain.
fn throw<'a>(
    tallies: &mut BTreeMap<&'a str, Tally>,
    kind: &'a str,
    dir: &Path,
    args: &[&str],
    what: String,
    names: &[String],
) {
    let (code, stderr, timed_out) = run(args, dir);
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let case = Case {
        what,
        code,
        stderr,
        timed_out,
    };
    tallies.entry(kind).or_default().check(&case, &names);
}

#[test]
fn malformed_inputs_never_crash_and_always_name_the_field() {
    let tmp = tempfile::tempdir().unwrap();
    let mut sandbox = Sandbox {
        root: tmp.path().to_path_buf(),
        next: 0,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(20);
    let mut tallies: BTreeMap<&str, Tally> = BTreeMap::new();

    // The base files must be valid, or every case below fails for the wrong reason.
    let base = sandbox.case();
    std::fs::write(base.join("exp.toml"), EXPERIMENT).unwrap();
    let (code, stderr, _) = run(&["run", "exp.toml"], &base);
    assert_eq!(code, Some(0), "{stderr}");
    let robot_text = std::fs::read_to_string(base.join("out/fuzz/run-00/best.robot.json")).unwrap();
    let robot: serde_json::Value = serde_json::from_str(&robot_text).unwrap();

    for _ in 0..320 {
        let dir = sandbox.case();
        let (what, bytes, names) = malformed_experiment(&mut rng);
        std::fs::write(dir.join("exp.toml"), &bytes).unwrap();
        let args = ["run", "exp.toml", "--threads", "1"];
        throw(
            &mut tallies,
            "experiment files",
            &dir,
            &args,
            format!("experiment: {what}"),
            &names,
        );
    }
    for _ in 0..120 {
        let dir = sandbox.case();
        let (what, bytes, names) = malformed_robot(&mut rng, &robot);
        std::fs::write(dir.join("r.robot.json"), &bytes).unwrap();
        let args = ["simulate", "--robot", "r.robot.json", "--duration", "0.1"];
        throw(
            &mut tallies,
            "robot files",
            &dir,
            &args,
            format!("robot file: {what}"),
            &names,
        );
    }
    let evogym = [
        "simulate",
        "--robot",
        "r.json",
        "--task",
        "evogym:walker",
        "--duration",
        "0.1",
    ];
    let dir = sandbox.case();
    std::fs::write(dir.join("r.json"), EVOGYM_ROBOT).unwrap();
    let (code, stderr, _) = run(&evogym, &dir);
    assert_eq!(code, Some(0), "the EvoGym robot file is valid: {stderr}");
    for _ in 0..60 {
        let dir = sandbox.case();
        let (what, bytes, names) = malformed_evogym_file(&mut rng);
        std::fs::write(dir.join("r.json"), &bytes).unwrap();
        throw(
            &mut tallies,
            "EvoGym world and robot files",
            &dir,
            &evogym,
            format!("EvoGym robot file: {what}"),
            &names,
        );
    }
    for _ in 0..120 {
        let dir = sandbox.case();
        std::fs::write(dir.join("exp.toml"), EXPERIMENT).unwrap();
        let (args, names) = malformed_command(&mut rng, &base.join("out"));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let what = format!("command: vsrlab {}", args.join(" "));
        throw(&mut tallies, "command lines", &dir, &args, what, &names);
    }
    let validate = ["validate", "--brief", "--threads", "1", "exp.toml"];
    for _ in 0..60 {
        let dir = sandbox.case();
        let (what, text, names) = malformed_psa(&mut rng);
        std::fs::write(dir.join("exp.toml"), text).unwrap();
        let args = ["run", "exp.toml", "--threads", "1"];
        throw(
            &mut tallies,
            "PSA bodies",
            &dir,
            &args,
            format!("experiment: {what}"),
            &names,
        );
    }
    for _ in 0..60 {
        let dir = sandbox.case();
        let (what, text, names) = malformed_sweep(&mut rng);
        std::fs::write(dir.join("exp.toml"), text).unwrap();
        throw(
            &mut tallies,
            "sweeps",
            &dir,
            &validate,
            format!("experiment: {what}"),
            &names,
        );
    }
    for _ in 0..40 {
        let dir = sandbox.case();
        let (what, text, names) = file_reading_experiment(&mut rng, &dir, &robot);
        std::fs::write(dir.join("exp.toml"), text).unwrap();
        let what = format!("experiment: {what}");
        throw(
            &mut tallies,
            "transfer and initial files",
            &dir,
            &validate,
            what,
            &names,
        );
    }
    tallies.insert(
        "viewer requests",
        fuzz_viewer(&mut rng, &mut sandbox, &base.join("out/fuzz"), 400),
    );

    let outside = sandbox.outside_writes();
    let mut report = String::new();
    let mut broken = Vec::new();
    for (kind, tally) in &tallies {
        report.push_str(&format!(
            "{kind}: {} cases, exit codes {:?}\n",
            tally.cases, tally.by_code
        ));
        broken.extend(tally.broken.iter().cloned());
    }
    eprintln!("{report}");
    let total: usize = tallies.values().map(|t| t.cases).sum();
    assert!(total >= 1000, "{total} cases");
    assert!(outside.is_empty(), "written outside the case folders: {outside:?}");
    assert!(
        broken.is_empty(),
        "{} of {total} cases broke a rule:\n\n{}",
        broken.len(),
        broken.join("\n\n")
    );
}
